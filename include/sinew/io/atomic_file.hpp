#pragma once
// Output files appear whole or not at all: content goes to a temporary file in the target's
// directory, which replaces the target by rename(2) only after every byte reached the disk.
#include <filesystem>
#include <functional>
#include <ostream>

namespace sinew {

// Runs `writer` on a stream into a fresh temporary file next to `path`, flushes and fsyncs
// it, then renames it over `path` (inside a DeferredSync::Scope, io/deferred_sync.hpp, the
// fsync is left to the batch's sync()). On any failure (missing directory, permission denied,
// disk full, a stream error or an exception from `writer`) the temporary file is removed,
// an existing `path` is left untouched, and a sinew::Error names `path` and the reason.
void write_file_atomically(const std::filesystem::path& path,
                           const std::function<void(std::ostream&)>& writer);

// Gives the whole file `existing` the name `path` as well (a hard link made under a temporary
// name, then renamed over `path`, so `path` changes at once), for output identical to a file
// already written: no bytes to write or sync again. Inside a DeferredSync::Scope the folder is
// synced with the batch. Returns false, changing nothing, when the link cannot be made (a file
// system without hard links, `existing` gone); a sinew::Error names `path` when the rename fails.
bool link_file_atomically(const std::filesystem::path& existing, const std::filesystem::path& path);

// Removes the temporary files that writes into `dir` left behind when their process was killed
// mid-write: names of the form .NAME.tmp-PID-N (this module's own) whose PID no longer runs, or
// is this process's (call it before this process writes into `dir`). Other files are never
// touched. Returns how many it removed; a sinew::Error names a file it cannot remove.
int remove_stale_temporary_files(const std::filesystem::path& dir);

// Creates `dir` and its missing parents; a sinew::Error names `dir` when it cannot be
// created or exists as something other than a directory.
void ensure_directory(const std::filesystem::path& dir);

}  // namespace sinew
