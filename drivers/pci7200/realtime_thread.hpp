// Real-time setup for the calling thread (the feeder): SCHED_FIFO priority, CPU affinity and
// locked memory, each applied when permitted and reported when refused.
#pragma once

#include <string>

namespace gantry::pci7200 {

struct RealtimeRequest {
  int priority = 0;          // SCHED_FIFO 1..99; 0 leaves the normal scheduler
  int cpu = -1;              // pin to this CPU (ideally an isolated one); -1: any
  bool lock_memory = false;  // mlockall: no page faults on the real-time path (whole process)
};

// Returns one line saying what was granted and, for what was refused, how to allow it.
std::string make_current_thread_realtime(const RealtimeRequest& request);

}  // namespace gantry::pci7200
