// Output locations are checked before any work (docs/refusals.md): an output
// that cannot be written is bad input (InputError, exit 3) naming the path; a write that
// fails later (disk full) is an I/O failure (exit 1) naming the path and the cause.
#pragma once

#include <string>

namespace uwbsar::slam {

/// Creates `dir` (and parents) if needed and checks that a file can be created in it.
void EnsureDirectory(const std::string& dir);
/// The same check without creating anything: `dir` is a writable folder, or could be created
/// (its nearest existing ancestor is a writable folder).
void CheckOutputFolder(const std::string& dir);
/// `path` is not a folder, its folder exists and a file can be created in it.
void CheckOutputFile(const std::string& path);

}  // namespace uwbsar::slam
