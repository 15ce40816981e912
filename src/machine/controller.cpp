// The controller's threads and requests (docs/controller.md).
#include "gantry/machine/controller.hpp"

#include <fmt/format.h>  // messages

#include <algorithm>  // clamp
#include <bit>        // countr_zero

#include "gantry/core/bounded.hpp"          // checked_llround
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

// The interpreter's sink: the planner of the current activity; and its MachineLink, the
// live machine's answers (sync, inputs, keypad) for probes, ON INPUT and SK.
class Controller::ForwardSink : public MotionSink, public MachineLink {
 public:
  explicit ForwardSink(Controller& c) : c_(c) {}
  MotionSink* to = nullptr;
  void move(const CanonMove& m) override {
    const std::shared_ptr<const std::string>& top = c_.top_file_;  // set before the job began
    if (!m.loc.file || !top || m.loc.file == top || *m.loc.file == *top) return to->move(m);
    CanonMove called = m;  // line_ is the calling line while a called file is read
    called.loc.caller_line = static_cast<int>(c_.line_.load(std::memory_order_relaxed));
    to->move(called);
  }
  void flush() override { to->flush(); }
  void settings_changed(const Settings& s) override { to->settings_changed(s); }

  MotionReport sync() override {
    to->flush();
    c_.wait_for_motion();
    if (c_.feed_.aborted()) throw GantryError(Diagnostic{{}, Severity::Error, "stopped"});
    MotionReport r;
    r.machine = c_.played_machine();
    r.fired = c_.feed_.take_fired();  // the feeder is idle: its flush is done
    r.latched = c_.feed_.latched();
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
    return c_.input_switches(c_.feed_.inputs());
  }
  MotionReport keypad(const SourceLoc&) override {
    sync();
    return c_.keypad_session();
  }
  std::uint32_t axes_to_home() const override {
    return c_.must_home_.load(std::memory_order_acquire);
  }
  void homed(int axis) override {
    c_.must_home_.fetch_and(~(1u << axis), std::memory_order_acq_rel);
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
      feed_(settings_, card, input_roles(settings).stops, *this),
      qsink_(&feed_.sink()),
      forward_(std::make_unique<ForwardSink>(*this)) {
  forward_->to = qsink_;  // the planner runs on the feeder thread (feeder_thread.hpp)
  options.stop_check = &feed_.abort_flag();  // a stop ends even a file that loops without moving
  options.fm_hot_key = [this] { return hot_key_.exchange(0); };
  interp_ = std::make_unique<Interpreter>(settings, *forward_, forward_.get(), io, store,
                                          std::move(options));
  interp_->on_progress([this](std::size_t done, std::size_t total) {
    line_.store(done, std::memory_order_relaxed);
    lines_.store(total, std::memory_order_relaxed);
    if (progress_) progress_(done, total);  // set while idle only
    after_statement();
  });
  roles_ = input_roles(settings);
  feed_.start();
  job_thread_ = std::thread([this] { job_main(); });
}

Controller::~Controller() {
  estop();  // whatever runs stops now
  {
    std::lock_guard lock(m_);
    quit_ = true;
    feed_.quit();
  }
  cv_.notify_all();
  feed_.wake();
  job_thread_.join();
  feed_.join();
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
  feed_.wake();
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
    hot_key_.store(0);  // a key pressed before the run is not the run's
    activity_file_ = script->name() ? *script->name() : std::string();
    top_file_ = typed ? nullptr : script->name();
    start_activity([this, script, typed] {
      try {
        interp_->run(script, typed);
      } catch (const GantryError& e) {
        std::lock_guard lock(m_);
        if (message_.empty() && !feed_.aborted()) message_ = e.diagnostic().message;
        // A stop that cut no motion (the file waited for the operator) names the line the
        // file had reached.
        if (!feed_.aborted() || !stopped_at_.file) stopped_at_ = e.diagnostic().loc;
        if (!error_)
          error_ =
              feed_.aborted() ? Diagnostic{stopped_at_, Severity::Error, message_} : e.diagnostic();
        feed_.abort();
      }
    });
  });
}

Outcome Controller::pause() {
  return pause(/*every_output=*/false);
}

