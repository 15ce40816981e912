// O-word loops against OpenSBP's GOTO loops: the same counted loop, one move per pass, both
// ways (issue 23: O-word loops no slower than GOTO loops). Figures: passes per second.
// Run: build/bench/gantry_bench --benchmark_filter=CountedLoop
#include <benchmark/benchmark.h>
#include <fmt/format.h>

#include "gantry/interp/interpreter.hpp"
#include "gantry/lang/script.hpp"

namespace {

using namespace gantry;

class Discard : public MotionSink {
 public:
  void move(const CanonMove&) override {}
  void flush() override {}
};

void counted_loop(benchmark::State& state, const std::string& text, const char* name) {
  const Settings settings = default_settings();
  for (auto _ : state) {
    Discard sink;
    ScriptedIO io(true, {}, nullptr);
    PersistentStore store;
    Interpreter interp(settings, sink, io, store);
    interp.run(Script::from_text(text, name));
    benchmark::DoNotOptimize(interp.statements_executed());
  }
  state.counters["passes/s"] = benchmark::Counter(
      static_cast<double>(state.range(0)) * static_cast<double>(state.iterations()),
      benchmark::Counter::kIsRate);
}

// Three lines a pass each way: the count, a move, the test and jump back.
void BM_CountedLoopOpenSbpGoto(benchmark::State& state) {
  counted_loop(state,
               fmt::format("SA\n&i = 0\nLOOP:\n&i = &i + 1\nM2, (&i MOD 10) / 10, 1\n"
                           "IF &i < {} THEN GOTO LOOP\nEND\n",
                           state.range(0)),
               "loop.sbp");
}
BENCHMARK(BM_CountedLoopOpenSbpGoto)->Arg(200000)->Unit(benchmark::kMillisecond);

void BM_CountedLoopGcodeWhile(benchmark::State& state) {
  counted_loop(state,
               fmt::format("G20 G90 F60\n#1 = 0\no1 while [#1 LT {}]\n#1 = [#1 + 1]\n"
                           "G1 X[[#1 MOD 10] / 10] Y1\no1 endwhile\nM2\n",
                           state.range(0)),
               "loop.ngc");
}
BENCHMARK(BM_CountedLoopGcodeWhile)->Arg(200000)->Unit(benchmark::kMillisecond);

void BM_CountedLoopGcodeRepeat(benchmark::State& state) {
  counted_loop(state,
               fmt::format("G20 G90 F60\n#1 = 0\no1 repeat [{}]\n#1 = [#1 + 1]\n"
                           "G1 X[[#1 MOD 10] / 10] Y1\no1 endrepeat\nM2\n",
                           state.range(0)),
               "loop.ngc");
}
BENCHMARK(BM_CountedLoopGcodeRepeat)->Arg(200000)->Unit(benchmark::kMillisecond);

// The control flow alone: the same loops counting without a move.
void BM_CountedLoopOpenSbpGotoNoMove(benchmark::State& state) {
  counted_loop(
      state,
      fmt::format("&i = 0\nLOOP:\n&i = &i + 1\nIF &i < {} THEN GOTO LOOP\nEND\n", state.range(0)),
      "loop.sbp");
}
BENCHMARK(BM_CountedLoopOpenSbpGotoNoMove)->Arg(200000)->Unit(benchmark::kMillisecond);

void BM_CountedLoopGcodeWhileNoMove(benchmark::State& state) {
  counted_loop(
      state,
      fmt::format("#1 = 0\no1 while [#1 LT {}]\n#1 = [#1 + 1]\no1 endwhile\nM2\n", state.range(0)),
      "loop.ngc");
}
BENCHMARK(BM_CountedLoopGcodeWhileNoMove)->Arg(200000)->Unit(benchmark::kMillisecond);

}  // namespace
