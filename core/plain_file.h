// uwbsar's own files inside a folder (the lock file, the commit journal) are opened only when
// they are regular files: never through a symbolic link (which could point at a saved map or
// at a file outside the folder) and never waiting on a FIFO (docs/refusals.md).
#pragma once

#include <sys/types.h>

#include <string>

namespace uwbsar {

/// What a file of mode `mode` (st_mode) is, in words: "a symbolic link", "a folder", "a FIFO",
/// "a socket", "a device" or "a regular file".
std::string FileKindName(mode_t mode);

/// Opens `path` with `flags` (O_NOFOLLOW, O_NONBLOCK and O_CLOEXEC added; a file O_CREAT makes
/// gets mode 0644) when it is, or is made, a regular file. Returns the descriptor, or -1 with
/// `*why` saying why ("is a symbolic link", "is a FIFO", or the system's reason) and `*error`
/// the errno (0 when the file is there but not a regular one).
int OpenRegularFile(const std::string& path, int flags, std::string* why, int* error);

}  // namespace uwbsar
