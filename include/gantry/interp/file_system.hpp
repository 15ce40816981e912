// The files a run reads and writes: part files for FP and C<n>, and OPEN's user files.
#pragma once

#include <istream>
#include <map>
#include <memory>
#include <ostream>
#include <sstream>
#include <string>
#include <vector>

#include "gantry/lang/script.hpp"  // Script

namespace gantry {

class FileSystem {
 public:
  virtual ~FileSystem() = default;
  // A part file, loaded as Script::load does (`is_command` finds its unknown commands).
  virtual std::shared_ptr<const Script> load_script(const std::string& path,
                                                    const IsCommand& is_command) = 0;
  virtual bool is_file(const std::string& path) = 0;
  // A user file to read (null if it cannot be read) or to write (null if it cannot be made).
  virtual std::shared_ptr<std::istream> open_read(const std::string& path) = 0;
  virtual std::shared_ptr<std::ostream> open_write(const std::string& path, bool append) = 0;
  // Why `path` cannot be read or written as a file, "" when it can (core/file_problem.hpp):
  // asked before opening, so a check and a run refuse the same files with the same words.
  virtual std::string read_problem(const std::string& path);
  virtual std::string write_problem(const std::string& /*path*/) { return ""; }
  // The names of the files and folders in `folder` ("": the working directory); none when
  // it cannot be listed.
  virtual std::vector<std::string> list(const std::string& /*folder*/) { return {}; }
};

// A part file's path as files written on Windows name it: where `path` is missing, each
// missing part is looked up without regard to case (`MyPart.SBP` finds `mypart.sbp`). An exact
// name always wins; two names that differ only in case, and no exact one, are refused.
struct PartFileLookup {
  std::string path;   // the file found, else the path tried
  std::string error;  // why it was refused ("": found, or simply missing)
};
PartFileLookup find_part_file(FileSystem& files, const std::string& path);

// C<n>'s folders besides --macros: the operator's ($XDG_CONFIG_HOME/gantry/macros, else
// ~/.config/gantry/macros) and the macros Gantry ships (C6, C7, C9...): beside an installed
// gantry, <prefix>/share/gantry/macros, else the source tree's parts/macros.
std::string user_macro_folder();
std::string shipped_macro_folder();

// The machine's own files.
class DiskFileSystem : public FileSystem {
 public:
  std::shared_ptr<const Script> load_script(const std::string& path,
                                            const IsCommand& is_command) override;
  bool is_file(const std::string& path) override;
  std::shared_ptr<std::istream> open_read(const std::string& path) override;
  std::shared_ptr<std::ostream> open_write(const std::string& path, bool append) override;
  std::string read_problem(const std::string& path) override;
  std::string write_problem(const std::string& path) override;
  std::vector<std::string> list(const std::string& folder) override;
};

// Reads the disk (or another file system) but keeps every write in memory, where later reads find
// it: a check or a preview behaves as the run would and changes nothing on disk.
class SandboxFileSystem : public FileSystem {
 public:
  // `base`: where reads go when the sandbox has not written the file (null: the disk).
  explicit SandboxFileSystem(FileSystem* base = nullptr) : base_(base ? base : &disk_) {}
  std::shared_ptr<const Script> load_script(const std::string& path,
                                            const IsCommand& is_command) override;
  bool is_file(const std::string& path) override;
  std::shared_ptr<std::istream> open_read(const std::string& path) override;
  std::shared_ptr<std::ostream> open_write(const std::string& path, bool append) override;
  std::string read_problem(const std::string& path) override;
  std::string write_problem(const std::string& path) override;
  std::vector<std::string> list(const std::string& folder) override;

 private:
  DiskFileSystem disk_;
  FileSystem* base_;
  std::map<std::string, std::shared_ptr<std::stringstream>> written_;
};

}  // namespace gantry