Outcome Controller::pause(bool every_output) {
  return refuse_or(Request::Pause,
                   [&] { feed_.hold(0, /*discard=*/false, /*pause=*/true, every_output); });
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
      feed_.request_resume();
    message_.clear();  // a stop switch's pause is over
  });
}

Outcome Controller::stop() {
  return refuse_or(Request::Stop, [&] {
    feed_.request_stop();
    message_ = "stopped by the operator";
  });
}

Outcome Controller::estop() {
  return refuse_or(Request::EStop, [&] {
    // Stopped mid-motion: the axes the profile names must be homed again (homing.require).
    if (state_ == MachineState::Running || state_ == MachineState::Jogging ||
        state_ == MachineState::Homing || state_ == MachineState::Probing ||
        state_ == MachineState::Stopping)
      must_home_.fetch_or(settings_.homing.require, std::memory_order_acq_rel);
    feed_.request_estop();
    message_ = "E-stop";
  });
}

Outcome Controller::acknowledge() {
  {
    std::unique_lock lock(m_);
    cv_.wait(lock, [&] { return !busy_; });  // the aborted activity has wound down
  }
  Outcome o = refuse_or(Request::Acknowledge, [&] { feed_.request_acknowledge(); });
  if (!o) return o;
  std::unique_lock lock(m_);
  cv_.wait(lock, [&] { return feed_.phase() == FeedPhase::Playing; });
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
      try {
        qsink_->move(m);
        qsink_->flush();
      } catch (const GantryError&) {  // stopped
      }
      std::lock_guard lock(m_);
      jog_target_ = m.to;
    });
  });
}

Outcome Controller::jog_release() {
  return refuse_or(Request::JogRelease, [&] {
    feed_.hold(0, /*discard=*/true);
    if (keypad_open_) state_ = MachineState::Keypad;
  });
}

void Controller::schedule(Request r, double at_s) {
  std::lock_guard lock(m_);
  scheduled_.emplace_back(r, at_s);
}

bool Controller::settled() const {
  const FeedPhase ph = feed_.phase();
  return !busy_ || (state_ == MachineState::Paused && ph == FeedPhase::Held) ||
         (state_ == MachineState::Paused && step_waiting_) ||
         (state_ == MachineState::Keypad && !keypad_jogging_) ||
         (state_ == MachineState::EStop && ph == FeedPhase::Halted && !busy_);
}

void Controller::wait() {
  std::unique_lock lock(m_);
  cv_.wait(lock, [&] { return settled(); });
}

bool Controller::wait_for(std::chrono::milliseconds timeout) {
  std::unique_lock lock(m_);
  return cv_.wait_for(lock, timeout, [&] { return settled(); });
}

Controller::Summary Controller::summary() const {
  std::lock_guard lock(m_);
  Summary s;
  s.error = error_;
  if (!s.error && !message_.empty()) s.error = Diagnostic{stopped_at_, Severity::Error, message_};
  s.fault = fault_;
  s.cut = feed_.interrupted();
  s.lines = s.cut ? feed_.steps().ran().statements : interp_->statements_executed();
  s.moves = s.cut ? feed_.steps().ran().moves : interp_->moves_emitted();
  s.commanded = fault_ == CardFault::None ? feed_.steps().position() : fault_commanded_;
  s.planned_time_s = feed_.planned_time();
  s.lead = feed_.steps().lead().stats();
  s.lead_s = feed_.steps().lead().lead_s();
  s.starved_releases = feed_.starved_releases();
  s.feeder_realtime = feed_.realtime();
  return s;
}

void Controller::set_feed_override(double factor) {
  // Within the profile's [feed_override] bounds, whichever front end asks (the front ends
  // step within them too, so what they show is what runs).
  factor =
      std::clamp(factor, settings_.feed_override.min / 100.0, settings_.feed_override.max / 100.0);
  std::lock_guard lock(m_);
  feed_override_ = factor;
  // On a card that queues words it acts at once (the feeder re-plans and re-ramps what is not
  // yet generated); in virtual time after the statement running, in order with the moves, so
  // that a run is the same every time.
  if (card_.queues_words())
    feed_.live_override(factor);
  else
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
    s.file = top_file_;
    s.step_hold = step_waiting_;
    s.warning = busy_ && feed_.warning();
    s.settled = settled();
    s.activities_ended = activities_ended_;
  }
  s.phase = feed_.phase();
  s.line = line_.load(std::memory_order_relaxed);
  s.lines = lines_.load(std::memory_order_relaxed);
  s.playing_line = feed_.playing_line();
  s.playing_file = feed_.playing_file();
  s.playing_caller_line = feed_.playing_caller_line();
  const OutputLevels out = feed_.outputs();
  s.outputs = out.switches;
  s.spindle_rpm = out.spindle_rpm;
  s.elapsed_s = elapsed_s();
  {
    std::lock_guard lock(m_);
    s.remaining_s = std::max(0.0, estimate_s_ - s.elapsed_s);
    s.feed_override = feed_override_;
  }
  s.inputs = input_switches(feed_.inputs());
  s.steps = feed_.played();
  s.machine = played_machine(s.steps);
  return s;
}

