// Tool changes on the machine: the rack's automatic sequence and the tool-length sensor
// (docs/hardware.md, "Tool changer"; the profile's [toolchanger]). G-code's M6 and OpenSBP's
// C9 run them; the lengths measured go to the tool table G43 reads.
#pragma once

#include <optional>

#include "gantry/core/diagnostic.hpp"  // SourceLoc

namespace gantry {

class CommandContext;

// Refuses, at `loc` and before anything moves, a change from tool `from` to tool `to` that
// the rack cannot make (a tool with no slot, a place outside the soft limits, a sensor
// measure with no tool table line to write), so that a refused change moves nothing.
void check_tool_change(CommandContext& ctx, int from, int to, const SourceLoc& loc);

// Refuses, at `loc` and before anything moves, a measure of tool `tool` (in the spindle) on
// the sensor that cannot be made: no sensor in the profile, no tool in the spindle, no tool
// table line to write (`writes_table`), the sensor's places outside the soft limits. `code`
// names the command for the messages ("G37").
void check_tool_measure(CommandContext& ctx, int tool, const char* code, const SourceLoc& loc,
                        bool writes_table);

// A measure of the tool in the spindle on the sensor, with no change (G37, M37 alone on a
// machine with a sensor): refused as check_tool_measure refuses, then measure_tool and back
// over the X, Y where it began. nullopt: a check or a preview (nothing measured).
std::optional<double> measure_tool_in_spindle(CommandContext& ctx, const char* code,
                                              const SourceLoc& loc);

// The rack's sequence: the spindle stops (its spin-down wait), Z rises to clear_z, tool
// `from` goes back to its slot (down to slot_z, the drawbar opens, up), tool `to` is picked
// from its (the drawbar opens, down, it closes, up). The tool in the spindle
// (ModalState::gcode.tool) follows each step. Ends at clear_z over tool `to`'s slot.
void rack_tool_change(CommandContext& ctx, int from, int to, const SourceLoc& loc);

// With a tool-length sensor in the profile: Z at clear_z, to the sensor, down to
// sensor_start_z, then a probe down to sensor_min_z; the length (the Z where it closed less
// sensor_zero_z) becomes tool `tool`'s Z in the tool table (written back to its file), and Z
// rises to clear_z again. nullopt: no sensor, or no live machine (a check measures nothing).
// The sensor not closing is an error at `loc` that stops the job.
std::optional<double> measure_tool(CommandContext& ctx, int tool, const SourceLoc& loc);

// The sensor's probe alone: Z at clear_z, over the sensor, down to sensor_start_z, then the
// probe; the table base Z where the sensor closed (the tool left there), nullopt with no live
// machine. The sensor not closing is an error at `loc` naming tool `tool`.
std::optional<double> sensor_trip_z(CommandContext& ctx, int tool, const SourceLoc& loc);

// WinCNC's M37.1 alone: the tool in the spindle, whose length (G43's) is `length`, is probed
// on the sensor and the machine returns; the sensor_zero_z that makes the sensor measure
// that length (the trip less `length`), nullopt with no live machine. Refused before
// anything moves as check_tool_measure refuses (no tool table line needed).
std::optional<double> calibrate_sensor(CommandContext& ctx, double length, const char* code,
                                       const SourceLoc& loc);

// Back over the table base X, Y where a change began, at clear_z.
void return_from_change(CommandContext& ctx, double x, double y, const SourceLoc& loc);

// OpenSBP's C9 on a machine with a rack: the whole change to tool `to` (refused before
// anything moves as check_tool_change refuses), its measure, and back. OpenSBP has no G43:
// with the sensor, working Z's zero follows the new tool's length (it moves by the new
// length less the old one's, as the tool table gives them), so Z 0 stays on the material.
void opensbp_rack_change(CommandContext& ctx, int to, const SourceLoc& loc);

}  // namespace gantry
