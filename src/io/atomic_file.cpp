#include "sinew/io/atomic_file.hpp"

#include <fcntl.h>
#include <signal.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <fmt/format.h>
#include <regex>
#include <streambuf>
#include <system_error>
#include <vector>

#include "sinew/core/error.hpp"
#include "sinew/io/deferred_sync.hpp"

namespace sinew {
namespace fs = std::filesystem;
namespace {

std::string reason(int err) { return std::generic_category().message(err); }

// A buffered stream over a POSIX descriptor that remembers the errno of the first failed
// write, so "No space left on device" reaches the message instead of a bare failbit.
class DescriptorBuffer final : public std::streambuf {
 public:
  explicit DescriptorBuffer(int fd) : fd_(fd), buffer_(1 << 16) { reset(); }
  int error() const { return error_; }

 protected:
  int_type overflow(int_type ch) override {
    if (!drain()) return traits_type::eof();
    if (!traits_type::eq_int_type(ch, traits_type::eof())) {
      *pptr() = traits_type::to_char_type(ch);
      pbump(1);
    }
    return traits_type::not_eof(ch);
  }
  std::streamsize xsputn(const char* s, std::streamsize n) override {
    if (n < static_cast<std::streamsize>(buffer_.size())) return std::streambuf::xsputn(s, n);
    // Large blocks (base64 arrays) bypass the buffer.
    if (!drain() || !write_all(s, static_cast<size_t>(n))) return 0;
    return n;
  }
  int sync() override { return drain() ? 0 : -1; }

 private:
  void reset() { setp(buffer_.data(), buffer_.data() + buffer_.size()); }
  bool drain() {
    const bool ok = write_all(pbase(), static_cast<size_t>(pptr() - pbase()));
    reset();
    return ok;
  }
  bool write_all(const char* data, size_t size) {
    if (error_ != 0) return false;
    while (size > 0) {
      const ssize_t n = ::write(fd_, data, size);
      if (n < 0) {
        if (errno == EINTR) continue;
        error_ = errno;
        return false;
      }
      data += n;
      size -= static_cast<size_t>(n);
    }
    return true;
  }

  int fd_;
  std::vector<char> buffer_;
  int error_ = 0;
};

// Removes the temporary file unless the rename consumed it.
struct TemporaryFile {
  fs::path path;
  int fd = -1;
  bool renamed = false;
  ~TemporaryFile() {
    if (fd >= 0) ::close(fd);
    if (!renamed && !path.empty()) ::unlink(path.c_str());
  }
};

std::atomic<unsigned> temporary_counter{0};

// ".NAME.tmp-PID-N", NAME the target's file name.
std::string temporary_name(const fs::path& target, unsigned counter) {
  return fmt::format(".{}.tmp-{}-{}", target.filename().string(), ::getpid(), counter);
}
const std::regex& temporary_pattern() {
  static const std::regex pattern(R"(\..+\.tmp-([0-9]{1,9})-[0-9]+)");
  return pattern;
}

}  // namespace

void write_file_atomically(const fs::path& path, const std::function<void(std::ostream&)>& writer) {
  const std::string where = path.string();
  if (path.empty() || !path.has_filename()) throw Error("no file name given", where);
  const fs::path dir = path.has_parent_path() ? path.parent_path() : fs::path(".");
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) {
    throw Error(fmt::format("cannot write: directory '{}' does not exist", dir.string()), where);
  }
  if (fs::is_directory(path, ec)) throw Error("cannot write: it is a directory", where);