double Controller::elapsed_s() const {
  std::lock_guard lock(m_);
  return static_cast<double>(feed_.tick() - start_tick_) / settings_.card.pacer_hz();
}

// The played step counts in units (machine frame).
Vec6 Controller::played_machine(const Steps6& steps) const {
  return steps_to_machine(settings_, steps);
}

Vec6 Controller::played_machine() const {
  return played_machine(feed_.played());
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
    target = table + d * (j.step_size > 0 ? j.step_size : s.display.keypad_step);
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
  if (j.speed_fraction > 0 && j.speed_fraction < 1)
    for (double* v : {&m.speeds.xy, &m.speeds.z, &m.speeds.a, &m.speeds.b, &m.speeds.c})
      *v *= j.speed_fraction;
  m.keypad = true;
  return m;
}

// ---- job thread --------------------------------------------------------------------------

// After each statement of a file. A new feed override goes to the planner (it re-plans what
// it holds). Single step: the statement's motion plays out, then the file holds as Paused
// until resume (the next statement) or stop.
Outcome Controller::hot_key(int key) {
  if (key < 1 || key > 10)
    return {false, fmt::format("Alt-F{}: the hot keys are Alt-F1 to Alt-F10", key), {}};
  std::lock_guard lock(m_);
  if (!busy_ || !running_file_)
    return {false,
            fmt::format("Alt-F{} calls subroutine N{} of the Friendly Motion program running, "
                        "and no program runs",
                        key, 10000 + key),
            {}};
  hot_key_.store(key);
  return {};
}

void Controller::after_statement() {
  feed_.pause_outputs(outputs_off_on_pause(interp_->settings()));  // VN may change them
  // A hot key only a Friendly Motion line takes: in another language it is told, not kept.
  if (hot_key_.load() != 0 && !interp_->in_friendly_motion())
    if (const int key = hot_key_.exchange(0); key != 0)
      io_.warn({{},
                Severity::Warning,
                fmt::format("Alt-F{} calls subroutine N{} of a Friendly Motion program; the "
                            "file running is not one, so nothing was called",
                            key, 10000 + key)});
  if (override_changed_.exchange(false)) {
    double factor = 1;
    {
      std::lock_guard lock(m_);
      factor = feed_override_;
    }
    qsink_->feed_override(factor);
  }
  if (!single_step_ || !running_file_) return;
  forward_->sync();
  std::unique_lock lock(m_);
  if (state_ != MachineState::Running) return;  // homing, probing, at SK: not a step
  state_ = MachineState::Paused;
  step_waiting_ = true;
  cv_.notify_all();
  cv_.wait(lock, [&] { return !step_waiting_ || feed_.aborted() || quit_; });
  step_waiting_ = false;
  if (feed_.aborted() || quit_) throw GantryError(Diagnostic{{}, Severity::Error, "stopped"});
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
    cv_.wait(lock, [&] { return pending_jog_ || !keypad_open_ || feed_.aborted() || quit_; });
    if (feed_.aborted() || quit_ || (!keypad_open_ && !pending_jog_)) break;
    const CanonMove m = *std::exchange(pending_jog_, std::nullopt);
    lock.unlock();
    bool stopped = false;
    try {
      qsink_->move(m);
      qsink_->flush();
    } catch (const GantryError&) {  // a stop or E-stop: the file ends
      stopped = true;
    }
    wait_for_motion();
    lock.lock();
    if (stopped || feed_.aborted()) break;
    // At rest, the jog's requests spent (as at the end of an activity).
    const bool cut = feed_.spent_jog();
    interp_->set_machine_position(cut ? played_machine() : m.to);  // as for a jog
    keypad_jogging_ = false;
    if (state_ == MachineState::Jogging) state_ = MachineState::Keypad;
    cv_.notify_all();
  }
  keypad_open_ = false;
  keypad_jogging_ = false;
  pending_jog_.reset();
  if (feed_.aborted()) throw GantryError(Diagnostic{{}, Severity::Error, "stopped"});
  MotionReport r;  // where the jogs left the tool, exactly (a step ends on its point)
  const ModalState& st = interp_->state();
  r.machine = st.position + st.machine_origin + st.zero + st.applied_offset;
  return r;
}

