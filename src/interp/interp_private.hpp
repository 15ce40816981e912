// Interpreter internals shared by its two source files.
#pragma once

#include <array>
#include <memory>
#include <optional>

#include "gantry/interp/interpreter.hpp"

namespace gantry {

// One running file: where it is, its GOSUB returns, how its coordinates map to the machine.
struct Interpreter::Frame {
  std::shared_ptr<const Script> script;
  Cursor pc;                   // the next line to execute
  std::vector<Cursor> gosubs;  // return points
  SourceLoc called_from;       // the FP or C# line in the caller (no file for the top level)
  Transform transform;
  FileCall call;
  int repetition = 0;
  double plunge_start_z = 0;        // machine Z when FP was called, for the plunge of each pass
  SpeedSettings saved_speeds;       // at the file's start
  std::array<bool, 10> vs_owned{};  // speeds (move xy..c, jog xy..c) VS set last here
  std::optional<Settings> saved_values;  // before this file's first file-scoped change
  std::optional<Units> saved_units;      // before this file's SU
};

// A file opened with OPEN ... AS #n.
struct Interpreter::UserFile {
  int number = 0;
  OpenStmt::Mode mode = OpenStmt::Mode::Input;
  std::string path;
  std::shared_ptr<std::istream> in;
  std::shared_ptr<std::ostream> out;
};

}  // namespace gantry
