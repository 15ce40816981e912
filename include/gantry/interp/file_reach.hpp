// A part file's reach: the folders its file statements and commands may read and write
// (docs/security.md). The interpreter asks it at the one place every file name a part file
// gives is resolved, so a check refuses exactly what a run would.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace gantry {

enum class FileAccess { Read, Write };

// Besides the job's folder (the running part file's; for typed lines, the working directory).
struct FileReach {
  std::vector<std::string> read_write;  // the Gantry data folder, the operator's allowed folders
  std::vector<std::string> read_only;   // the macro folders C<n> looks in
};

// `path` made absolute with `..` and every symbolic link resolved, a dangling one (whose
// target does not exist yet, and which writing would create) included.
std::filesystem::path resolved_path(const std::string& path);

// "" when `path` resolves inside `job_folder` or a folder of `reach` that allows `access`;
// else why not, and how the operator allows it.
std::string reach_refusal(const std::string& path, FileAccess access, const std::string& job_folder,
                          const FileReach& reach);

}  // namespace gantry