  TemporaryFile tmp;
  for (int attempt = 0; attempt < 100 && tmp.fd < 0; ++attempt) {
    tmp.path = dir / temporary_name(path, temporary_counter.fetch_add(1));
    tmp.fd = ::open(tmp.path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (tmp.fd < 0 && errno != EEXIST) {
      const int err = errno;
      tmp.path.clear();
      throw Error(fmt::format("cannot create a temporary file in '{}': {}", dir.string(), reason(err)),
                  where);
    }
  }
  if (tmp.fd < 0) {
    tmp.path.clear();
    throw Error(fmt::format("cannot create a unique temporary file in '{}'", dir.string()), where);
  }

  DescriptorBuffer buffer(tmp.fd);
  std::ostream out(&buffer);
  try {
    writer(out);
  } catch (const Error& e) {
    throw e.within(where);
  } catch (const std::exception& e) {
    throw Error(e.what(), where);
  }
  out.flush();
  if (!out) {
    throw Error(buffer.error() != 0 ? fmt::format("write failed: {}", reason(buffer.error()))
                                    : std::string("write failed: the output stream reported an error"),
                where);
  }
  // In a DeferredSync scope the fsync waits for the batch's sync(): the rename still replaces
  // the target only with a whole file (a killed process leaves the old one or the new one).
  DeferredSync* deferred = DeferredSync::current();
  if (deferred == nullptr) {
    if (::fsync(tmp.fd) != 0) throw Error(fmt::format("write failed: {}", reason(errno)), where);
    const int fd = tmp.fd;
    tmp.fd = -1;
    if (::close(fd) != 0) throw Error(fmt::format("write failed: {}", reason(errno)), where);
  }
  if (::rename(tmp.path.c_str(), path.c_str()) != 0) {
    throw Error(fmt::format("cannot replace the file: {}", reason(errno)), where);
  }
  tmp.renamed = true;
  if (deferred != nullptr) {
    const int fd = tmp.fd;
    tmp.fd = -1;
    deferred->adopt(fd, path);
  }
}

bool link_file_atomically(const fs::path& existing, const fs::path& path) {
  const std::string where = path.string();
  const fs::path dir = path.has_parent_path() ? path.parent_path() : fs::path(".");
  fs::path tmp;
  bool linked = false;
  for (int attempt = 0; attempt < 100 && !linked; ++attempt) {
    tmp = dir / temporary_name(path, temporary_counter.fetch_add(1));
    if (::link(existing.c_str(), tmp.c_str()) == 0) {
      linked = true;
    } else if (errno != EEXIST) {
      return false;  // no hard links here (EPERM, EXDEV, EMLINK, ...) or no source: write instead
    }
  }
  if (!linked) return false;
  if (::rename(tmp.c_str(), path.c_str()) != 0) {
    const int err = errno;
    ::unlink(tmp.c_str());
    throw Error(fmt::format("cannot replace the file: {}", reason(err)), where);
  }
  if (DeferredSync* deferred = DeferredSync::current()) deferred->adopt_name(path);
  return true;
}

int remove_stale_temporary_files(const fs::path& dir) {
  int removed = 0;
  std::error_code ec;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    std::smatch m;
    std::error_code type_ec;
    if (!std::regex_match(name, m, temporary_pattern()) || !it->is_regular_file(type_ec)) continue;
    const auto pid = static_cast<pid_t>(std::stol(m[1].str()));
    const bool running = pid != ::getpid() && (::kill(pid, 0) == 0 || errno == EPERM);
    if (running) continue;
    if (::unlink(it->path().c_str()) != 0 && errno != ENOENT)
      throw Error(fmt::format("cannot remove a stale temporary file: {}", reason(errno)), it->path().string());
    ++removed;
  }
  if (ec) throw Error(fmt::format("cannot list the folder: {}", ec.message()), dir.string());
  return removed;
}

void ensure_directory(const fs::path& dir) {
  const std::string where = dir.string();
  if (dir.empty()) throw Error("no directory name given", "output directory");
  std::error_code ec;
  const fs::file_status status = fs::status(dir, ec);
  if (fs::exists(status)) {
    if (!fs::is_directory(status)) throw Error("exists and is not a directory", where);
    return;
  }
  fs::create_directories(dir, ec);
  if (ec) throw Error(fmt::format("cannot create directory: {}", ec.message()), where);
}

}  // namespace sinew
