// File commands: FP runs another part file as a subroutine; FS sets the parts folder FP's
// relative names are found in; FE opens a file in the operator's editor; FC converts a
// drawing (HP-GL, DXF) into a part file.
#include <fmt/format.h>  // messages

#include <algorithm>   // replace, all_of
#include <cerrno>      // EINTR
#include <cmath>       // round
#include <filesystem>  // FS's folder, FC's names

#include "gantry/commands/command_table.hpp"
#include "gantry/convert/to_sbp.hpp"  // hpgl_to_sbp, dxf_to_sbp
#include "gantry/core/text.hpp"       // lower
#include "gantry/interp/command_context.hpp"
#include "gantry/interp/file_reach.hpp"           // FileAccess
#include "gantry/interp/interpreter_options.hpp"  // InterpreterOptions
#include "gantry/lang/scan.hpp"                   // upper, is_word

#include <spawn.h>     // posix_spawnp: FE's editor, without a shell
#include <sys/wait.h>  // waitpid, WEXITSTATUS
#include <unistd.h>    // isatty

extern char** environ;  // the editor's environment: Gantry's own

namespace gantry {
namespace {

// Parameter i, a file or folder name. A bare `&name` never assigned reads as its own name,
// which as a file name is always a mistake: it is refused where it is written.
std::optional<std::string> file_name(const CommandContext& ctx, const CommandCall& call, size_t i) {
  const std::string text = i < call.args.size() ? call.args[i].text : "";
  if (text.size() > 1 && text[0] == '&' &&
      std::all_of(text.begin() + 1, text.end(), scan::is_word)) {
    const std::string name = scan::upper(text.substr(1));
    const auto vars = ctx.variables();
    if (std::none_of(vars.begin(), vars.end(), [&](const auto& v) { return v.first == name; }))
      fail(call.args[i].loc, fmt::format("undefined variable &{}; set it before this line", name));
  }
  return call.text(i);
}

// A name with no extension is a part file's, as SB3 takes it: `FP, sub` runs sub.sbp.
std::string part_file_name(const std::string& name) {
  std::string unix_name = name;
  std::replace(unix_name.begin(), unix_name.end(), '\\', '/');  // written on Windows
  return std::filesystem::path(unix_name).has_extension() ? name : name + ".sbp";
}

// FP's nine parameters (FG's first nine).
FileCall file_call(const CommandContext& ctx, const CommandCall& call) {
  FileCall fc;
  fc.path = part_file_name(*file_name(ctx, call, 0));
  fc.proportion[0] = *call.number(1);
  fc.proportion[1] = *call.number(2);
  fc.proportion[2] = *call.number(3);
  for (size_t i = 1; i <= 3; ++i)
    if (!(*call.number(i) > 0))
      fail(call.param_loc(i), "FP proportions must be above 0 (1 keeps the file's size)");
  const double reps = *call.number(4);
  if (reps != std::round(reps) || reps < 1 || reps > 1e6)
    fail(call.param_loc(4), "FP repetitions must be a whole number, 1 or more");
  fc.repetitions = static_cast<int>(reps);
  const double offset = *call.number(5);
  if (offset != 0 && offset != 1 && offset != 2)
    fail(call.param_loc(5), "FP offset is 0 (none), 1 (3D: X, Y, Z from here) or 2 (2D)");
  fc.offset = static_cast<int>(offset);
  fc.plunge = *call.number(6);
  fc.tabs = *call.number(7) != 0;
  fc.from_zero = *call.number(8) != 0;
  return fc;
}

void file_part(CommandContext& ctx, const CommandCall& call) {
  ctx.call_file(file_call(ctx, call), call.loc);
}

// FG: FP from a chosen line; the lines before it run without motion, then the tool comes
// to where they leave it (docs/language.md, "Starting at a line").
// FG: with no start line, the line where the last run of that file stopped (after a broken
// bit, say), else its first.
void file_goto(CommandContext& ctx, const CommandCall& call) {
  FileCall fc = file_call(ctx, call);
  fc.start_loc = call.param_loc(9);
  if (const std::optional<double> line = call.number(9)) {
    fc.start_line = static_cast<int>(*line);
  } else if (SourceLoc& stop = ctx.last_stop(); stop.file && stop.line > 0) {
    std::error_code a, b;
    const auto here = std::filesystem::weakly_canonical(ctx.file_path(fc.path, call.loc), a);
    if (!a && here == std::filesystem::weakly_canonical(*stop.file, b) && !b) {
      fc.start_line = stop.line;
      ctx.print(
          fmt::format("FG: from line {}, where the last run of {} stopped\n", stop.line, fc.path));
      stop = {};  // once
    }
  }
  ctx.call_file(fc, call.loc);
}

std::vector<ParamSpec> part_params() {
  return {
      {"file name", "", true, std::nullopt,
       "The part file (.sbp when the name has none); a relative name is found in the parts "
       "folder (the top-level file's), regardless of case when the exact name is missing.",
       ParamKind::Text},
      {"proportion X", "", false, 1.0, "Scale of X."},
      {"proportion Y", "", false, 1.0, "Scale of Y."},
      {"proportion Z", "", false, 1.0, "Scale of Z."},
      {"repetitions", "", false, 1.0, "How many times the file runs."},
      {"offset", "", false, 0.0, "0 none; 1 3D: X, Y, Z start from here; 2 2D: X, Y from here."},
      {"plunge", "units", false, 0.0,
       "Z change of each repetition, the first included (negative goes down)."},
      ParamSpec{"tab feature", "", false, 0.0,
                "1 leaves tabs (VB's sizes) on the cutting moves of the last repetition, "
                "and in the files it calls."}
          .integer(0, 1),
      ParamSpec{"plunge from Z 0", "", false, 0.0,
                "1 first moves Z to 0 and takes the plunges from there."}
          .integer(0, 1)};
}

// ---- FS -------------------------------------------------------------------------------------

// FS: a relative folder is found from the current parts folder ("..", a subfolder), so a
// part file can move down into a folder of sub-files and back.
void file_set_folder(CommandContext& ctx, const CommandCall& call) {
  std::string folder = ctx.top_folder();
  if (const std::optional<std::string> name = file_name(ctx, call, 0)) {
    std::filesystem::path p =
        std::filesystem::path(ctx.reachable_path(*name, call.param_loc(0), FileAccess::Read))
            .lexically_normal();
    folder = p.string();
    while (folder.size() > 1 && folder.back() == '/') folder.pop_back();
    std::error_code ec;
    if (!std::filesystem::is_directory(folder.empty() ? "." : folder, ec))
      fail(call.param_loc(0),
           fmt::format("FS: there is no folder {}; the parts folder stays {}", folder,
                       ctx.parts_folder().empty() ? "the working directory" : ctx.parts_folder()));
  }
  ctx.set_parts_folder(folder, call.text(1).value_or("*.sb?"));
}

// ---- FE -------------------------------------------------------------------------------------

// Runs `words` (a program found on PATH and its arguments) with no shell between, and waits:
// its exit status, 127 when it could not be started, -1 when it did not exit.
int run_program(const std::vector<std::string>& words) {
  std::vector<char*> argv;
  for (const std::string& w : words) argv.push_back(const_cast<char*>(w.c_str()));
  argv.push_back(nullptr);
  pid_t pid = 0;
  if (::posix_spawnp(&pid, argv[0], nullptr, nullptr, argv.data(), environ) != 0) return 127;
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0)
    if (errno != EINTR) return -1;
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

void file_edit(CommandContext& ctx, const CommandCall& call) {
  const std::optional<std::string> name = file_name(ctx, call, 0);
  const std::string path =
      name ? ctx.reachable_path(*name, call.param_loc(0), FileAccess::Write) : ctx.last_file();
  if (name) ctx.set_last_file(path);
  const EditorChoice editor = editor_choice(ctx);
  const std::string& program = editor.text;
  const InterpreterOptions& o = ctx.options();
  // An editor needs a person at a terminal; a check or a preview starts nothing.
  const char* why = o.dry_run             ? "a check or a preview starts no program"
                    : !o.operator_present ? "nobody is at a terminal to edit"
                    : !isatty(STDIN_FILENO) || !isatty(STDOUT_FILENO)
                        ? "there is no terminal to edit in"
                        : nullptr;
  const std::string what = path.empty() ? "a new file" : path;
  if (why) {
    ctx.print(fmt::format("FE would open {} in {}; {}\n", what, program, why));
    return;
  }
  ctx.come_to_rest(call.loc);  // the machine waits while the operator edits
  std::vector<std::string> words = editor.words;
  if (!path.empty()) words.push_back(path);  // one argument, whatever its characters
  const int rc = words.empty() ? 127 : run_program(words);
  if (rc != 0)
    ctx.warn(call.loc, fmt::format("FE: {} {}; the part file continues", program,
                                   rc == 127 ? "could not be started (is it installed? the machine "
                                               "profile's [machine] editor names the editor)"
                                             : fmt::format("exited with status {}", rc)));
}

// ---- FC -------------------------------------------------------------------------------------

enum class Drawing { HpGl, Dxf, GCode, Raster, Unknown };

Drawing kind_of(const std::string& name) {
  const std::string ext = ascii::lower(std::filesystem::path(name).extension().string());
  if (ext == ".plt" || ext == ".hpg" || ext == ".hpgl" || ext == ".hgl") return Drawing::HpGl;
  if (ext == ".dxf") return Drawing::Dxf;
  if (ext == ".nc" || ext == ".tap" || ext == ".ngc" || ext == ".gcode" || ext == ".cnc" ||
      ext == ".g")
    return Drawing::GCode;
  if (ext == ".bmp" || ext == ".jpg" || ext == ".jpeg" || ext == ".png" || ext == ".gif" ||
      ext == ".tif" || ext == ".tiff")
    return Drawing::Raster;
  return Drawing::Unknown;
}

enum Fc { kFcFile, kFcPart, kFcCutZ, kFcSafeZ, kFcScale };

void file_convert(CommandContext& ctx, const CommandCall& call) {
  const std::string name = *file_name(ctx, call, kFcFile);
  const SourceLoc& at = call.param_loc(kFcFile);
  const Drawing kind = kind_of(name);
  if (kind == Drawing::GCode)
    fail(at, fmt::format("FC: {} is a G-code file; there is nothing to convert: FP runs G-code "
                         "files directly (docs/gcode.md). Nothing was done",
                         name));
  if (kind == Drawing::Raster)
    fail(at, fmt::format("FC: {} is a raster image; converting an image's grey levels into "
                         "heights is not offered by Gantry: make the toolpath with CAM "
                         "software and run its part file with FP. Nothing was done",
                         name));
  if (kind == Drawing::Unknown)
    fail(at, fmt::format("FC: {} has no extension FC converts: .dxf (DXF) or .plt, .hpg "
                         "(HP-GL); rename the file if it is one of those. Nothing was done",
                         name));
  std::string path;
  const std::optional<std::string> text = ctx.read_file(name, at, &path);
  if (!text) fail(at, fmt::format("FC: cannot read {}", path));
  ConvertOptions o;
  o.source = name;
  o.units = ctx.settings().units;
  o.cut_z = *call.number(kFcCutZ);
  o.safe_z = call.number(kFcSafeZ).value_or(ctx.settings().cutter.safe_z);
  if (!(o.safe_z > o.cut_z))
    fail(call.param_loc(kFcSafeZ),
         fmt::format("FC: safe Z {} is not above the cutting Z {}; the jogs between paths "
                     "would go through the material",
                     format_number(o.safe_z), format_number(o.cut_z)));
  o.scale = call.number(kFcScale).value_or(0);
  Conversion c;
  try {
    c = kind == Drawing::Dxf ? dxf_to_sbp(*text, o) : hpgl_to_sbp(*text, o);
  } catch (const GantryError& e) {
    Diagnostic d = e.diagnostic();  // located in the drawing; the FC line leads to it
    if (d.via.empty()) d.via.push_back(call.loc);
    throw GantryError(std::move(d));
  }
  const std::string part =
      call.text(kFcPart).value_or(std::filesystem::path(name).replace_extension(".sbp").string());
  if (ctx.file_path(part, call.param_loc(kFcPart)) == path)
    fail(call.param_loc(kFcPart),
         "FC: the part file would overwrite the drawing; give another name");
  for (const std::string& n : c.notes)
    ctx.warn(call.loc, fmt::format("FC: not converted from {}: {}", name, n));
  if (c.paths == 0) ctx.warn(call.loc, fmt::format("FC: {} holds nothing to cut", name));
  const std::string written = ctx.write_file(part, c.text, call.param_loc(kFcPart));
  ctx.print(fmt::format("FC converted {} ({}) into {} path{} in {}; run it with FP, {}\n", name,
                        kind == Drawing::Dxf ? "DXF" : "HP-GL", c.paths, c.paths == 1 ? "" : "s",
                        written, part));
}

ParamSpec text(std::string_view name, std::string_view help, bool required = false) {
  return {name, "", required, std::nullopt, help, ParamKind::Text};
}

}  // namespace

void add_file_commands(std::vector<CommandSpec>& out) {
  const auto F = CommandGroup::File;
  out.push_back({"FP", "File: run a part file", F,
                 "Runs another part file, then continues on the next line. Variables are "
                 "shared; the file may be scaled, repeated a plunge deeper each time, placed "
                 "relative to the current position, and tabbed on its last repetition.",
                 part_params(), file_part});
  std::vector<ParamSpec> goto_params = part_params();
  goto_params.push_back(ParamSpec{"start line", "", false, std::nullopt,
                                  "Gantry's: the first line of the file to run (blank: the "
                                  "line where the last run of that file stopped, else 1). The "
                                  "lines before it set variables, modes and the location "
                                  "without moving; then the tool goes there by Safe-Z."}
                            .integer(1, 1e9));
  out.push_back(
      {"FG", "File: run a part file from a line", F,
       "Runs a part file as FP does, starting at a chosen line: the lines before it run without "
       "motion, output or questions, the tool then rises to Safe-Z, crosses to where those lines "
       "leave it and goes down there, and the file runs on from that line.",
       goto_params, file_goto,
       "FG runs on from the line: stepping line by line is the controller's single step "
       "(the console's `step`, the window's Single step), which FG does not turn on"});
  out.push_back(
      {"FS",
       "File: set the parts folder",
       F,
       "Sets the folder FP (and every command that reads or writes a file) finds relative "
       "names in, for the rest of the run. A relative folder is taken from the current parts "
       "folder, so `FS, sub` and later `FS, ..` move down and back. Blank: the top-level "
       "file's folder again.",
       {text("folder", "Absolute, or relative to the parts folder (blank: the top-level file's)."),
        text("mask", "File selector mask, shown by UV (blank: *.sb?).")},
       file_set_folder,
       "the mask filters nothing: Gantry has no file selector (UV shows it)"});
  out.push_back(
      {"FE",
       "File edit",
       F,
       "Opens a file in the editor the machine profile names ([machine] editor; else $VISUAL, "
       "$EDITOR, or vi), started without a shell, and waits for it to close; a part file then "
       "continues. Blank: the last file loaded (the running file, FP's "
       "or FE's). A check or a preview, or a run with nobody at a terminal, starts nothing and "
       "prints what FE would open.",
       {text("file name", "The file to edit (blank: the last one loaded).")},
       file_edit});
  out.push_back(
      {"FC",
       "File conversion",
       F,
       "Converts a drawing into a part file of M2 lines and CG arcs, cut at one Z with jogs at "
       "safe Z between paths: HP-GL (.plt, .hpg: IN, PU, PD, PA, PR, SP) and DXF (LINE, ARC, "
       "CIRCLE, LWPOLYLINE, POLYLINE with bulges). What is left out is named in warnings. "
       "G-code needs no conversion; raster images are not offered.",
       {text("file name", "The drawing; a relative name is found in the parts folder.", true),
        text("part file", "The part file to write (blank: the drawing's name with .sbp)."),
        {"cut Z", "units", false, 0.0, "Z of the cutting moves; FP's plunge cuts deeper passes."},
        {"safe Z", "units", false, std::nullopt,
         "Z of the jogs between paths, above cut Z (blank: the profile's safe Z, VC)."},
        ParamSpec{"scale", "", false, std::nullopt,
                  "Part-file units per drawing unit (blank: from the drawing: HP-GL 0.025 mm; "
                  "DXF $INSUNITS, else 1)."}
            .at_least(1e-9)},
       file_convert,
       "raster images, HP-GL's arcs, circles and labels, and DXF's other entities (SPLINE, "
       "ELLIPSE, TEXT, INSERT...)"});
}

}  // namespace gantry