void Controller::start_activity(std::function<void()> work) {
  // Called under m_ with the state changed already.
  busy_ = true;
  // A stop request belongs to the activity it stops; one made at rest (an E-stop) had none
  // to end, and would stop this one before it began.
  feed_.clear_abort();
  feed_.new_activity();  // nothing cut yet; the step generator counts anew
  jog_target_.reset();
  error_.reset();
  fault_ = CardFault::None;
  start_tick_ = feed_.tick();
  work_ = std::move(work);
  // Scheduled requests become ticks of this activity (the feeder is idle: tick_ is settled).
  const double hz = settings_.card.pacer_hz();
  for (const auto& [r, at] : scheduled_) {
    const std::int64_t tick =
        feed_.tick() + checked_llround(at * hz).value_or(StepGenerator::kNever / 2);
    switch (r) {
      case Request::Pause:
        effect_state_ = MachineState::Paused;
        feed_.hold(tick, /*discard=*/false, /*pause=*/true);
        break;
      case Request::Stop:
        effect_state_ = MachineState::Stopping;
        feed_.hold(tick, /*discard=*/true);
        break;
      case Request::JogRelease:
        feed_.hold(tick, /*discard=*/true);
        break;
      case Request::EStop:
        feed_.halt(tick);
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
    feed_.pause_outputs(outputs_off_on_pause(interp_->settings()));
    {
      double factor = 1;
      {
        std::lock_guard lock(m_);
        factor = feed_override_;
      }
      qsink_->new_plan(interp_->settings(), factor);  // the planner, on the feeder thread
    }
    forward_->to = qsink_;
    if (activity_) activity_(activity(false));  // before any motion
    work();
    qsink_->fence();
    wait_for_motion();
    if (running_file_ && (feed_.interrupted() || feed_.aborted())) {
      // The stop dropped the file's last switchings with the rest of its motion stream: the
      // card's outputs become what the file's end left (after an E-stop the card plays
      // nothing until acknowledged, which switches everything off).
      feed_.queue_emptied();  // the queue is empty: what was cut is gone
      qsink_->outputs(interp_->state().outputs);
      wait_for_motion();
    }
    std::unique_lock lock(m_);
    // The queue is empty and the feeder idle: the activity's requests are spent.
    feed_.end_activity();
    effect_state_.reset();
    const bool cut = feed_.interrupted() || feed_.aborted();
    const bool jogged = jog_target_.has_value();
    if (cut && stopped_at_.file)  // FG resumes where a file stopped short
      interp_->set_last_stop(stopped_at_);
    else if (running_file_ && !typed_)  // a part file ran to its end
      interp_->set_last_stop({});
    if (cut) {
      interp_->set_machine_position(played_machine());  // where the pulses brought the tool
      if (fault_ != CardFault::None) say_where_the_card_stopped();
    } else if (jog_target_)
      interp_->set_machine_position(*jog_target_);  // exact: fixed steps never drift
    feed_.clear_abort();
    if (state_ != MachineState::EStop)
      state_ = jogged || state_ == MachineState::Jogging ? MachineState::Idle  // released too
               : cut                                     ? MachineState::Stopped
                                                         : MachineState::Idle;
    if (activity_) {  // told outside m_ (a save takes a while), before wait() returns
      const Activity ended = activity(true);
      const std::function<void(const Activity&)> told = activity_;
      lock.unlock();
      told(ended);
      lock.lock();
    }
    busy_ = false;
    ++activities_ended_;
    cv_.notify_all();
  }
}

// Job thread, the position settled: a card fault's message ends with where the tool is, in
// the coordinates the readout and the file use (the card's own count differs by the origin
// a restored session, a home or a zero set).
void Controller::say_where_the_card_stopped() {
  const ModalState& st = interp_->state();
  std::string where;
  for (int i = 0; i < kAxisCount; ++i)
    if (i < 3 || st.position[i] != 0)
      where += fmt::format(" {}={:.4f}", axis_name(settings_, i), st.position[i]);
  message_ += fmt::format("; the tool is at{} (the pulses played)", where);
  if (error_) error_->message = message_;
}

// Job thread, the state settled.
Controller::Activity Controller::activity(bool at_rest) const {
  Activity a;
  a.at_rest = at_rest;
  a.part_file = running_file_ && !typed_;
  a.file = activity_file_;
  a.modal = interp_->state();
  a.units = interp_->settings().units;
  if (!at_rest) return a;
  a.estop = state_ == MachineState::EStop || fault_ != CardFault::None;
  a.fault = fault_;
  a.error = error_;
  if (!a.error && !message_.empty()) a.error = Diagnostic{stopped_at_, Severity::Error, message_};
  a.elapsed_s = static_cast<double>(feed_.tick() - start_tick_) / settings_.card.pacer_hz();
  return a;
}

void Controller::on_activity(std::function<void(const Activity&)> f) {
  std::lock_guard lock(m_);
  activity_ = std::move(f);
}

void Controller::restore(const std::function<void(ModalState&, const Vec6& machine)>& edit) {
  std::lock_guard lock(m_);
  if (busy_) return;
  ModalState st = interp_->state();
  edit(st, played_machine());
  interp_->restore_state(st);
}

void Controller::wait_for_motion() {
  feed_.wait_for_motion();
}

// ---- from the feeder thread ----------------------------------------------------------------

void Controller::card_faulted(const GantryError& e, CardFault fault, const Steps6& commanded) {
  std::lock_guard lock(m_);
  message_ = e.diagnostic().message;
  if (fault == CardFault::Limit) message_ = active_limits(card_.inputs()) + ": " + message_;
  stopped_at_ = e.diagnostic().loc;
  fault_ = fault;
  fault_commanded_ = commanded;
  must_home_.fetch_or(settings_.homing.require, std::memory_order_acq_rel);  // mid-motion
  error_ = Diagnostic{stopped_at_, Severity::Error, message_};
  if (fault == CardFault::EStop) state_ = MachineState::EStop;
}

void Controller::roles_changed(const InputRoles& roles) {
  std::lock_guard lock(m_);
  roles_ = roles;
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
        add(fmt::format("{} {} limit switch (input bit {})", axis_name(settings_, i), side, bit));
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
    const char L = axis_name(settings_, i);
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
void Controller::stop_switch_pressed(std::uint32_t bits) {
  const bool jogging = state() == MachineState::Jogging;
  // A jog ends as if the key were let go; anything else at rest refuses the pause.
  if (!(jogging ? jog_release() : pause(/*every_output=*/true))) return;
  std::lock_guard lock(m_);
  const std::string stops = active_stops(bits);
  message_ = jogging ? stops + " stopped the jog"
                     : fmt::format("{} paused the file: release it, then resume", stops);
}

// A hold or halt took effect (the feeder has published where the tool is).
void Controller::feeder_phase_changed(FeedPhase phase, const SourceLoc& rest) {
  {
    std::lock_guard lock(m_);
    if (phase == FeedPhase::Held || phase == FeedPhase::Halted) stopped_at_ = rest;
    if (phase == FeedPhase::Held && effect_state_) {
      state_ = *effect_state_;  // a scheduled pause or stop took effect
      if (state_ == MachineState::Stopping) {
        feed_.abort();
        message_ = "stopped by the operator";
      }
      effect_state_.reset();
    }
    if (phase == FeedPhase::Halted) {
      if (state_ == MachineState::Running || state_ == MachineState::Jogging ||
          state_ == MachineState::Homing || state_ == MachineState::Probing ||
          state_ == MachineState::Stopping)  // a scheduled E-stop mid-motion (homing.require)
        must_home_.fetch_or(settings_.homing.require, std::memory_order_acq_rel);
      state_ = MachineState::EStop;
      feed_.halted();
      feed_.abort();
      if (message_.empty()) message_ = "E-stop";
    }
  }
  cv_.notify_all();
}

}  // namespace gantry
