// The Script line store on files read from disk: a GOSUB/RETURN loop whose subroutine sits
// more than 1 MiB from its caller against the same program with it near (issue 27: far no
// slower than near), the 200k-line expression file from disk against the same text in memory,
// and the peak memory of checking a 10M-line file (target < 200 MB).
// Run: build/bench/gantry_bench --benchmark_filter=Script
#include <benchmark/benchmark.h>
#include <fmt/format.h>

#include <filesystem>
#include <fstream>
#include <string>

#include <sys/resource.h>  // wait4's rusage: the child's peak RSS
#include <sys/wait.h>
#include <unistd.h>  // fork

#include "gantry/interp/interpreter.hpp"
#include "gantry/lang/script.hpp"

namespace {

using namespace gantry;

class Drop : public MotionSink {
 public:
  void move(const CanonMove&) override {}
  void flush() override {}
};

// `text` written once per process to a file in the temporary directory.
std::string on_disk(const std::string& name, const std::string& text) {
  const std::string path =
      (std::filesystem::temp_directory_path() / ("gantry_script_bench_" + name)).string();
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

// Runs the loaded script once per iteration (its load pass outside the timing); lines/s.
void run_script(benchmark::State& state, const std::shared_ptr<const Script>& script,
                double lines) {
  if (!script->ok()) {
    state.SkipWithError(format(script->errors().front()).c_str());
    return;
  }
  const Settings settings = default_settings();
  for (auto _ : state) {
    Drop sink;
    ScriptedIO io(true, {}, nullptr);
    PersistentStore store;
    Interpreter interp(settings, sink, io, store);
    interp.run(script);
    benchmark::DoNotOptimize(interp.statements_executed());
  }
  state.counters["lines/s"] = benchmark::Counter(lines * static_cast<double>(state.iterations()),
                                                 benchmark::Counter::kIsRate);
}

// 2 MiB of comment lines: never run, only read by the load pass.
std::string padding() {
  std::string pad;
  while (pad.size() < (size_t{2} << 20)) pad += "' padding that the run jumps over, 48 bytes\n";
  return pad;
}

// A counted loop calling a two-line subroutine: 7 lines a pass. Far: 2 MiB of comments
// between the loop and the subroutine; near: the same comments after the subroutine.
std::string gosub_program(int passes, bool far) {
  const std::string loop = fmt::format(
      "SA\n&i = 0\n&dx = 0.01\n&x0 = 1\nLOOP:\n&i = &i + 1\nGOSUB STEP\n"
      "IF &i < {} THEN GOTO LOOP\nEND\n",
      passes);
  const std::string sub = "STEP:\n&x = &x0 + (&i MOD 100) * &dx\nM2, &x, 2\nRETURN\n";
  return far ? loop + padding() + sub : loop + sub + padding();
}

void BM_ScriptGosubNear(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  run_script(state, Script::load(on_disk("near.sbp", gosub_program(n, false))), 7.0 * n);
}
BENCHMARK(BM_ScriptGosubNear)->Arg(200000)->Unit(benchmark::kMillisecond);

void BM_ScriptGosubFar(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  run_script(state, Script::load(on_disk("far.sbp", gosub_program(n, true))), 7.0 * n);
}
BENCHMARK(BM_ScriptGosubFar)->Arg(200000)->Unit(benchmark::kMillisecond);

// The file: four-line blocks of assignments, IF and a GOSUB to one subroutine at the
// end (4 MiB on, so most calls cross more than 1 MiB), from disk and from memory.
std::string expression_file(int lines) {
  std::string text = "SA\n&i = 0\n&dx = 0.01\n";
  for (int k = 0; k < lines / 4; ++k)
    text +=
        "&i = &i + 1\n&x = 1 + (&i MOD 100) * &dx\nIF &x > 1.5 THEN &x = &x - 0.5\n"
        "GOSUB CUT\n";
  return text + "END\nCUT:\nM2, &x, 2 + SIN(&i / 10) / 2\nRETURN\n";
}

void BM_ScriptExpressionFileFromDisk(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  run_script(state, Script::load(on_disk("expr.sbp", expression_file(n))), 1.5 * n);
}
BENCHMARK(BM_ScriptExpressionFileFromDisk)->Arg(200000)->Unit(benchmark::kMillisecond);

void BM_ScriptExpressionFileFromText(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  run_script(state, Script::from_text(expression_file(n), "expr.sbp"), 1.5 * n);
}
BENCHMARK(BM_ScriptExpressionFileFromText)->Arg(200000)->Unit(benchmark::kMillisecond);

// This process's resident memory now, in MiB (/proc/self/statm: pages).
double resident_mb() {
  std::ifstream statm("/proc/self/statm");
  double size = 0, resident = 0;
  statm >> size >> resident;
  return resident * static_cast<double>(::sysconf(_SC_PAGESIZE)) / (1024.0 * 1024.0);
}

// Writes `lines` lines made by `line(i)` to a file in the temporary directory, a MiB at a time.
template <typename Line>
std::string write_big_file(const char* name, long lines, Line line) {
  const std::string path = (std::filesystem::temp_directory_path() / name).string();
  std::ofstream out(path, std::ios::binary);
  std::string chunk;
  for (long i = 0; i < lines; ++i) {
    line(i, chunk);
    if (chunk.size() > (size_t{1} << 20)) {
      out << chunk;
      chunk.clear();
    }
  }
  out << chunk;
  return path;
}

// Peak RSS of loading (the whole-file check pass) and running the file at `path`, in a child
// process: rss_MB (its peak, which starts at bench_process_MB, this process's resident memory
// when it forks) against target_MB. The file is removed after.
void peak_rss(benchmark::State& state, const std::string& path) {
  double rss_mb = 0, parent_mb = 0;
  for (auto _ : state) {
    parent_mb = resident_mb();  // the child starts with this much counted in its peak
    const pid_t child = ::fork();
    if (child == 0) {
      const auto script = Script::load(path);
      Drop sink;
      ScriptedIO io(true, {}, nullptr);
      PersistentStore store;
      Interpreter interp(default_settings(), sink, io, store);
      if (script->ok()) interp.run(script);
      ::_exit(script->ok() && interp.statements_executed() > 0 ? 0 : 1);
    }
    int status = 0;
    struct rusage ru {};
    ::wait4(child, &status, 0, &ru);
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) state.SkipWithError("the child failed");
    rss_mb = static_cast<double>(ru.ru_maxrss) / 1024.0;  // KiB
  }
  state.counters["rss_MB"] = rss_mb;
  state.counters["bench_process_MB"] = parent_mb;
  state.counters["target_MB"] = 200;
  state.counters["file_MB"] =
      static_cast<double>(std::filesystem::file_size(path)) / (1024.0 * 1024.0);
  std::filesystem::remove(path);
}

// A 10M-line file of moves.
void BM_ScriptTenMillionLinesPeakRss(benchmark::State& state) {
  peak_rss(state, write_big_file("gantry_script_bench_10m.sbp", state.range(0),
                                 [](long i, std::string& out) {
                                   if (i == 0) return void(out += "SA\n");
                                   out += fmt::format("M3, {}.{:04}, {}.5, -0.{:03}\n", 1 + i % 20,
                                                      i % 10000, 1 + i % 15, i % 500);
                                 }));
}
BENCHMARK(BM_ScriptTenMillionLinesPeakRss)
    ->Arg(10000000)
    ->Iterations(1)
    ->Unit(benchmark::kMillisecond);

// A 10M-line file of labels and jumps, bench/sbp_bench_files.py's mixed.sbp in shape: blocks
// of eight lines with two labels, a forward GOTO, a backward one and a GOSUB to one of ten
// subroutines at the end (2.5 M labels, 3.75 M jumps, 2.5 M of them forward).
void BM_ScriptTenMillionLinesOfLabelsPeakRss(benchmark::State& state) {
  const long blocks = state.range(0) / 8;
  peak_rss(state,
           write_big_file("gantry_script_bench_10m_labels.sbp", blocks + 1,
                          [blocks](long k, std::string& out) {
                            if (k == 0) out += "SA\n&b = 1\n&c = 0\n";
                            if (k == blocks) {
                              out += "END\n";
                              for (int j = 0; j < 10; ++j)
                                out += fmt::format("S{}:\n&d = SIN(&a + {})\nRETURN\n", j, j);
                              return;
                            }
                            out += fmt::format(
                                "B{0}:\n&a = {1}.5 + ABS(&b - 1.25)\n&b = SQR(&a * 1.5) MOD 7\n"
                                "IF &a > {2} THEN GOTO C{0}\nGOSUB S{3}\nC{0}:\n"
                                "&c = &c + &a * 0.5\nIF &a < -1000 THEN GOTO B0\n",
                                k, k % 10, 5 + k % 10, k % 10);
                          }));
}
BENCHMARK(BM_ScriptTenMillionLinesOfLabelsPeakRss)
    ->Arg(10000000)
    ->Iterations(1)
    ->Unit(benchmark::kMillisecond);

}  // namespace
