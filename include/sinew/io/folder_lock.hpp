#pragma once
// An exclusive lock on an output folder, so two runs writing into one folder do not mix their
// frames: flock(2) on the hidden file .sinew.lock inside it, which holds the owner's pid. The
// kernel drops the lock when the process ends however it ends (a killed run leaves no stale
// lock); a clean release also removes the file.
#include <filesystem>
#include <string>

namespace sinew {

class FolderLock {
 public:
  // Locks the existing folder `dir`; a sinew::Error names the folder and, when another process
  // holds it, that process's pid.
  explicit FolderLock(const std::filesystem::path& dir);
  ~FolderLock();
  FolderLock(const FolderLock&) = delete;
  FolderLock& operator=(const FolderLock&) = delete;

  static constexpr const char* kFileName = ".sinew.lock";

 private:
  std::filesystem::path file_;
  int fd_ = -1;
};

}  // namespace sinew
