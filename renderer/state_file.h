// Glint's own files (the back-end cache, the editor's settings, layout, recent files and
// recovery files, a farm's plan), read as untrusted input: another program or user may have put
// anything at their paths. Only a regular file is read (a FIFO would block the reader, a device
// would never end), at most a given size, with every read error reported. Writing them is
// write_state_file_atomically (renderer/atomic_file.h), which never writes through a link.
#pragma once

#include <cstddef>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>

namespace glint {

// No state file of Glint's is near this size; a larger one is not Glint's.
constexpr size_t kMaxStateFileBytes = size_t(16) << 20;

// what() reads "FILE: PROBLEM"; `problem` alone for callers that phrase their own message.
struct StateFileError : std::runtime_error {
  StateFileError(const std::filesystem::path& file, std::string problem);
  std::string problem;
};

// The contents of `file`, or nullopt where nothing is there. Throws StateFileError for a file
// that is not regular (naming what it is), larger than `max_bytes`, or unreadable.
std::optional<std::string> read_state_file(const std::filesystem::path& file,
                                           size_t max_bytes = kMaxStateFileBytes);

// `text` as `file`'s new contents (write_state_file_atomically). Throws FileWriteError.
void write_state_file(const std::filesystem::path& file, const std::string& text);

}  // namespace glint
