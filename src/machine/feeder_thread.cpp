// The controller's feeder thread: plays the job's queue on the card and owns the flag protocol.
#include "gantry/machine/feeder_thread.hpp"

#include <fmt/format.h>  // the note
#include <pthread.h>
#include <sched.h>
#include <sys/mman.h>

#include <algorithm>  // max
#include <cerrno>
#include <cstdio>   // stderr
#include <cstring>  // strerror
#include <mutex>    // once_flag

namespace gantry {

Vec6 steps_to_machine(const Settings& settings, const Steps6& steps) {
  Vec6 m = Vec6::Zero();
  for (int i = 0; i < kAxisCount; ++i)
    m[i] = static_cast<double>(steps[i]) / settings.axes[i].steps_per_unit;
  return m;
}

// ---- job thread -> feeder ----------------------------------------------------------------

namespace {

FeederThread::Item item_of(FeederThread::Item::Kind kind) {
  FeederThread::Item item;
  item.kind = kind;
  return item;
}

}  // namespace

void FeederThread::Sink::move(const CanonMove& m) {
  Item item = item_of(Item::kMove);
  item.move = m;
  push(std::move(item));
}

void FeederThread::Sink::flush() {
  push(item_of(Item::kFlush));
}

void FeederThread::Sink::settings_changed(const Settings& s) {
  Item item = item_of(Item::kSettings);
  item.settings = std::make_shared<const Settings>(s);
  push(std::move(item));
}

void FeederThread::Sink::new_plan(const Settings& s, double feed_override) {
  Item item = item_of(Item::kPlanner);
  item.settings = std::make_shared<const Settings>(s);
  item.factor = feed_override;
  push(std::move(item), /*abortable=*/false);
}

void FeederThread::Sink::feed_override(double factor) {
  Item item = item_of(Item::kOverride);
  item.factor = factor;
  push(std::move(item));
}

void FeederThread::Sink::watch(std::span<const InputTrigger> t) {
  Item item = item_of(Item::kWatch);
  item.triggers = std::make_shared<const std::vector<InputTrigger>>(t.begin(), t.end());
  push(std::move(item), /*abortable=*/false);  // disarming is pushed as a run winds down
}

void FeederThread::Sink::fence() {
  dead_ = false;
  push(item_of(Item::kFlush), /*abortable=*/false);
}

void FeederThread::Sink::outputs(std::uint32_t mask) {
  dead_ = false;
  for (int n = 1; n <= 12; ++n) {
    Item item = item_of(Item::kSegment);
    item.seg.output = n;  // one the profile does not wire switches nothing
    item.seg.output_on = (mask >> (n - 1) & 1u) != 0;
    push(std::move(item), /*abortable=*/false);
  }
  fence();
}

void FeederThread::Sink::push(Item&& item, bool abortable) {
  if (dead_) return;
  const bool flush = item.kind == Item::kFlush;
  while (true) {
    if (abortable && f_.abort_.load(std::memory_order_acquire)) {
      dead_ = true;
      throw GantryError(Diagnostic{item.seg.loc, Severity::Error, "stopped"});
    }
    if (f_.queue_.try_push(std::move(item))) break;
    f_.queue_.wait_for_room();
  }
  if (flush) ++f_.flushes_pushed_;
  f_.wake_.fetch_add(1, std::memory_order_release);
  f_.wake_.notify_one();
}

void FeederThread::wait_for_motion() {
  while (true) {
    const std::uint64_t done = flushes_done_.load(std::memory_order_acquire);
    if (done >= flushes_pushed_) return;
    flushes_done_.wait(done);
  }
}

// ---- life ----------------------------------------------------------------------------------

FeederThread::FeederThread(const Settings& settings, Card& card, const InputTrip& stops,
                           FeederEvents& events)
    : settings_(settings),
      card_(card),
      events_(events),
      steps_((card.start(settings.card.pacer_hz()), settings), card),
      feeder_(steps_),
      queue_(256),
      planner_(std::make_unique<LookAheadPlanner>(settings, plan_out_)),
      stop_trip_(stops) {
  steps_.lead().on_grow([](const std::string& note) {  // once per run: the operator's log
    std::fprintf(stderr, "gantry: %s\n", note.c_str());
  });
  steps_.on_block([this] {
    publish();  // the readout moves during long segments
    watch_stop_switches();
  });
}

void FeederThread::start() {
  thread_ = std::thread([this] {
    if (card_.queues_words()) make_realtime();
    main();
  });
}

// On a card that queues words the feeder must come back within the lead every time: it asks
// for SCHED_FIFO above the job thread (and below a card's own player thread, 80) and locks
// the process's memory (pages locked as they are touched: no page fault in the loop). Best
// effort: without the privilege it runs as it is, and says so once per process.
void FeederThread::make_realtime() {
  std::string refused;
  sched_param param{};
  param.sched_priority = kFeederPriority;
  int policy = SCHED_OTHER;
  sched_param now{};
  pthread_getschedparam(pthread_self(), &policy, &now);
  if (policy != SCHED_FIFO || now.sched_priority < kFeederPriority) {
    if (const int err = pthread_setschedparam(pthread_self(), SCHED_FIFO, &param))
      refused = fmt::format("SCHED_FIFO refused ({}: grant CAP_SYS_NICE or `ulimit -r {}`)",
                            std::strerror(err), kFeederPriority);
  }
  static std::once_flag locked;
  std::call_once(locked, [&] {
    if (mlockall(MCL_CURRENT | MCL_FUTURE | MCL_ONFAULT) != 0)
      refused += fmt::format("{}memory not locked ({}: raise `ulimit -l` or grant CAP_IPC_LOCK)",
                             refused.empty() ? "" : "; ", std::strerror(errno));
  });
  realtime_ = refused.empty();
  static std::once_flag said;
  if (!refused.empty())
    std::call_once(said, [&] {
      std::fprintf(stderr,
                   "gantry: the feeder thread runs without real-time guarantees: %s; it may "
                   "underrun under load (docs/hardware.md)\n",
                   refused.c_str());
    });
}

void FeederThread::quit() {
  quit_ = true;
}

void FeederThread::join() {
  wake_.fetch_add(1);
  wake_.notify_all();
  thread_.join();
}

// ---- requests --------------------------------------------------------------------------------

void FeederThread::hold(std::int64_t tick, bool discard, bool pause, bool every_output) {
  on_hold_ = discard ? OnHold::Discard : OnHold::Wait;
  feeder_.request_hold(tick, pause, every_output);
}

void FeederThread::request_stop() {
  hold(0, /*discard=*/true);
  abort_ = true;
}

void FeederThread::request_estop() {
  feeder_.request_halt(0, settings_.limits.esc_steps);  // WinCNC's esc_step: a cushion
  cmd_halt_ = true;
  abort_ = true;
}

void FeederThread::wake() {
  wake_.fetch_add(1, std::memory_order_release);
  wake_.notify_one();
}

void FeederThread::new_activity() {
  interrupted_ = false;
  steps_.new_run();
}

bool FeederThread::spent_jog() {
  feeder_.request_hold(StepGenerator::kNever);
  on_hold_ = OnHold::Wait;
  dropping_ = false;
  return interrupted_.exchange(false);
}

void FeederThread::end_activity() {
  feeder_.request_hold(StepGenerator::kNever);
  on_hold_ = OnHold::Wait;
  cmd_resume_ = false;
  dropping_ = false;
}

Steps6 FeederThread::played() const {
  Steps6 steps{};
  for (int i = 0; i < kAxisCount; ++i) steps[i] = played_[i].load(std::memory_order_acquire);
  return steps;
}

// ---- the thread ------------------------------------------------------------------------------

void FeederThread::main() {
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
      try {
        feeder_.resume();  // replays the kept path: the card may fault as it plays
      } catch (const GantryError& e) {
        card_faulted(e, false);
      }
    } else if (ph == FeedPhase::Halted && cmd_acknowledge_.exchange(false)) {
      feeder_.discard();  // the card starts again
    }
    if (feeder_.phase() != last_phase_) on_feeder_event();
    apply_live_override();
    publish();
    // The card's queue is half way down from the refill point and the planner holds what it
    // would send only after more moves (its look-ahead of up to 1,024, say after SW's
    // warning, with moves still queued unplanned): the front goes as the plan stands, before
    // the next move is planned. Not at the refill point itself: the lead's wait returns
    // there after every block, and moves queued are planned in microseconds; releasing then
    // brought the path to rest after every move of a dense file (a 10 s circle of 720 chords
    // took 55 s on the card).
    if (const CardLead& lead = steps_.lead();
        lead.bounded() && !dropping_ && !drop_to_flush_ && !planner_->empty() &&
        (feeder_.phase() == FeedPhase::Playing || feeder_.phase() == FeedPhase::Slowing) &&
        lead.queued(steps_.sent()) > 0 && lead.queued(steps_.sent()) <= lead.refill_ticks() / 2) {
      release_front();
      continue;
    }
    Item item;
    if (feeder_.phase() == FeedPhase::Held || !queue_.try_pop(item)) {
      if (feeder_.phase() != FeedPhase::Held && feed_from_plan()) continue;
      wake_.wait(seen, std::memory_order_acquire);
      continue;
    }
    plan_out_.muted = dropping_ || drop_to_flush_;
    if (dropping_) {
      // The planner still takes the moves (muted): its state is what the stream made it.
      if (item.kind == Item::kMove) planner_->move(item.move);
      if (item.kind == Item::kOverride) planner_->feed_override(item.factor);
      if (item.kind == Item::kFlush) planner_->flush();
      flushes_dropped_ += item.kind == Item::kFlush;
    } else if (drop_to_flush_ && item.kind != Item::kSettings) {
      // The rest of the statement an input edge cut; what follows its flush plays.
      if (item.kind == Item::kFlush) {
        planner_->flush();
        ++flushes_dropped_;
        drop_to_flush_ = false;
      } else if (item.kind == Item::kWatch || item.kind == Item::kMove ||
                 item.kind == Item::kOverride) {
        feed(item);
      }
    } else {
      try {
        feed(item);
        if (input_cut_) finish_input_cut(item.kind == Item::kFlush);
      } catch (const GantryError& e) {
        card_faulted(e, item.kind == Item::kFlush);
      }
    }
    plan_out_.muted = false;
    if (feeder_.phase() != last_phase_) on_feeder_event();
    publish();
  }
  // The controller's destructor E-stops before it quits: the card's outputs go off (the
  // spindle relay, the charge pump) every time, not only when this loop saw the request
  // before quit_. A card keeps its last word after the process ends.
  if (cmd_halt_.exchange(false)) feeder_.halt_now();
}

