// Throughput of each pipeline stage, printed as rates and as multiples of real time.
// Run: cmake -DGANTRY_BENCH=ON ... && build/bench/gantry_bench
#include <benchmark/benchmark.h>  // the harness
#include <fmt/format.h>           // generated part files

#include <random>  // move generation

#include "gantry/lang/parser.hpp"          // parse_program
#include "gantry/machine/job.hpp"          // check_program, run_job
#include "gantry/step/step_generator.hpp"  // StepGenerator
#include "sim/sim_card.hpp"                // SimCard

namespace {

using namespace gantry;

// `lines` M3 moves wandering inside the default table.
std::string generated_file(int lines) {
  std::mt19937 rng(42);
  std::uniform_real_distribution<double> x(1, 23), y(1, 17), z(-0.5, 0.5);
  std::string text = "SA\nMS, 4, 2\n";
  for (int i = 0; i < lines; ++i)
    text += fmt::format("M3, {:.4f}, {:.4f}, {:.4f}\n", x(rng), y(rng), z(rng));
  return text;
}

// Parse + interpret (no motion): statements per second.
void BM_ParseAndInterpret(benchmark::State& state) {
  const std::string text = generated_file(static_cast<int>(state.range(0)));
  const Settings settings = default_settings();
  for (auto _ : state) {
    Program p = parse_program(text, "bench.sbp");
    benchmark::DoNotOptimize(check_program(p, settings));
  }
  state.counters["lines/s"] = benchmark::Counter(
      static_cast<double>(state.range(0) * state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_ParseAndInterpret)->Arg(100000)->Unit(benchmark::kMillisecond);

class DiscardCard : public Card {
 public:
  void start(double) override {}
  void write(std::span<const std::uint32_t> w) override { ticks_ += w.size(); }
  void drain() override {}
  std::uint64_t ticks_played() const override { return ticks_; }

 private:
  std::uint64_t ticks_ = 0;
};

// Step generation alone: six axes moving together at 100 kHz each on the 200 kHz pacer.
void BM_StepGeneratorSixAxesAt100kHz(benchmark::State& state) {
  Settings s = default_settings();
  for (auto& ax : s.axes) {
    ax.steps_per_unit = 10000;  // 10 units/s = 100 kHz
    ax.max_speed = 10;
  }
  const double len = std::sqrt(6.0) * 10;  // one second at 10 units/s per axis
  PlannedSegment seg;
  seg.profile =
      Trapezoid::plan(len, std::sqrt(6.0) * 10, std::sqrt(6.0) * 10, std::sqrt(6.0) * 10, 1e9);
  std::uint64_t words = 0;
  for (auto _ : state) {
    DiscardCard card;
    StepGenerator gen(s, card);
    seg.from = Vec6::Zero();
    seg.to = Vec6::Constant(10);
    gen.segment(seg);
    gen.flush();
    words += card.ticks_played();
  }
  state.counters["words/s"] =
      benchmark::Counter(static_cast<double>(words), benchmark::Counter::kIsRate);
  state.counters["x_realtime"] = benchmark::Counter(static_cast<double>(words) / s.card.pacer_hz(),
                                                    benchmark::Counter::kIsRate);
}
BENCHMARK(BM_StepGeneratorSixAxesAt100kHz)->Unit(benchmark::kMillisecond);

// The whole job on the simulated card: machine seconds per wall second.
void BM_FullPipeline(benchmark::State& state) {
  const std::string text = generated_file(static_cast<int>(state.range(0)));
  const Settings settings = default_settings();
  const Program p = parse_program(text, "bench.sbp");
  double machine_s = 0;
  for (auto _ : state) {
    SimCard card(settings);
    run_job(p, settings, card);
    machine_s += card.time_s();
  }
  state.counters["x_realtime"] = benchmark::Counter(machine_s, benchmark::Counter::kIsRate);
}
BENCHMARK(BM_FullPipeline)->Arg(200)->Unit(benchmark::kMillisecond);

}  // namespace
