#include "sinew/io/deferred_sync.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <fmt/format.h>
#include <system_error>

#include "sinew/core/error.hpp"

namespace sinew {
namespace {

thread_local DeferredSync* active = nullptr;

std::string reason(int err) { return std::generic_category().message(err); }

}  // namespace

DeferredSync::Scope::Scope(DeferredSync& sync) : previous_(active) { active = &sync; }
DeferredSync::Scope::~Scope() { active = previous_; }

DeferredSync* DeferredSync::current() { return active; }

DeferredSync::~DeferredSync() {
  for (const File& f : files_) ::close(f.fd);
}

void DeferredSync::adopt(int fd, const std::filesystem::path& path) {
  if (files_.size() >= kMaxPending) {
    try {
      sync();
    } catch (...) {
      ::close(fd);
      throw;
    }
  }
  files_.push_back({fd, path});
  folders_.insert(path.has_parent_path() ? path.parent_path() : std::filesystem::path("."));
}

void DeferredSync::adopt_name(const std::filesystem::path& path) {
  folders_.insert(path.has_parent_path() ? path.parent_path() : std::filesystem::path("."));
}

void DeferredSync::sync() {
  std::vector<File> files;
  files.swap(files_);
  std::set<std::filesystem::path> folders;
  folders.swap(folders_);
  int failed_errno = 0;
  std::string failed_path;
  for (const File& f : files) {
    // Every descriptor is closed even after a failure; the first failure is reported.
    if (::fsync(f.fd) != 0 && failed_errno == 0) {
      failed_errno = errno;
      failed_path = f.path.string();
    }
    ::close(f.fd);
  }
  if (failed_errno != 0) throw Error(fmt::format("write failed: {}", reason(failed_errno)), failed_path);
  for (const auto& folder : folders) {
    const int fd = ::open(folder.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (fd < 0) throw Error(fmt::format("cannot open the folder to sync it: {}", reason(errno)), folder.string());
    const int rc = ::fsync(fd);
    const int err = errno;
    ::close(fd);
    if (rc != 0) throw Error(fmt::format("cannot sync the folder: {}", reason(err)), folder.string());
  }
}

}  // namespace sinew
