// Real-time set-up of the calling thread and the process, each step best effort: a machine
// without the privilege still runs, with looser timing, and the card says what it got.
#pragma once

#include <string>

namespace gantry {

struct RealtimeResult {
  bool fifo = false;           // SCHED_FIFO granted
  bool memory_locked = false;  // mlockall succeeded
  bool pinned = false;         // affinity set (or not asked for)
  std::string notes;           // what was refused and why, for the operator
};

// Locks the process's memory (current and future pages), so the player never waits on a
// page fault. Process-wide: done once, from start().
bool lock_memory(std::string* note);

// Puts the calling thread under SCHED_FIFO at `priority`, on `cpu` when >= 0, and touches
// its stack so the pages are resident before the first tick.
void make_thread_realtime(int priority, int cpu, RealtimeResult& result);

}  // namespace gantry