// The card faulted and stopped by itself, while playing `item` (a lost flush is counted
// here) or while replaying a kept path on resume.
void FeederThread::card_faulted(const GantryError& e, bool flush_lost) {
  const CardFault fault = card_.fault();
  events_.card_faulted(e, fault, steps_.position());  // before the card starts again
  interrupted_ = true;
  abort_ = true;
  dropping_ = true;
  flushes_dropped_ += flush_lost;
  if (fault != CardFault::EStop) {  // the card starts again: the tool can move off it
    feeder_.halt_now();
    feeder_.discard();
    last_phase_ = FeedPhase::Playing;
  }
}

void FeederThread::feed(Item& item) {
  switch (item.kind) {
    case Item::kMove:
      planner_->move(item.move);
      break;
    case Item::kSegment:
      feeder_.segment(item.seg);
      break;
    case Item::kSettings: {
      planner_->settings_changed(*item.settings);            // at rest first, then to the feeder
      const InputRoles roles = input_roles(*item.settings);  // VN: at rest, not real-time
      stop_trip_ = roles.stops;
      events_.roles_changed(roles);
      break;
    }
    case Item::kFlush:
      planner_->flush();                            // the plan to rest, then the feeder's flush
      if (feeder_.phase() == FeedPhase::Playing) {  // a real card still plays its queue
        card_.drain();
        steps_.check_card();  // a fault in the last words
      }
      break;
    case Item::kWatch:
      arm_watch(item.triggers);
      break;
    case Item::kPlanner:  // an activity's start: nothing is held (the last one flushed)
      planner_ = std::make_unique<LookAheadPlanner>(*item.settings, plan_out_);
      planner_->feed_override(item.factor);
      break;
    case Item::kOverride:
      planner_->feed_override(item.factor);
      break;
  }
}

