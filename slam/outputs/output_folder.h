// Output locations are checked before any work (docs/refusals.md): an output
// that cannot be written is bad input (InputError, exit 3) naming the path; a write that
// fails later (disk full) is an I/O failure (exit 1) naming the path and the cause.
#pragma once

#include <string>
#include <vector>

namespace uwbsar::slam {

/// Creates `dir` (and parents) if needed and checks that a file can be created in it.
void EnsureDirectory(const std::string& dir);
/// The same check without creating anything: `dir` is a writable folder, or could be created
/// (its nearest existing ancestor is a writable folder).
void CheckOutputFolder(const std::string& dir);
/// `path` is not a folder, its folder exists and a file can be created in it.
void CheckOutputFile(const std::string& path);

/// Something a command reads, as RefuseOutputOnInput names it.
struct CommandInput {
  std::string what;  ///< e.g. "the input bag", "the --config file"
  std::string path;
  /// A saved session's folder: the output may be a folder inside it (`--out DIR/localize`,
  /// which the map-folder refusal suggests), never the folder itself.
  bool may_hold_output = false;
};

/// Refuses (InputError, one line naming both) an output `path`, given as `option` (e.g.
/// "--out"), that is or lies inside one of `inputs` (but see may_hold_output):
/// writing there would replace or remove what the command reads, such as a recording's
/// ground_truth.tum. Paths are compared canonical (links resolved; a path yet to be created
/// through its nearest existing folder). Creates nothing; empty paths are skipped.
void RefuseOutputOnInput(const std::string& option, const std::string& path,
                         const std::vector<CommandInput>& inputs);

}  // namespace uwbsar::slam
