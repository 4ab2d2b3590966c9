// Atomic replacement of a file, for every output Glint writes (images, projects): the bytes go
// to a temporary file beside the target, every write, the fsync and the close are checked, and
// only a complete file is renamed over the target. On any failure the temporary file is
// removed and the old file stays as it was.
//  - A file the user named (an image, a project) may be a symbolic link to a regular file: it
//    is written through (the final target of the link chain is replaced, the links stay). A
//    link to, or a file that is, a device, FIFO, socket or folder is refused: nothing is ever
//    renamed over a file that is not regular.
//  - Glint's own files (caches, the editor's state, farm scripts and plans) are never written
//    through a link: write_state_file_atomically refuses a path that is a link or any other
//    non-regular file, so a link planted at such a path cannot redirect the write.
//  - An existing target keeps its permission bits (and, best effort, its owner and group); a
//    new file gets 0666 minus the umask, as any program creating a file.
//  - Temporary names are unique and of a fixed short length (".glint-XXXXXXXX.tmp", created
//    with O_EXCL), so concurrent saves of one file all succeed (the last rename wins) and any
//    target name the file system allows also has room for its temporary file.
#pragma once

#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>

namespace glint {

// what() reads "FILE: PROBLEM" (FILE as the caller named it); `problem` alone, for callers
// with their own error type.
struct FileWriteError : std::runtime_error {
  FileWriteError(const std::filesystem::path& file, std::string problem);
  std::string problem;
};

// Replaces `file`, a file the user named, with `size` bytes from `data` as described above.
// Throws FileWriteError with the OS reason (e.g. "cannot write: No space left on device").
void write_file_atomically(const std::filesystem::path& file, const void* data, size_t size);

// The same for one of Glint's own files: refused (FileWriteError) where `file` is a symbolic
// link, a folder, a device, a FIFO or a socket.
void write_state_file_atomically(const std::filesystem::path& file, const void* data, size_t size);

// The problem that would stop write_file_atomically from writing `file`, found without
// touching the target: a folder that does not exist or is not writable (with the OS reason,
// e.g. "Read-only file system"; checked by creating and removing a temporary file there), a
// name too long for the file system, a target that is a folder, a device, a FIFO or a socket.
// nullopt when writable. For
// commands that should fail before spending minutes on a render.
std::optional<std::string> file_write_problem(const std::filesystem::path& file);

// What a file of this st_mode is, for messages: "a FIFO", "a character device", "a folder",
// "a symbolic link" (from lstat)...; "" for a regular file.
std::string non_regular_kind(unsigned mode);

// The file that writing `file` replaces: `file` itself, or the final target of the chain of
// symbolic links it names (which need not exist yet). Throws FileWriteError for a loop.
std::filesystem::path write_target(const std::filesystem::path& file);

}  // namespace glint