// The queue is empty. Mid-motion on a card that queues words, the feeder waits for the job
// thread only until the card's queue is down to where the next block is due (the lead less
// one block); then it plays the planner's front as the plan stands, which brings the path
// held to rest: a late job thread slows the machine, the card never runs dry mid-motion.
// With nothing held and the path at rest, it ends the stream there, so that the card may
// run dry at rest. Returns false when there is nothing to do but wait for a request or an item.
bool FeederThread::feed_from_plan() {
  CardLead& lead = steps_.lead();
  if (!lead.bounded() || dropping_ || drop_to_flush_ || feeder_.phase() == FeedPhase::Halted)
    return false;
  const std::int64_t queued = lead.queued(steps_.sent());
  if (queued <= 0) return false;  // nothing plays
  if (planner_->empty()) {
    // At rest with nothing held: the stream ends here (the card may run dry at rest), and
    // the feeder looks again as the card plays out what it holds.
    if (!feeder_.at_rest()) return false;
    try {
      if (!feeder_.rest_stream()) return false;  // an axis moving on its own (MI): wait
    } catch (const GantryError& e) {
      card_faulted(e, false);
      return true;
    }
    lead.sleep_at_most(queued, std::chrono::milliseconds(1));
    return true;
  }
  const std::int64_t slack = lead.slack(steps_.sent());
  if (slack > 0) {  // the job thread may still come in time
    const auto t0 = std::chrono::steady_clock::now();
    lead.sleep_at_most(slack, std::chrono::milliseconds(1));
    lead.starved_for(std::chrono::steady_clock::now() - t0);
    return true;
  }
  release_front();
  publish();
  return true;
}

