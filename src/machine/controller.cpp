// The controller's threads and requests (docs/controller.md).
#include "gantry/machine/controller.hpp"

#include <fmt/format.h>  // messages

#include <bit>  // countr_zero

#include "gantry/core/bounded.hpp"  // checked_llround
#include "gantry/interp/program_check.hpp"  // check_program
#include "gantry/motion/cycle_timer.hpp"    // the estimate

namespace gantry {
namespace {

// VN output modes 2 and 5: the output switches an operator's pause turns off until resume.
std::uint32_t outputs_off_on_pause(const Settings& s) {
  std::uint32_t mask = 0;
  for (int n = 0; n < 12; ++n)
    if (s.switches.output_modes[n] == 2 || s.switches.output_modes[n] == 5) mask |= 1u << n;
  return mask;
}

// An input's name for the operator: its switch number, else its bit.
std::string input_name(const InputSettings& in, int bit) {
  for (int n = 1; n <= 12; ++n)
    if (in.switch_bits[n - 1] == bit) return fmt::format("input {}", n);
  return fmt::format("input bit {}", bit);
}

}  // namespace

// Job thread -> feeder: pushes planned segments, waiting while the queue is full. Once the
// activity is aborted (stop, E-stop, fault) the next push throws, which unwinds the
// interpreter; later pushes are dropped (the run's own clean-up flushes).
class Controller::QueueSink : public SegmentSink {
 public:
  explicit QueueSink(Controller& c) : c_(c) {}
  void segment(const PlannedSegment& s) override {
    push({FeedItem::kSegment, s, nullptr, nullptr});
  }
  void flush() override { push({FeedItem::kFlush, {}, nullptr, nullptr}); }
  void settings_changed(const Settings& s) override {
    push({FeedItem::kSettings, {}, std::make_shared<const Settings>(s), nullptr});
  }
  void watch(std::span<const InputTrigger> t) {
    push({FeedItem::kWatch,
          {},
          nullptr,
          std::make_shared<const std::vector<InputTrigger>>(t.begin(), t.end())},
         /*abortable=*/false);  // disarming is pushed as a run winds down
  }
  // The activity's last item, pushed whatever happened: once it is done the queue is empty.
  void fence() {
    dead_ = false;
    push({FeedItem::kFlush, {}, nullptr, nullptr}, /*abortable=*/false);
  }
  // After a stop: output switches 1-12 as `mask` says (bit n-1: switch n), then a fence.
  void outputs(std::uint32_t mask) {
    dead_ = false;
    for (int n = 1; n <= 12; ++n) {
      PlannedSegment seg;
      seg.output = n;  // one the profile does not wire switches nothing
      seg.output_on = (mask >> (n - 1) & 1u) != 0;
      push({FeedItem::kSegment, seg, nullptr, nullptr}, /*abortable=*/false);
    }
    fence();
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

// The interpreter's sink: the planner of the current activity; and its MachineLink, the
// live machine's answers (sync, inputs, keypad) for probes, ON INPUT and SK.
class Controller::ForwardSink : public MotionSink, public MachineLink {
 public:
  explicit ForwardSink(Controller& c) : c_(c) {}
  MotionSink* to = nullptr;
  void move(const CanonMove& m) override { to->move(m); }
  void flush() override { to->flush(); }
  void settings_changed(const Settings& s) override { to->settings_changed(s); }

  MotionReport sync() override {
    to->flush();
    c_.wait_for_motion();
    if (c_.abort_.load(std::memory_order_acquire))
      throw GantryError(Diagnostic{{}, Severity::Error, "stopped"});
    MotionReport r;
    r.machine = c_.played_machine();
    r.fired = std::exchange(c_.fired_, std::nullopt);  // the feeder is idle: its flush is done
    r.latched = c_.latched_;
    r.elapsed_s = c_.elapsed_s();
    return r;
  }
  void watch_inputs(std::span<const InputTrigger> t, Watching w) override {
    c_.qsink_->watch(t);
    std::lock_guard lock(c_.m_);
    if (c_.state_ == MachineState::Running || c_.state_ == MachineState::Homing ||
        c_.state_ == MachineState::Probing)
      c_.state_ = w == Watching::Probe  ? MachineState::Probing
                  : w == Watching::Home ? MachineState::Homing
                                        : MachineState::Running;
  }
  std::array<bool, 12> input_switches() const override {
    return c_.input_switches(c_.inputs_.load(std::memory_order_acquire));
  }
  MotionReport keypad(const SourceLoc&) override {
    sync();
    return c_.keypad_session();
  }

 private:
  Controller& c_;
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
      forward_(std::make_unique<ForwardSink>(*this)) {
  planner_ = std::make_unique<LookAheadPlanner>(settings, *qsink_);
  forward_->to = planner_.get();
  options.stop_check = &abort_;  // a stop ends even a file that loops without moving
  interp_ = std::make_unique<Interpreter>(settings, *forward_, forward_.get(), io, store,
                                         std::move(options));
  interp_->on_progress([this](std::size_t done, std::size_t total) {
    line_.store(done, std::memory_order_relaxed);
    lines_.store(total, std::memory_order_relaxed);
    if (progress_) progress_(done, total);  // set while idle only
    after_statement();
  });
  roles_ = input_roles(settings);
  stop_trip_ = roles_.stops;
  steps_.on_block([this] {
    publish();  // the readout moves during long segments
    watch_stop_switches();
  });
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

Outcome Controller::run(std::shared_ptr<const Script> script, bool checked,
                        double estimated_time_s) {
  return start_run(std::move(script), checked, estimated_time_s, false);
}

Outcome Controller::run_typed(std::shared_ptr<const Script> lines) {
  return start_run(std::move(lines), false, 0, true);
}

Outcome Controller::start_run(std::shared_ptr<const Script> script, bool checked,
                              double estimated_time_s, bool typed) {
  {
    std::lock_guard lock(m_);
    const Verdict v = decide(state_, Request::Run);
    if (!v.next || busy_) return {false, fmt::format("run: refused, {}", v.refusal), {}};
  }
  if (std::optional<std::string> why = input_refusal(Vec6::Zero()))
    return {false, fmt::format("run: refused, {}", *why), {}};
  // The check runs from the live state: soft limits are checked for the whole file before
  // anything moves, with the offending line named.
  JobOptions check;
  check.interpreter = interp_->options();  // the run's dialect, macros, warning (a dry run)
  const ModalState start = interp_->state();
  check.start_state = &start;
  const auto variables = interp_->variables();  // &X = 5 typed before: MX, &X checks
  check.start_variables = &variables;
  check.record = &interp_->recorder();  // RP, RR: the lines they would play are checked
  std::vector<Diagnostic> errors;
  double estimate = estimated_time_s;
  if (!checked) {
    CycleTimer timer(interp_->settings(), check.feed_override);
    check.check_moves = &timer;
    DiagnosticLog found = check_program(script, interp_->settings(), store_, check, false);
    estimate = timer.seconds();
    for (Diagnostic& d : found.kept())
      if (d.severity == Severity::Error) errors.push_back(std::move(d));
  }
  if (!errors.empty()) return {false, "run: refused, the file has errors", std::move(errors)};
  return refuse_or(Request::Run, [&] {
    message_.clear();
    estimate_s_ = estimate;
    line_ = 0;
    lines_ = script->line_count();
    running_file_ = true;
    typed_ = typed;
    start_activity([this, script, typed] {
      try {
        interp_->run(script, typed);
      } catch (const GantryError& e) {
        std::lock_guard lock(m_);
        if (message_.empty() && !abort_) message_ = e.diagnostic().message;
        // A stop that cut no motion (the file waited for the operator) names the line the
        // file had reached.
        if (!abort_ || !stopped_at_.file) stopped_at_ = e.diagnostic().loc;
        if (!error_)
          error_ = abort_ ? Diagnostic{stopped_at_, Severity::Error, message_} : e.diagnostic();
        abort_ = true;
      }
    });
  });
}

Outcome Controller::pause() {
  return pause(/*every_output=*/false);
}

Outcome Controller::pause(bool every_output) {
  return refuse_or(Request::Pause, [&] {
    on_hold_ = OnHold::Wait;
    feeder_.request_hold(0, /*pause=*/true, every_output);
  });
}

Outcome Controller::resume() {
  {
    std::lock_guard lock(m_);
    const std::string stops = active_stops(card_.inputs());
    if (!stops.empty() && decide(state_, Request::Resume).next)
      return {false, fmt::format("resume: refused, {} is active: release it first", stops), {}};
  }
  return refuse_or(Request::Resume, [&] {
    if (step_waiting_)
      step_waiting_ = false;  // single step: the next statement
    else if (keypad_open_)
      keypad_open_ = false;  // the file goes on once the last jog is at rest
    else
      cmd_resume_ = true;
    message_.clear();  // a stop switch's pause is over
  });
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
  ModalState st = interp_->state();  // the E-stop switched every output off (VN modes 1, 4 too)
  st.outputs = 0;
  interp_->restore_state(st);
  message_.clear();
  return o;
}

Outcome Controller::jog(const JogRequest& j) {
  {
    std::lock_guard lock(m_);
    const Verdict v = decide(state_, Request::Jog);
    const bool keypad = state_ == MachineState::Keypad;
    if (!v.next || (busy_ && !keypad))
      return {false, fmt::format("jog: refused, {}", v.refusal), {}};
    if (keypad && keypad_jogging_)
      return {false, "jog: refused, the last jog is still slowing to rest", {}};
  }
  const CanonMove m = keypad_move(j);
  if (m.from == m.to) return {false, "jog: refused, the tool is at the soft limit that way", {}};
  if (std::optional<std::string> why = input_refusal(m.to - m.from))
    return {false, fmt::format("jog: refused, {}", *why), {}};
  return refuse_or(Request::Jog, [&] {
    message_.clear();
    if (keypad_open_) {  // the job thread waits at SK: it plays the jog
      pending_jog_ = m;
      keypad_jogging_ = true;
      return;
    }
    running_file_ = false;
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
    if (keypad_open_) state_ = MachineState::Keypad;
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
           (state_ == MachineState::Paused && step_waiting_) ||
           (state_ == MachineState::Keypad && !keypad_jogging_) ||
           (state_ == MachineState::EStop && ph == FeedPhase::Halted && !busy_);
  });
}

Controller::Summary Controller::summary() const {
  std::lock_guard lock(m_);
  Summary s;
  s.error = error_;
  if (!s.error && !message_.empty()) s.error = Diagnostic{stopped_at_, Severity::Error, message_};
  s.fault = fault_;
  s.cut = interrupted_;
  s.lines = s.cut ? steps_.ran().statements : interp_->statements_executed();
  s.moves = s.cut ? steps_.ran().moves : interp_->moves_emitted();
  s.commanded = fault_ == CardFault::None ? steps_.position() : fault_commanded_;
  s.planned_time_s = planner_->planned_time();
  return s;
}

void Controller::set_feed_override(double factor) {
  std::lock_guard lock(m_);
  feed_override_ = factor;
  override_changed_ = true;
}

void Controller::set_single_step(bool on) {
  single_step_ = on;
}

void Controller::on_progress(std::function<void(std::size_t, std::size_t)> f) {
  std::lock_guard lock(m_);
  progress_ = std::move(f);
}

ControllerStatus Controller::status() const {
  ControllerStatus s;
  {
    std::lock_guard lock(m_);
    s.state = state_;
    s.message = message_;
    s.stopped_at = stopped_at_;
    s.step_hold = step_waiting_;
    s.warning = busy_ && warning_.load(std::memory_order_relaxed);
  }
  s.phase = feeder_.phase();
  s.line = line_.load(std::memory_order_relaxed);
  s.lines = lines_.load(std::memory_order_relaxed);
  s.playing_line = playing_line_.load(std::memory_order_relaxed);
  s.elapsed_s = elapsed_s();
  {
    std::lock_guard lock(m_);
    s.remaining_s = std::max(0.0, estimate_s_ - s.elapsed_s);
  }
  s.inputs = input_switches(inputs_.load(std::memory_order_acquire));
  for (int i = 0; i < kAxisCount; ++i) s.steps[i] = played_[i].load(std::memory_order_acquire);
  s.machine = played_machine(s.steps);
  return s;
}

double Controller::elapsed_s() const {
  std::lock_guard lock(m_);
  return static_cast<double>(tick_.load() - start_tick_) / settings_.card.pacer_hz();
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

// After each statement of a file. A new feed override goes to the planner (it re-plans what
// it holds). Single step: the statement's motion plays out, then the file holds as Paused
// until resume (the next statement) or stop.
void Controller::after_statement() {
  feeder_.pause_outputs(outputs_off_on_pause(interp_->settings()));  // VN may change them
  if (override_changed_.exchange(false)) {
    std::lock_guard lock(m_);
    planner_->feed_override(feed_override_);
  }
  if (!single_step_ || !running_file_) return;
  forward_->sync();
  std::unique_lock lock(m_);
  if (state_ != MachineState::Running) return;  // homing, probing, at SK: not a step
  state_ = MachineState::Paused;
  step_waiting_ = true;
  cv_.notify_all();
  cv_.wait(lock, [&] { return !step_waiting_ || abort_ || quit_; });
  step_waiting_ = false;
  if (abort_ || quit_) throw GantryError(Diagnostic{{}, Severity::Error, "stopped"});
}

// SK, with the file's motion played out: the operator's jogs play here, one at a time, as
// an activity's would, until resume closes the keypad (the last jog at rest first) or a
// stop or E-stop ends the file.
MotionReport Controller::keypad_session() {
  std::unique_lock lock(m_);
  keypad_open_ = true;
  state_ = MachineState::Keypad;
  cv_.notify_all();
  while (true) {
    cv_.wait(lock, [&] { return pending_jog_ || !keypad_open_ || abort_ || quit_; });
    if (abort_ || quit_ || (!keypad_open_ && !pending_jog_)) break;
    const CanonMove m = *std::exchange(pending_jog_, std::nullopt);
    lock.unlock();
    bool stopped = false;
    try {
      planner_->move(m);
      planner_->flush();
    } catch (const GantryError&) {  // a stop or E-stop: the file ends
      stopped = true;
    }
    wait_for_motion();
    lock.lock();
    if (stopped || abort_) break;
    // At rest, the jog's requests spent (as at the end of an activity).
    feeder_.request_hold(StepGenerator::kNever);
    on_hold_ = OnHold::Wait;
    dropping_ = false;
    interp_->set_machine_position(interrupted_ ? played_machine() : m.to);  // as for a jog
    interrupted_ = false;
    keypad_jogging_ = false;
    if (state_ == MachineState::Jogging) state_ = MachineState::Keypad;
    cv_.notify_all();
  }
  keypad_open_ = false;
  keypad_jogging_ = false;
  pending_jog_.reset();
  if (abort_) throw GantryError(Diagnostic{{}, Severity::Error, "stopped"});
  MotionReport r;  // where the jogs left the tool, exactly (a step ends on its point)
  const ModalState& st = interp_->state();
  r.machine = st.position + st.machine_origin + st.zero + st.applied_offset;
  return r;
}

void Controller::start_activity(std::function<void()> work) {
  // Called under m_ with the state changed already.
  busy_ = true;
  interrupted_ = false;
  jog_target_.reset();
  error_.reset();
  fault_ = CardFault::None;
  steps_.new_run();
  start_tick_ = tick_.load();
  work_ = std::move(work);
  // Scheduled requests become ticks of this activity (the feeder is idle: tick_ is settled).
  const double hz = settings_.card.pacer_hz();
  for (const auto& [r, at] : scheduled_) {
    const std::int64_t tick =
        tick_.load() + checked_llround(at * hz).value_or(StepGenerator::kNever / 2);
    switch (r) {
      case Request::Pause:
        on_hold_ = OnHold::Wait;
        effect_state_ = MachineState::Paused;
        feeder_.request_hold(tick, /*pause=*/true);
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
    feeder_.pause_outputs(outputs_off_on_pause(interp_->settings()));
    planner_->feed_override(feed_override_);
    forward_->to = planner_.get();
    work();
    qsink_->fence();
    wait_for_motion();
    if (running_file_ && (interrupted_ || abort_)) {
      // The stop dropped the file's last switchings with the rest of its motion stream: the
      // card's outputs become what the file's end left (after an E-stop the card plays
      // nothing until acknowledged, which switches everything off).
      dropping_ = false;  // the queue is empty: what was cut is gone
      qsink_->outputs(interp_->state().outputs);
      wait_for_motion();
    }
    std::lock_guard lock(m_);
    // The queue is empty and the feeder idle: the activity's requests are spent.
    feeder_.request_hold(StepGenerator::kNever);
    on_hold_ = OnHold::Wait;
    cmd_resume_ = false;
    dropping_ = false;
    effect_state_.reset();
    const bool cut = interrupted_ || abort_;
    const bool jogged = jog_target_.has_value();
    if (cut && stopped_at_.file)  // FG resumes where a file stopped short
      interp_->set_last_stop(stopped_at_);
    else if (running_file_ && !typed_)  // a part file ran to its end
      interp_->set_last_stop({});
    if (cut)
      interp_->set_machine_position(played_machine());  // where the pulses brought the tool
    else if (jog_target_)
      interp_->set_machine_position(*jog_target_);  // exact: fixed steps never drift
    abort_ = false;
    if (state_ != MachineState::EStop)
      state_ = jogged || state_ == MachineState::Jogging ? MachineState::Idle  // released too
               : cut                                     ? MachineState::Stopped
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
    } else if (drop_to_flush_ && item.kind != FeedItem::kSettings) {
      // The rest of the statement an input edge cut; what follows its flush plays.
      if (item.kind == FeedItem::kFlush) {
        ++flushes_dropped_;
        drop_to_flush_ = false;
      } else if (item.kind == FeedItem::kWatch) {
        feed(item);
      }
    } else {
      try {
        feed(item);
        if (input_cut_) finish_input_cut(item.kind == FeedItem::kFlush);
      } catch (const GantryError& e) {  // the card faulted: it stopped by itself
        const CardFault fault = card_.fault();
        {
          std::lock_guard lock(m_);
          message_ = e.diagnostic().message;
          if (fault == CardFault::Limit) message_ = active_limits(card_.inputs()) + ": " + message_;
          stopped_at_ = e.diagnostic().loc;
          fault_ = fault;
          fault_commanded_ = steps_.position();  // before the card starts again
          error_ = Diagnostic{stopped_at_, Severity::Error, message_};
          if (fault == CardFault::EStop) state_ = MachineState::EStop;
        }
        interrupted_ = true;
        abort_ = true;
        dropping_ = true;
        flushes_dropped_ += item.kind == FeedItem::kFlush;
        if (fault != CardFault::EStop) {  // the card starts again: the tool can move off it
          feeder_.halt_now();
          feeder_.discard();
          last_phase_ = FeedPhase::Playing;
        }
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
    case FeedItem::kSettings: {
      feeder_.settings_changed(*item.settings);
      const InputRoles roles = input_roles(*item.settings);  // VN: at rest, not real-time
      stop_trip_ = roles.stops;
      std::lock_guard lock(m_);
      roles_ = roles;
      break;
    }
    case FeedItem::kFlush:
      feeder_.flush();
      if (feeder_.phase() == FeedPhase::Playing) {  // a real card still plays its queue
        card_.drain();
        steps_.check_card();  // a fault in the last words
      }
      break;
    case FeedItem::kWatch:
      arm_watch(item.triggers);
      break;
  }
}

// ---- input edges (ON INPUT, probes, homing) ------------------------------------------------

void Controller::arm_watch(std::shared_ptr<const std::vector<InputTrigger>> triggers) {
  watched_ = std::move(triggers);  // shared: nothing allocated here
  InputWatch w;
  for (const InputTrigger& t : *watched_) {
    const int bit = settings_.inputs.switch_bits[t.input - 1];
    if (bit < 0) continue;  // the interpreter has said it never fires
    w.mask |= 1u << bit;
    if (t.closing) w.levels |= 1u << bit;
    if (t.instant) w.stop |= 1u << bit;
  }
  fired_.reset();
  steps_.watch_inputs(w, [this](const InputEdge& e) { on_input_edge(e); });
}

// Inside the step generator, right after the block in which the card saw the edge: the tool
// was where the words before the edge's tick left it; the motion is cut there (instant) or
// ramps down from the next word on.
void Controller::on_input_edge(const InputEdge& e) {
  const bool closed = (e.bits >> e.bit & 1u) != 0;
  for (const InputTrigger& t : *watched_)
    if (settings_.inputs.switch_bits[t.input - 1] == e.bit && t.closing == closed) fired_ = t;
  if (!fired_) return;
  const std::optional<Steps6> at = steps_.position_at(e.tick);
  latched_ = played_machine(at ? *at : steps_.played_position());
  input_cut_ = true;
  if (fired_->instant)
    feeder_.request_halt(0);
  else
    feeder_.request_hold(0);
}

// After each item while an edge's cut is under way. At rest, what the cut left of the
// statement's motion is dropped (up to its flush); still slowing, it goes on.
void Controller::finish_input_cut(bool consumed_flush) {
  const FeedPhase ph = feeder_.phase();
  if (ph == FeedPhase::Playing && consumed_flush) {
    // The edge came in the statement's last words: the motion ended before the cut.
    if (fired_->instant) {
      feeder_.halt_now();
      feeder_.discard();
    }
    feeder_.request_hold(StepGenerator::kNever);
    feeder_.request_halt(StepGenerator::kNever);
    input_cut_ = false;
  } else if (ph == FeedPhase::Held || ph == FeedPhase::Halted) {
    drop_to_flush_ = !(ph == FeedPhase::Held && feeder_.flush_kept());
    feeder_.discard();
    input_cut_ = false;
  }
}

std::array<bool, 12> Controller::input_switches(std::uint32_t bits) const {
  std::array<bool, 12> out{};
  for (int n = 0; n < 12; ++n) {
    const int bit = settings_.inputs.switch_bits[n];
    out[n] = bit >= 0 && (bits >> bit & 1u) != 0;
  }
  return out;
}

std::string Controller::active_limits(std::uint32_t bits) const {
  const InputSettings& in = settings_.inputs;
  std::uint32_t active = roles_.limits.active(bits);
  std::string out;
  auto add = [&](const std::string& what) { out += (out.empty() ? "" : ", ") + what; };
  for (int i = 0; i < kAxisCount; ++i)
    for (const auto& [bit, side] : {std::pair{in.min_bit[i], "low"}, {in.max_bit[i], "high"}})
      if (bit >= 0 && (active >> bit & 1u)) {
        add(fmt::format("{} {} limit switch (input bit {})",
                        static_cast<char>(kAxisLetters[i] - 'a' + 'A'), side, bit));
        active &= ~(1u << bit);
      }
  for (; active; active &= active - 1)  // VN's limit inputs: no axis of their own
    add(fmt::format("the limit switch on {}", input_name(in, std::countr_zero(active))));
  return out.empty() ? "a limit switch" : out;
}

std::string Controller::active_stops(std::uint32_t bits) const {
  std::string out;
  for (std::uint32_t active = roles_.stops.active(bits); active; active &= active - 1)
    out += fmt::format("{}the stop switch on {}", out.empty() ? "" : ", ",
                       input_name(settings_.inputs, std::countr_zero(active)));
  return out;
}

// With a direction (a jog): refused only towards an active limit switch of an axis; a limit
// input of no axis lets the keypad jog (SB3's override: press the key again). Without (a
// run): refused while any is active. An active stop switch refuses everything.
std::optional<std::string> Controller::input_refusal(const Vec6& direction) const {
  const InputSettings& in = settings_.inputs;
  const std::uint32_t bits = card_.inputs();  // now: a switch may change at rest
  std::lock_guard lock(m_);
  if (const std::string stops = active_stops(bits); !stops.empty())
    return fmt::format("{} is active: release it first", stops);
  auto active = [&](int bit) { return bit >= 0 && (roles_.limits.active(bits) >> bit & 1u); };
  const bool any_way = direction.isZero();
  for (int i = 0; i < kAxisCount; ++i) {
    const char L = static_cast<char>(kAxisLetters[i] - 'a' + 'A');
    if (active(in.min_bit[i]) && (any_way || direction[i] < 0))
      return fmt::format(
          "the {} low limit switch is closed: {}", L,
          any_way ? "jog off it with the keypad first" : fmt::format("jog away from it (+{})", L));
    if (active(in.max_bit[i]) && (any_way || direction[i] > 0))
      return fmt::format(
          "the {} high limit switch is closed: {}", L,
          any_way ? "jog off it with the keypad first" : fmt::format("jog away from it (-{})", L));
  }
  if (any_way && roles_.limits.tripped(bits))
    return fmt::format("{} is active: jog off it with the keypad first", active_limits(bits));
  return std::nullopt;
}

// SB3's remote stop: like the space bar, a ramped stop along the path that can be resumed,
// and the spindle stops (every output switch goes off at rest, on again at resume). Nothing
// moves again while the switch is active. Seen after the block in which the card read it.
void Controller::watch_stop_switches() {
  const std::uint32_t bits = card_.inputs();
  const bool active = stop_trip_.tripped(bits);
  const bool pressed = active && !stop_active_;
  stop_active_ = active;
  if (!pressed) return;
  const bool jogging = state() == MachineState::Jogging;
  // A jog ends as if the key were let go; anything else at rest refuses the pause.
  if (!(jogging ? jog_release() : pause(/*every_output=*/true))) return;
  std::lock_guard lock(m_);
  const std::string stops = active_stops(bits);
  message_ = jogging ? stops + " stopped the jog"
                     : fmt::format("{} paused the file: release it, then resume", stops);
}

void Controller::publish() {
  const Steps6 p = steps_.played_position();
  for (int i = 0; i < kAxisCount; ++i) played_[i].store(p[i], std::memory_order_release);
  tick_.store(steps_.tick(), std::memory_order_release);
  inputs_.store(card_.inputs(), std::memory_order_release);
  playing_line_.store(steps_.loc().line, std::memory_order_relaxed);
  warning_.store(steps_.warning() && feeder_.phase() == FeedPhase::Playing,
                 std::memory_order_relaxed);
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
