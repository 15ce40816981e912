// The transition table: each state's answer to each request.
#include "gantry/machine/machine_state.hpp"

#include <fmt/format.h>

#include <array>

namespace gantry {
namespace {

using S = MachineState;

constexpr Verdict go(S s) {
  return {s, {}};
}
constexpr Verdict no(std::string_view why) {
  return {std::nullopt, why};
}

// Rows: states in enum order; columns: requests in enum order
// (Run, Pause, Resume, Stop, EStop, Acknowledge, Jog, JogRelease).
constexpr Verdict kIdleLike[kRequests] = {
    go(S::Running),
    no("nothing is running"),
    no("nothing is paused"),
    no("nothing is moving"),
    go(S::EStop),
    no("there is no E-stop to acknowledge"),
    go(S::Jogging),
    no("no jog is running"),
};

const std::array<std::array<Verdict, kRequests>, kMachineStates> kTable = {{
    // Idle
    {kIdleLike[0], kIdleLike[1], kIdleLike[2], kIdleLike[3], kIdleLike[4], kIdleLike[5],
     kIdleLike[6], kIdleLike[7]},
    // Running
    {no("a file is running"), go(S::Paused), no("the file is running, not paused"), go(S::Stopping),
     go(S::EStop), no("there is no E-stop to acknowledge"),
     no("a file is running: pause or stop it first"), no("no jog is running")},
    // Paused
    {no("a file is paused: resume it or stop it first"), no("the file is paused already"),
     go(S::Running), go(S::Stopping), go(S::EStop), no("there is no E-stop to acknowledge"),
     no("a file is paused: resume it or stop it first"), no("no jog is running")},
    // Stopping
    {no("stopping: wait until the tool is at rest"), no("stopping: wait until the tool is at rest"),
     no("stopping: wait until the tool is at rest"), no("stopping already"), go(S::EStop),
     no("there is no E-stop to acknowledge"), no("stopping: wait until the tool is at rest"),
     no("no jog is running")},
    // Stopped: as Idle
    {kIdleLike[0], kIdleLike[1], kIdleLike[2], kIdleLike[3], kIdleLike[4], kIdleLike[5],
     kIdleLike[6], kIdleLike[7]},
    // EStop
    {no("E-stop: acknowledge it first"), no("E-stop: acknowledge it first"),
     no("E-stop: acknowledge it first"), no("E-stop: nothing is moving"), go(S::EStop), go(S::Idle),
     no("E-stop: acknowledge it first"), no("E-stop: acknowledge it first")},
    // Jogging
    {no("a jog is running: release the key first"), no("a jog is running: release the key first"),
     no("a jog is running: release the key first"), go(S::Stopping), go(S::EStop),
     no("there is no E-stop to acknowledge"), no("a jog is running: release the key first"),
     go(S::Idle)},
    // Homing, Probing: a file runs, as Running
    {},
    {},
    // Keypad: the file waits at SK; the operator jogs, then resumes it
    {no("a file waits at SK: close the keypad (resume) or stop the file first"),
     no("the file waits at SK already"), go(S::Running), go(S::Stopping), go(S::EStop),
     no("there is no E-stop to acknowledge"), go(S::Jogging), no("no jog is running")},
}};

}  // namespace

const char* state_name(MachineState s) {
  static const char* const names[] = {"idle",  "running", "paused", "stopping", "stopped",
                                      "estop", "jogging", "homing", "probing",  "keypad"};
  return names[static_cast<int>(s)];
}

const char* request_name(Request r) {
  static const char* const names[] = {"run",   "pause",       "resume", "stop",
                                      "estop", "acknowledge", "jog",    "jog release"};
  return names[static_cast<int>(r)];
}

Verdict decide(MachineState s, Request r) {
  if (s == S::Homing || s == S::Probing) s = S::Running;
  return kTable[static_cast<int>(s)][static_cast<int>(r)];
}

std::string transition_table_markdown() {
  std::string out = "| State |";
  for (int r = 0; r < kRequests; ++r) out += fmt::format(" {} |", request_name(Request(r)));
  out += "\n|---|";
  for (int r = 0; r < kRequests; ++r) out += "---|";
  out += "\n";
  for (int s = 0; s < kMachineStates; ++s) {
    out += fmt::format("| **{}** |", state_name(MachineState(s)));
    for (int r = 0; r < kRequests; ++r) {
      const Verdict v = decide(MachineState(s), Request(r));
      out += v.next ? fmt::format(" -> {} |", state_name(*v.next))
                    : fmt::format(" refused: {} |", v.refusal);
    }
    out += "\n";
  }
  return out;
}

}  // namespace gantry