// The card is due and no move came in time: the planner's front block goes as the plan stands.
void FeederThread::release_front() {
  try {
    planner_->release_front();
    starved_.fetch_add(1, std::memory_order_relaxed);
    if (input_cut_) finish_input_cut(false);
  } catch (const GantryError& e) {
    card_faulted(e, false);
  }
  if (feeder_.phase() != last_phase_) on_feeder_event();
}

// The operator's override on a card that queues words: the planner re-plans what it holds
// (and what is queued is planned with it as it comes); the motion feeder re-ramps the segment
// playing from its next word.
void FeederThread::live_override(double factor) {
  live_factor_.store(factor, std::memory_order_release);
  feeder_.live_override(factor);
  wake();
}

void FeederThread::apply_live_override() {
  const double f = live_factor_.exchange(0, std::memory_order_acq_rel);
  if (f > 0) planner_->feed_override(f);
}

// ---- the planner's output ------------------------------------------------------------------

void FeederThread::PlanOut::segment(const PlannedSegment& s) {
  if (!muted) f_.feeder_.segment(s);
}

void FeederThread::PlanOut::flush() {
  if (!muted) f_.feeder_.flush();  // a dropped flush is counted by the loop
}

void FeederThread::PlanOut::settings_changed(const Settings& s) {
  if (!f_.dropping_) f_.feeder_.settings_changed(s);  // an input edge's cut keeps them
}

