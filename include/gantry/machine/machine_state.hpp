// The controller's states and the operator's requests, and the one table that says which
// request each state accepts, what it leads to, and why a refused one is refused.
#pragma once

#include <optional>
#include <string>
#include <string_view>

namespace gantry {

enum class MachineState {
  Idle,      // at rest, ready
  Running,   // a part file runs
  Paused,    // a part file is held (slowing to rest, then at rest) until resume or stop
  Stopping,  // slowing to rest to end what runs; the position is known once at rest
  Stopped,   // a file ended by a stop or a fault, with the line it stopped at
  EStop,     // pulses stopped at once; nothing moves until it is acknowledged
  Jogging,   // a keypad jog, continuous or a fixed step
  Homing,    // a part file (or C3) runs its homing moves towards the proximity switches
  Probing,   // a part file runs a probe move (P*), watching its input
  Keypad,    // a part file waits at SK while the operator jogs; resume closes the keypad
};

enum class Request { Run, Pause, Resume, Stop, EStop, Acknowledge, Jog, JogRelease };

inline constexpr int kMachineStates = 10;
inline constexpr int kRequests = 8;

const char* state_name(MachineState s);
const char* request_name(Request r);

// The state a request leads to, or the reason it is refused in `s`.
struct Verdict {
  std::optional<MachineState> next;
  std::string_view refusal;
};
Verdict decide(MachineState s, Request r);

// The table as Markdown (docs/controller.md holds a copy; a test keeps them equal).
std::string transition_table_markdown();

}  // namespace gantry
