// SCHED_FIFO, affinity and mlockall for the feeder thread.
#include "pci7200/realtime_thread.hpp"

#include <fmt/format.h>
#include <pthread.h>
#include <sched.h>
#include <sys/mman.h>

#include <algorithm>
#include <cerrno>
#include <cstring>

namespace gantry::pci7200 {

std::string make_current_thread_realtime(const RealtimeRequest& request) {
  std::string report;
  auto add = [&report](const std::string& part) {
    if (!report.empty()) report += ", ";
    report += part;
  };
  if (request.priority > 0) {
    sched_param param{};
    param.sched_priority = std::clamp(request.priority, sched_get_priority_min(SCHED_FIFO),
                                      sched_get_priority_max(SCHED_FIFO));
    const int rc = pthread_setschedparam(pthread_self(), SCHED_FIFO, &param);
    if (rc == 0)
      add(fmt::format("SCHED_FIFO priority {}", param.sched_priority));
    else
      add(
          fmt::format("normal scheduling (SCHED_FIFO refused: {}; run as root, grant "
                      "CAP_SYS_NICE, or raise the rtprio limit)",
                      std::strerror(rc)));
  } else {
    add("normal scheduling");
  }
  if (request.cpu >= 0) {
    cpu_set_t set;
    CPU_ZERO(&set);
    CPU_SET(request.cpu, &set);
    const int rc = pthread_setaffinity_np(pthread_self(), sizeof(set), &set);
    if (rc == 0)
      add(fmt::format("on CPU {}", request.cpu));
    else
      add(fmt::format("on any CPU (CPU {} refused: {})", request.cpu, std::strerror(rc)));
  }
  if (request.lock_memory) {
    if (mlockall(MCL_CURRENT | MCL_FUTURE) == 0)
      add("memory locked");
    else
      add(
          fmt::format("memory not locked (mlockall: {}; raise `ulimit -l` or grant "
                      "CAP_IPC_LOCK)",
                      std::strerror(errno)));
  }
  return report;
}

}  // namespace gantry::pci7200
