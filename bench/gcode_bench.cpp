// G-code's front end against issue 23's targets, one core: the block parser >= 8 M lines/s
// and the interpreter >= 4 M lines/s on `G1 X.. Y.. Z..` lines. Each benchmark prints its
// rate and `of_target` (1 = the target met). Run:
//   cmake -DGANTRY_BENCH=ON ... && build/bench/gantry_bench --benchmark_filter=Gcode
#include <benchmark/benchmark.h>
#include <fmt/format.h>

#include <random>
#include <string>
#include <vector>

#include "gantry/interp/interpreter.hpp"
#include "gantry/interp/operator_io.hpp"
#include "gantry/interp/persistent_store.hpp"
#include "gantry/lang/gcode.hpp"
#include "gantry/lang/script.hpp"

namespace {

using namespace gantry;

constexpr double kParseTarget = 8e6;      // lines/s
constexpr double kInterpretTarget = 4e6;  // lines/s

// `n` feeding moves wandering inside the default table, as a CAM post writes them.
std::string g1_program(int n) {
  std::mt19937 rng(23);
  std::uniform_real_distribution<double> x(1, 23), y(1, 17), z(-0.5, 0.5);
  std::string text = "G20 G90 G17 F240\n";
  for (int i = 0; i < n; ++i)
    text += fmt::format("G1 X{:.4f} Y{:.4f} Z{:.4f}\n", x(rng), y(rng), z(rng));
  return text;
}

class DropSink : public MotionSink {
 public:
  void move(const CanonMove&) override {}
  void flush() override {}
};

void rates(benchmark::State& state, double lines, double target) {
  const double done = lines * static_cast<double>(state.iterations());
  state.counters["lines/s"] = benchmark::Counter(done, benchmark::Counter::kIsRate);
  state.counters["of_target"] = benchmark::Counter(done / target, benchmark::Counter::kIsRate);
}

// parse_gcode_block on every line, one block reused (as the interpreter reads them).
void BM_GcodeParse(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const std::string text = g1_program(n);
  std::vector<std::string_view> lines;
  for (size_t b = 0, e; b < text.size(); b = e + 1) {
    e = text.find('\n', b);
    lines.emplace_back(text.data() + b, e - b);
  }
  const auto file = std::make_shared<const std::string>("bench.nc");
  GcodeBlock block;
  Diagnostic error;
  for (auto _ : state) {
    int line = 0;
    for (std::string_view l : lines)
      benchmark::DoNotOptimize(parse_gcode_block(l, file, ++line, &block, &error));
  }
  rates(state, static_cast<double>(lines.size()), kParseTarget);
}
BENCHMARK(BM_GcodeParse)->Arg(1000000)->Unit(benchmark::kMillisecond);

// The loaded program run into a sink that drops the moves: reading each line, its block,
// modes, units, soft limits and the canonical moves (what `gantry moves` does after loading).
void BM_GcodeInterpret(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const auto script = Script::from_text(g1_program(n), "bench.nc");
  const Settings settings = default_settings();
  for (auto _ : state) {
    DropSink sink;
    std::string printed;
    ScriptedIO io(true, {}, &printed);
    PersistentStore store;
    Interpreter interp(settings, sink, io, store);
    interp.run(script);
    benchmark::DoNotOptimize(interp.statements_executed());
  }
  rates(state, n + 1, kInterpretTarget);
}
BENCHMARK(BM_GcodeInterpret)->Arg(1000000)->Unit(benchmark::kMillisecond);

// The same program checked (`gantry check`, and before every run): a dry run.
void BM_GcodeCheck(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const auto script = Script::from_text(g1_program(n), "bench.nc");
  const Settings settings = default_settings();
  for (auto _ : state) {
    DropSink sink;
    std::string printed;
    ScriptedIO io(true, {}, &printed);
    PersistentStore store;
    InterpreterOptions o;
    o.dry_run = true;
    Interpreter interp(settings, sink, io, store, o);
    benchmark::DoNotOptimize(interp.check(script).size());
  }
  rates(state, n + 1, kInterpretTarget);
}
BENCHMARK(BM_GcodeCheck)->Arg(1000000)->Unit(benchmark::kMillisecond);

}  // namespace
