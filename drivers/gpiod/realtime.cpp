// SCHED_FIFO, CPU affinity, mlockall and stack pre-faulting for the player thread.
#include "gpiod/realtime.hpp"

#include <fmt/format.h>
#include <pthread.h>
#include <sched.h>
#include <sys/mman.h>

#include <cerrno>
#include <cstring>

namespace gantry {
namespace {

void add_note(std::string& notes, const std::string& note) {
  if (!notes.empty()) notes += "; ";
  notes += note;
}

// Touching the stack now makes its pages resident (and locked, after mlockall), so the
// player's first calls do not fault.
void prefault_stack() {
  constexpr std::size_t kStackBytes = 64 * 1024;
  volatile unsigned char stack[kStackBytes];
  for (std::size_t i = 0; i < kStackBytes; i += 4096) stack[i] = 0;
  static_cast<void>(stack[0]);  // a volatile read: the stores above must happen
}

}  // namespace

bool lock_memory(std::string* note) {
  if (mlockall(MCL_CURRENT | MCL_FUTURE) == 0) return true;
  if (note)
    *note = fmt::format(
        "mlockall failed ({}): page faults may delay ticks; raise RLIMIT_MEMLOCK (ulimit -l) "
        "or grant CAP_IPC_LOCK",
        std::strerror(errno));
  return false;
}

void make_thread_realtime(int priority, int cpu, RealtimeResult& result) {
  result.pinned = cpu < 0;
  if (cpu >= 0) {
    cpu_set_t set;
    CPU_ZERO(&set);
    CPU_SET(cpu, &set);
    const int err = pthread_setaffinity_np(pthread_self(), sizeof set, &set);
    result.pinned = err == 0;
    if (err)
      add_note(result.notes, fmt::format("cannot pin to CPU {}: {}", cpu, std::strerror(err)));
  }
  sched_param param{};
  param.sched_priority = priority;
  const int err = pthread_setschedparam(pthread_self(), SCHED_FIFO, &param);
  result.fifo = err == 0;
  if (err)
    add_note(result.notes,
             fmt::format("SCHED_FIFO refused ({}): ticks run at normal priority; grant "
                         "CAP_SYS_NICE or an rtprio limit",
                         std::strerror(err)));
  prefault_stack();
}

}  // namespace gantry
