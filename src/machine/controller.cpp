// The controller's threads and requests (docs/controller.md).
#include "gantry/machine/controller.hpp"

#include <fmt/format.h>  // messages

#include <cmath>  // llround

#include "gantry/machine/job.hpp"  // check_program

namespace gantry {

// Job thread -> feeder: pushes planned segments, waiting while the queue is full. Once the
// activity is aborted (stop, E-stop, fault) the next push throws, which unwinds the
// interpreter; later pushes are dropped (the run's own clean-up flushes).
class Controller::QueueSink : public SegmentSink {
 public:
  explicit QueueSink(Controller& c) : c_(c) {}
  void segment(const PlannedSegment& s) override { push({FeedItem::kSegment, s, nullptr}); }
  void flush() override { push({FeedItem::kFlush, {}, nullptr}); }
  void settings_changed(const Settings& s) override {
    push({FeedItem::kSettings, {}, std::make_shared<const Settings>(s)});
  }
  // The activity's last item, pushed whatever happened: once it is done the queue is empty.
  void fence() {
    dead_ = false;
    push({FeedItem::kFlush, {}, nullptr}, /*abortable=*/false);
  }

 private:
  void push(FeedItem&& item, bool abortable = true) {
    if (dead_) return;
    const bool flush = item.kind == FeedItem::kFlush;
    while (true) {
      if (abortable && c_.abort_.load(std::memory_order_acquire)) {
        dead_ = true;
        throw GantryError(Diagnostic{item.seg.loc, Severity::Error, "stopped"});
      }
      if (c_.queue_.try_push(std::move(item))) break;
      c_.queue_.wait_for_room();
    }
    if (flush) ++c_.flushes_pushed_;
    c_.wake_.fetch_add(1, std::memory_order_release);
    c_.wake_.notify_one();
  }
  Controller& c_;
  bool dead_ = false;
};

// The interpreter's sink: the planner of the current activity.
class Controller::ForwardSink : public MotionSink {
 public:
  MotionSink* to = nullptr;
  void move(const CanonMove& m) override { to->move(m); }
  void flush() override { to->flush(); }
  void settings_changed(const Settings& s) override { to->settings_changed(s); }
};

Controller::Controller(const Settings& settings, Card& card, OperatorIO& io, PersistentStore& store,
                       InterpreterOptions options)
    : settings_(settings),
      card_(card),
      io_(io),
      store_(store),
      steps_((card.start(settings.card.pacer_hz()), settings), card),
      feeder_(steps_),
      queue_(256),
      qsink_(std::make_unique<QueueSink>(*this)),
      forward_(std::make_unique<ForwardSink>()) {
  planner_ = std::make_unique<LookAheadPlanner>(settings, *qsink_);
  forward_->to = planner_.get();
  interp_ = std::make_unique<Interpreter>(settings, *forward_, io, store, std::move(options));
  feeder_thread_ = std::thread([this] { feeder_main(); });
  job_thread_ = std::thread([this] { job_main(); });
}

Controller::~Controller() {
  estop();  // whatever runs stops now
  {
    std::lock_guard lock(m_);
    quit_ = true;
  }
  cv_.notify_all();
  wake_.fetch_add(1);
  wake_.notify_all();
  job_thread_.join();
  wake_.fetch_add(1);
  wake_.notify_all();
  feeder_thread_.join();
}

// ---- requests ----------------------------------------------------------------------------

Outcome Controller::refuse_or(Request r, const std::function<void()>& accept) {
  std::unique_lock lock(m_);
  const Verdict v = decide(state_, r);
  if (!v.next) return {false, fmt::format("{}: refused, {}", request_name(r), v.refusal), {}};
  state_ = *v.next;
  accept();
  lock.unlock();
  cv_.notify_all();
  wake_.fetch_add(1, std::memory_order_release);
  wake_.notify_one();
  return {};
}

Outcome Controller::run(std::shared_ptr<const Script> script) {
  {
    std::lock_guard lock(m_);
    const Verdict v = decide(state_, Request::Run);
    if (!v.next || busy_) return {false, fmt::format("run: refused, {}", v.refusal), {}};
  }
  // The check runs from the live state: soft limits are checked for the whole file before
  // anything moves, with the offending line named.
  JobOptions check;
  const ModalState start = interp_->state();
  check.start_state = &start;
  std::vector<Diagnostic> errors;
  for (Diagnostic& d : check_program(script, interp_->settings(), store_, check, false))
    if (d.severity == Severity::Error) errors.push_back(std::move(d));
  if (!errors.empty()) return {false, "run: refused, the file has errors", std::move(errors)};
  return refuse_or(Request::Run, [&] {
    message_.clear();
    start_activity([this, script] {
      try {
        interp_->run(script);
      } catch (const GantryError& e) {
        std::lock_guard lock(m_);
        if (message_.empty() && !abort_) message_ = e.diagnostic().message;
        if (!abort_) stopped_at_ = e.diagnostic().loc;
        abort_ = true;
      }
    });
  });
}

Outcome Controller::pause() {
  return refuse_or(Request::Pause, [&] {
    on_hold_ = OnHold::Wait;
    feeder_.request_hold(0);
  });
}

Outcome Controller::resume() {
  return refuse_or(Request::Resume, [&] { cmd_resume_ = true; });
}

Outcome Controller::stop() {
  return refuse_or(Request::Stop, [&] {
    on_hold_ = OnHold::Discard;
    feeder_.request_hold(0);
    abort_ = true;
    message_ = "stopped by the operator";
  });
}

Outcome Controller::estop() {
  return refuse_or(Request::EStop, [&] {
    feeder_.request_halt(0);
    cmd_halt_ = true;
    abort_ = true;
    message_ = "E-stop";
  });
}

Outcome Controller::acknowledge() {
  {
    std::unique_lock lock(m_);
    cv_.wait(lock, [&] { return !busy_; });  // the aborted activity has wound down
  }
  Outcome o = refuse_or(Request::Acknowledge, [&] { cmd_acknowledge_ = true; });
  if (!o) return o;
  std::unique_lock lock(m_);
  cv_.wait(lock, [&] { return feeder_.phase() == FeedPhase::Playing; });
  interp_->set_machine_position(played_machine());
  message_.clear();
  return o;
}

Outcome Controller::jog(const JogRequest& j) {
  {
    std::lock_guard lock(m_);
    const Verdict v = decide(state_, Request::Jog);
    if (!v.next || busy_) return {false, fmt::format("jog: refused, {}", v.refusal), {}};
  }
  const CanonMove m = keypad_move(j);
  if (m.from == m.to) return {false, "jog: refused, the tool is at the soft limit that way", {}};
  return refuse_or(Request::Jog, [&] {
    message_.clear();
    start_activity([this, m] {
      LookAheadPlanner& p = *planner_;
      try {
        p.move(m);
        p.flush();
      } catch (const GantryError&) {  // stopped
      }
      std::lock_guard lock(m_);
      jog_target_ = m.to;
    });
  });
}

Outcome Controller::jog_release() {
  return refuse_or(Request::JogRelease, [&] {
    on_hold_ = OnHold::Discard;
    feeder_.request_hold(0);
  });
}

void Controller::schedule(Request r, double at_s) {
  std::lock_guard lock(m_);
  scheduled_.emplace_back(r, at_s);
}

void Controller::wait() {
  std::unique_lock lock(m_);
  cv_.wait(lock, [&] {
    const FeedPhase ph = feeder_.phase();
    return !busy_ || (state_ == MachineState::Paused && ph == FeedPhase::Held) ||
           (state_ == MachineState::EStop && ph == FeedPhase::Halted && !busy_);
  });
}

ControllerStatus Controller::status() const {
  ControllerStatus s;
  {
    std::lock_guard lock(m_);
    s.state = state_;
    s.message = message_;
    s.stopped_at = stopped_at_;
  }
  s.phase = feeder_.phase();
  for (int i = 0; i < kAxisCount; ++i) s.steps[i] = played_[i].load(std::memory_order_acquire);
  s.machine = played_machine(s.steps);
  return s;
}

// The played step counts in units (machine frame).
Vec6 Controller::played_machine(const Steps6& steps) const {
  Vec6 m = Vec6::Zero();
  for (int i = 0; i < kAxisCount; ++i)
    m[i] = static_cast<double>(steps[i]) / settings_.axes[i].steps_per_unit;
  return m;
}

Vec6 Controller::played_machine() const {
  Steps6 steps{};
  for (int i = 0; i < kAxisCount; ++i) steps[i] = played_[i].load(std::memory_order_acquire);
  return played_machine(steps);
}

MachineState Controller::state() const {
  std::lock_guard lock(m_);
  return state_;
}

ModalState Controller::modal() const {
  std::lock_guard lock(m_);
  return interp_->state();
}

// Continuous: along the direction to the first soft limit it meets (table base coordinates);
// a step: the keypad step on each axis that moves.
CanonMove Controller::keypad_move(const JogRequest& j) const {
  std::lock_guard lock(m_);
  const ModalState& st = interp_->state();
  const Settings& s = interp_->settings();
  const Vec6 origin = st.machine_origin;
  const Vec6 table = st.position + st.zero + st.applied_offset;  // table base now
  Vec6 d = Vec6::Zero();
  for (int i = 0; i < kAxisCount; ++i) d[i] = j.direction[i] > 0 ? 1 : j.direction[i] < 0 ? -1 : 0;
  Vec6 target = table;
  if (j.step) {
    target = table + d * s.display.keypad_step;
    for (int i = 0; i < kAxisCount; ++i)
      if (d[i] != 0 && s.machine.limit_checking &&
          (target[i] < s.axes[i].min - 1e-12 || target[i] > s.axes[i].max + 1e-12))
        target = table;  // the step would leave the table: no move
  } else if (d.norm() > 0) {
    const Vec6 unit = d / d.norm();
    double t = 1e3;  // no limit checking: far
    for (int i = 0; i < kAxisCount; ++i)
      if (unit[i] != 0 && s.machine.limit_checking)
        t = std::min(t, ((unit[i] > 0 ? s.axes[i].max : s.axes[i].min) - table[i]) / unit[i]);
    target = table + unit * std::max(0.0, t);
  }
  CanonMove m;
  m.from = table + origin;
  m.to = target + origin;
  m.speed_class = j.fast ? SpeedClass::Jog : SpeedClass::Move;
  m.speeds = j.fast ? st.speeds.jog : st.speeds.move;
  m.keypad = true;
  return m;
}

// ---- job thread --------------------------------------------------------------------------

void Controller::start_activity(std::function<void()> work) {
  // Called under m_ with the state changed already.
  busy_ = true;
  interrupted_ = false;
  jog_target_.reset();
  work_ = std::move(work);
  // Scheduled requests become ticks of this activity (the feeder is idle: tick_ is settled).
  const double hz = settings_.card.pacer_hz();
  for (const auto& [r, at] : scheduled_) {
    const std::int64_t tick = tick_.load() + std::llround(at * hz);
    switch (r) {
      case Request::Pause:
        on_hold_ = OnHold::Wait;
        effect_state_ = MachineState::Paused;
        feeder_.request_hold(tick);
        break;
      case Request::Stop:
        on_hold_ = OnHold::Discard;
        effect_state_ = MachineState::Stopping;
        feeder_.request_hold(tick);
        break;
      case Request::JogRelease:
        on_hold_ = OnHold::Discard;
        feeder_.request_hold(tick);
        break;
      case Request::EStop:
        feeder_.request_halt(tick);
        break;
      default:
        break;
    }
  }
  scheduled_.clear();
}

void Controller::job_main() {
  while (true) {
    std::function<void()> work;
    {
      std::unique_lock lock(m_);
      cv_.wait(lock, [&] { return quit_ || work_; });
      if (quit_) return;
      work.swap(work_);
    }
    planner_ = std::make_unique<LookAheadPlanner>(interp_->settings(), *qsink_);
    forward_->to = planner_.get();
    work();
    qsink_->fence();
    wait_for_motion();
    std::lock_guard lock(m_);
    // The queue is empty and the feeder idle: the activity's requests are spent.
    feeder_.request_hold(StepGenerator::kNever);
    on_hold_ = OnHold::Wait;
    cmd_resume_ = false;
    dropping_ = false;
    effect_state_.reset();
    const bool cut = interrupted_ || abort_;
    if (cut)
      interp_->set_machine_position(played_machine());  // where the pulses brought the tool
    else if (jog_target_)
      interp_->set_machine_position(*jog_target_);  // exact: fixed steps never drift
    abort_ = false;
    if (state_ != MachineState::EStop)
      state_ = state_ == MachineState::Jogging || (state_ == MachineState::Stopping && jog_target_)
                   ? MachineState::Idle
               : cut ? MachineState::Stopped
                     : MachineState::Idle;
    busy_ = false;
    cv_.notify_all();
  }
}

void Controller::wait_for_motion() {
  while (true) {
    const std::uint64_t done = flushes_done_.load(std::memory_order_acquire);
    if (done >= flushes_pushed_) return;
    flushes_done_.wait(done);
  }
}

// ---- feeder thread -----------------------------------------------------------------------

void Controller::feeder_main() {
  while (!quit_) {
    const unsigned seen = wake_.load(std::memory_order_acquire);
    if (cmd_halt_.exchange(false)) feeder_.halt_now();
    const FeedPhase ph = feeder_.phase();
    if (ph == FeedPhase::Held && on_hold_ == OnHold::Discard) {
      feeder_.discard();
      interrupted_ = true;
      dropping_ = true;
      on_hold_ = OnHold::Wait;
    } else if (ph == FeedPhase::Held && cmd_resume_.exchange(false)) {
      feeder_.resume();
    } else if (ph == FeedPhase::Halted && cmd_acknowledge_.exchange(false)) {
      feeder_.discard();  // the card starts again
    }
    if (feeder_.phase() != last_phase_) on_feeder_event();
    publish();
    FeedItem item;
    if (feeder_.phase() == FeedPhase::Held || !queue_.try_pop(item)) {
      wake_.wait(seen, std::memory_order_acquire);
      continue;
    }
    if (dropping_) {
      flushes_dropped_ += item.kind == FeedItem::kFlush;
    } else {
      try {
        feed(item);
      } catch (const GantryError& e) {  // the card faulted: it stopped by itself
        {
          std::lock_guard lock(m_);
          message_ = e.diagnostic().message;
          stopped_at_ = e.diagnostic().loc;
          if (card_.fault() == CardFault::EStop) state_ = MachineState::EStop;
        }
        interrupted_ = true;
        abort_ = true;
        dropping_ = true;
        flushes_dropped_ += item.kind == FeedItem::kFlush;
      }
    }
    if (feeder_.phase() != last_phase_) on_feeder_event();
    publish();
  }
}

void Controller::feed(FeedItem& item) {
  switch (item.kind) {
    case FeedItem::kSegment:
      feeder_.segment(item.seg);
      break;
    case FeedItem::kSettings:
      feeder_.settings_changed(*item.settings);
      break;
    case FeedItem::kFlush:
      feeder_.flush();
      break;
  }
}

void Controller::publish() {
  const Steps6 p = steps_.played_position();
  for (int i = 0; i < kAxisCount; ++i) played_[i].store(p[i], std::memory_order_release);
  tick_.store(steps_.tick(), std::memory_order_release);
  flushes_done_.store(feeder_.flushes_completed() + flushes_dropped_, std::memory_order_release);
  flushes_done_.notify_all();
}

void Controller::on_feeder_event() {
  last_phase_ = feeder_.phase();
  publish();
  {
    std::lock_guard lock(m_);
    if (last_phase_ == FeedPhase::Held || last_phase_ == FeedPhase::Halted)
      stopped_at_ = feeder_.rest_loc();
    if (last_phase_ == FeedPhase::Held && effect_state_) {
      state_ = *effect_state_;  // a scheduled pause or stop took effect
      if (state_ == MachineState::Stopping) {
        abort_ = true;
        message_ = "stopped by the operator";
      }
      effect_state_.reset();
    }
    if (last_phase_ == FeedPhase::Halted) {
      state_ = MachineState::EStop;
      interrupted_ = true;
      abort_ = true;
      if (message_.empty()) message_ = "E-stop";
    }
  }
  cv_.notify_all();
}

}  // namespace gantry