// ---- input edges (ON INPUT, probes, homing) ------------------------------------------------

void FeederThread::arm_watch(std::shared_ptr<const std::vector<InputTrigger>> triggers) {
  watched_ = std::move(triggers);  // shared: nothing allocated here
  InputWatch w;
  for (const InputTrigger& t : *watched_) {
    const int bit = settings_.inputs.switch_bits[t.input - 1];
    if (bit < 0) continue;  // the interpreter has said it never fires
    w.mask |= 1u << bit;
    if (t.closing) w.levels |= 1u << bit;
    if (t.instant) w.stop |= 1u << bit;
    w.debounce = std::max(w.debounce, t.debounce);
  }
  fired_.reset();
  steps_.watch_inputs(w, [this](const InputEdge& e) { on_input_edge(e); });
}

// Inside the step generator, right after the block in which the card saw the edge: the tool
// was where the words before the edge's tick left it; the motion is cut there (instant) or
// ramps down from the next word on.
void FeederThread::on_input_edge(const InputEdge& e) {
  const bool closed = (e.bits >> e.bit & 1u) != 0;
  for (const InputTrigger& t : *watched_)
    if (settings_.inputs.switch_bits[t.input - 1] == e.bit && t.closing == closed) fired_ = t;
  if (!fired_) return;
  const std::optional<Steps6> at = steps_.position_at(e.tick);
  latched_ = steps_to_machine(settings_, at ? *at : steps_.played_position());
  input_cut_ = true;
  if (fired_->instant)
    feeder_.request_halt(0);
  else
    feeder_.request_hold(0);
}

// After each item while an edge's cut is under way. At rest, what the cut left of the
// statement's motion is dropped (up to its flush); still slowing, it goes on.
void FeederThread::finish_input_cut(bool consumed_flush) {
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

// SB3's remote stop: seen after the block in which the card read it; the controller pauses
// (or ends a jog) on the switch's closing edge.
void FeederThread::watch_stop_switches() {
  const std::uint32_t bits = card_.inputs();
  const bool active = stop_trip_.tripped(bits);
  const bool pressed = active && !stop_active_;
  stop_active_ = active;
  if (pressed) events_.stop_switch_pressed(bits);
}

void FeederThread::publish() {
  const Steps6 p = steps_.played_position();
  for (int i = 0; i < kAxisCount; ++i) played_[i].store(p[i], std::memory_order_release);
  tick_.store(steps_.tick(), std::memory_order_release);
  inputs_.store(card_.inputs(), std::memory_order_release);
  playing_line_.store(steps_.loc().line, std::memory_order_relaxed);
  playing_caller_line_.store(steps_.loc().caller_line, std::memory_order_relaxed);
  if (const std::shared_ptr<const std::string>& f = steps_.loc().file; f.get() != published_file_) {
    published_file_ = f.get();
    playing_file_.store(f, std::memory_order_relaxed);
  }
  const OutputLevels out = steps_.played_levels();
  outputs_.store(out.switches, std::memory_order_relaxed);
  spindle_rpm_.store(out.spindle_rpm, std::memory_order_relaxed);
  warning_.store(steps_.warning() && feeder_.phase() == FeedPhase::Playing,
                 std::memory_order_relaxed);
  planned_time_.store(planner_->planned_time(), std::memory_order_relaxed);
  flushes_done_.store(feeder_.flushes_completed() + flushes_dropped_, std::memory_order_release);
  flushes_done_.notify_all();
}

void FeederThread::on_feeder_event() {
  last_phase_ = feeder_.phase();
  publish();
  events_.feeder_phase_changed(last_phase_, feeder_.rest_loc());
}

}  // namespace gantry
