// A pendant's report to the jog's start (issue 26: at most 10 ms of processing): the 8 bytes
// decoded, made an event, the jog requested of the controller, and the first step played by
// the simulated card (virtual time: the card itself adds no delay).
// Run: build/bench/gantry_pendant_bench
#include <benchmark/benchmark.h>

#include <array>
#include <chrono>

#include "gantry/interp/operator_io.hpp"     // ScriptedIO
#include "gantry/session/pendant_input.hpp"  // PendantInput
#include "gantry/session/pendant_xhc.hpp"    // XhcTranslator
#include "pendant/xhc_protocol.hpp"          // decode_report
#include "sim/sim_card.hpp"                  // SimCard

namespace {

using namespace gantry;
using Clock = std::chrono::steady_clock;

// One detent of the wheel on X in step mode (0.001 a detent), alternately forward and back.
std::array<std::uint8_t, 8> wheel_report(bool forward) {
  return {0x04, 0x21, 0x00, 0x00, 0x0d, 0x11, static_cast<std::uint8_t>(forward ? 1 : 0xff), 0x21};
}

void BM_PendantReportToFirstStep(benchmark::State& state) {
  const Settings settings = default_settings();
  SimCard card{settings};
  ScriptedIO io{true, {}};
  PersistentStore store;
  Controller c{settings, card, io, store};
  session::PendantInput input(c, settings, {});
  session::XhcTranslator translator;
  bool forward = true;
  double to_request = 0;
  for (auto _ : state) {
    const std::int64_t before = c.status().steps[0];
    const auto report = wheel_report(forward);
    const auto t0 = Clock::now();
    for (const session::PendantEvent& e : translator.events(*pendant::decode_report(report, nullptr)))
      input.handle(e);
    const auto requested = Clock::now();  // handle() returns once the controller took the jog
    while (c.status().steps[0] == before) {
    }
    const auto t1 = Clock::now();
    state.SetIterationTime(std::chrono::duration<double>(t1 - t0).count());
    to_request += std::chrono::duration<double>(requested - t0).count();
    c.wait();
    input.tick();  // the step is at rest: the pendant's next may go
    forward = !forward;
  }
  // The pendant's own processing: report to the jog requested of the controller (the rest is
  // the controller's job and feeder threads planning and stepping).
  state.counters["to_jog_request_us"] =
      benchmark::Counter(to_request * 1e6 / static_cast<double>(state.iterations()));
}
BENCHMARK(BM_PendantReportToFirstStep)->UseManualTime()->Unit(benchmark::kMicrosecond);

// The pendant's own share: a report decoded and made events (no controller).
void BM_PendantDecodeAndTranslate(benchmark::State& state) {
  session::XhcTranslator translator;
  bool forward = true;
  for (auto _ : state) {
    const auto report = wheel_report(forward);
    auto events = translator.events(*pendant::decode_report(report, nullptr));
    benchmark::DoNotOptimize(events);
    forward = !forward;
  }
}
BENCHMARK(BM_PendantDecodeAndTranslate);

}  // namespace
