// How long this computer keeps a SCHED_FIFO thread off its CPU (issue 26's soak): a spinner per
// CPU records the gaps between its clock reads, and a sleeper the lateness of 1 ms wake-ups.
//
//   build/bench/stall_probe [seconds] [priority] [spinners]   (defaults: 10, 60, 1; 0: the sleeper alone)
//
// A gap a real-time spinner sees cannot be another process of this computer (it is preempted
// only by higher real-time priorities, interrupts and the kernel's own work): long gaps are
// the hypervisor running something else on the virtual CPU, or interrupts held off. Whatever
// the feeder thread does, it cannot get below them; the lead must cover them. The spinners
// spin 200 ms in each 500 ms, so the kernel's real-time throttling (950 ms a second) never
// cuts in and measures itself.
#include <pthread.h>
#include <sched.h>
#include <sys/mman.h>
#include <time.h>

#include <algorithm>
#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <thread>
#include <vector>

namespace {

std::int64_t now_ns() {
  timespec t{};
  clock_gettime(CLOCK_MONOTONIC, &t);
  return static_cast<std::int64_t>(t.tv_sec) * 1'000'000'000 + t.tv_nsec;
}

struct Figures {
  std::int64_t worst_ns = 0;
  long over_1ms = 0, over_5ms = 0, over_10ms = 0;
  void add(std::int64_t gap) {
    worst_ns = std::max(worst_ns, gap);
    over_1ms += gap > 1'000'000;
    over_5ms += gap > 5'000'000;
    over_10ms += gap > 10'000'000;
  }
};

bool realtime(int priority, int cpu) {
  if (cpu >= 0) {
    cpu_set_t set;
    CPU_ZERO(&set);
    CPU_SET(cpu, &set);
    pthread_setaffinity_np(pthread_self(), sizeof set, &set);
  }
  sched_param p{};
  p.sched_priority = priority;
  return pthread_setschedparam(pthread_self(), SCHED_FIFO, &p) == 0;
}

}  // namespace

int main(int argc, char** argv) {
  const double seconds = argc > 1 ? std::atof(argv[1]) : 10;
  const int priority = argc > 2 ? std::atoi(argv[2]) : 60;
  const bool spinners = argc > 3 ? std::atoi(argv[3]) != 0 : true;
  const bool locked = mlockall(MCL_CURRENT | MCL_FUTURE) == 0;
  const unsigned cpus = std::max(1u, std::thread::hardware_concurrency());
  const std::int64_t end = now_ns() + static_cast<std::int64_t>(seconds * 1e9);
  std::vector<Figures> spin(cpus);
  Figures sleep;
  std::atomic<bool> fifo{true};
  std::vector<std::thread> threads;
  for (unsigned c = 0; spinners && c < cpus; ++c)
    threads.emplace_back([&, c] {
      if (!realtime(priority, static_cast<int>(c))) fifo = false;
      while (now_ns() < end) {
        const std::int64_t stop = now_ns() + 200'000'000;
        std::int64_t last = now_ns();
        while (last < stop) {
          const std::int64_t t = now_ns();
          spin[c].add(t - last);
          last = t;
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(300));
      }
    });
  threads.emplace_back([&] {
    if (!realtime(priority + 1, -1)) fifo = false;
    std::int64_t due = now_ns();
    while (due < end) {
      due += 1'000'000;
      const timespec ts{static_cast<time_t>(due / 1'000'000'000),
                        static_cast<long>(due % 1'000'000'000)};
      clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, nullptr);
      sleep.add(now_ns() - due);
    }
  });
  for (std::thread& t : threads) t.join();
  std::printf("stall_probe: %.0f s, %u CPUs, %s priority %d, memory %slocked\n", seconds, cpus,
              fifo ? "SCHED_FIFO" : "SCHED_OTHER (SCHED_FIFO refused)", priority,
              locked ? "" : "not ");
  for (unsigned c = 0; spinners && c < cpus; ++c)
    std::printf("stall_probe: CPU %u spinner: worst gap %.2f ms; gaps > 1 ms: %ld, > 5 ms: %ld, "
                "> 10 ms: %ld\n",
                c, spin[c].worst_ns * 1e-6, spin[c].over_1ms, spin[c].over_5ms, spin[c].over_10ms);
  std::printf("stall_probe: 1 ms sleeper: worst lateness %.2f ms; late > 1 ms: %ld, > 5 ms: %ld, "
              "> 10 ms: %ld\n",
              sleep.worst_ns * 1e-6, sleep.over_1ms, sleep.over_5ms, sleep.over_10ms);
  return 0;
}
