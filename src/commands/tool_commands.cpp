// Tools commands, TC to TU: SB3's "virtual tools", each a separate program with its own
// screens. Gantry's drill press (TD), fluter (TF) and tabletop surfacer (TU) take their
// values as parameters and write a part file, which the operator checks and runs with FP;
// the header writer (TH) adds a comment header to a part file; setup (TS) prints the machine
// profile; the typesetter (TT) writes a part file that engraves text in Gantry's own
// single-stroke font; the copy machine (TC) probes a grid and writes what it found; the
// indexer (TI) writes a part file that runs another at each turn of a rotary axis.
#include <algorithm>  // sort
#include <cstddef>    // ptrdiff_t
#include <vector>

#include "gantry/commands/command_table.hpp"
#include "tool_commands.hpp"  // the families

namespace gantry {

// The tools by family (tool_commands_<family>.cpp), listed by code as SB3's menu lists them.
void add_tool_commands(std::vector<CommandSpec>& out) {
  const size_t first = out.size();
  tools::add_machining_tools(out);
  tools::add_text_tools(out);
  tools::add_file_tools(out);
  tools::add_machine_tools(out);
  std::sort(out.begin() + static_cast<std::ptrdiff_t>(first), out.end(),
            [](const CommandSpec& a, const CommandSpec& b) { return a.code < b.code; });
}

}  // namespace gantry
