#pragma once
// Output files appear whole or not at all: content goes to a temporary file in the target's
// directory, which replaces the target by rename(2) only after every byte reached the disk.
#include <filesystem>
#include <functional>
#include <ostream>

namespace sinew {

// Runs `writer` on a stream into a fresh temporary file next to `path`, flushes and fsyncs
// it, then renames it over `path`. On any failure (missing directory, permission denied,
// disk full, a stream error or an exception from `writer`) the temporary file is removed,
// an existing `path` is left untouched, and a sinew::Error names `path` and the reason.
void write_file_atomically(const std::filesystem::path& path,
                           const std::function<void(std::ostream&)>& writer);

// Creates `dir` and its missing parents; a sinew::Error names `dir` when it cannot be
// created or exists as something other than a directory.
void ensure_directory(const std::filesystem::path& dir);

}  // namespace sinew
