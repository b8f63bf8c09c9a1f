#include "sinew/io/folder_lock.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <fmt/format.h>
#include <system_error>

#include "sinew/core/error.hpp"

namespace sinew {
namespace {

std::string reason(int err) { return std::generic_category().message(err); }

// The pid the lock file holds ("" while its owner has not written it yet).
std::string owner_of(int fd) {
  char text[32] = {};
  const ssize_t n = ::pread(fd, text, sizeof text - 1, 0);
  std::string pid;
  for (ssize_t i = 0; i < n && text[i] >= '0' && text[i] <= '9'; ++i) pid += text[i];
  return pid;
}

}  // namespace

FolderLock::FolderLock(const std::filesystem::path& dir) : file_(dir / kFileName) {
  const std::string where = dir.string();
  // The owner removes the file when it releases the lock, so the file locked here may have been
  // unlinked in between: lock again until the locked file is the one at the path.
  for (int attempt = 0;; ++attempt) {
    const int fd = ::open(file_.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (fd < 0) throw Error(fmt::format("cannot create the lock file {}: {}", kFileName, reason(errno)), where);
    if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
      const int err = errno;
      const std::string pid = err == EWOULDBLOCK ? owner_of(fd) : "";
      ::close(fd);
      if (err == EWOULDBLOCK)
        throw Error(fmt::format("output folder is in use by another sinew run (pid {}); wait for it to end or choose "
                                "another --out folder",
                                pid.empty() ? "unknown" : pid),
                    where);
      throw Error(fmt::format("cannot lock the output folder: {}", reason(err)), where);
    }
    struct stat held {}, named {};
    if (::fstat(fd, &held) == 0 && ::stat(file_.c_str(), &named) == 0 && held.st_dev == named.st_dev &&
        held.st_ino == named.st_ino) {
      fd_ = fd;
      break;
    }
    ::close(fd);
    if (attempt >= 100) throw Error("cannot lock the output folder: its lock file keeps being replaced", where);
  }
  const std::string pid = fmt::format("{}\n", ::getpid());
  if (::ftruncate(fd_, 0) != 0 || ::pwrite(fd_, pid.data(), pid.size(), 0) != static_cast<ssize_t>(pid.size())) {
    const int err = errno;
    ::unlink(file_.c_str());
    ::close(fd_);
    throw Error(fmt::format("cannot write the lock file {}: {}", kFileName, reason(err)), where);
  }
}

FolderLock::~FolderLock() {
  // Unlinked while still locked: a process that opened the file meanwhile sees, after it gets
  // the lock, that the path no longer names it, and locks the path afresh.
  ::unlink(file_.c_str());
  ::close(fd_);
}

}  // namespace sinew
