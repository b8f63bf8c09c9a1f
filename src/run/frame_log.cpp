#include "sinew/run/frame_log.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <fmt/format.h>
#include <fstream>
#include <sstream>
#include <system_error>

#include "sinew/core/error.hpp"
#include "sinew/io/atomic_file.hpp"
#include "sinew/model/json_reader.hpp"
#include "sinew/run/run_summary.hpp"

namespace sinew {
namespace {

// A record is about a kilobyte (more with many boundary conditions); a longer line is damage.
constexpr std::size_t kMaxLine = 16u << 20;

std::string reason(int err) { return std::generic_category().message(err); }

}  // namespace

FrameLog::FrameLog(const std::filesystem::path& out, const std::vector<FrameRecord>& kept) : file_(out / kFileName) {
  write_file_atomically(file_, [&](std::ostream& os) {
    for (const FrameRecord& r : kept) os << frame_to_json(r).dump() << '\n';
  });
  fd_ = ::open(file_.c_str(), O_WRONLY | O_APPEND | O_CLOEXEC);
  if (fd_ < 0) throw Error(fmt::format("cannot open for appending: {}", reason(errno)), file_.string());
}

FrameLog::~FrameLog() { ::close(fd_); }

void FrameLog::append(const FrameRecord& record) {
  const std::string line = frame_to_json(record).dump() + '\n';
  // One write(2) of the whole line with O_APPEND: a reader sees whole lines, or a last one cut
  // short only if the process dies within the call.
  std::size_t done = 0;
  while (done < line.size()) {
    const ssize_t n = ::write(fd_, line.data() + done, line.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) throw Error(fmt::format("write failed: {}", reason(errno)), file_.string());
    done += static_cast<std::size_t>(n);
  }
}

void FrameLog::sync() {
  // Called before a checkpoint is written: a resume finds every frame the checkpoint claims.
  if (::fdatasync(fd_) != 0) throw Error(fmt::format("write failed: {}", reason(errno)), file_.string());
}

std::vector<FrameRecord> read_frame_log(const std::filesystem::path& out, int frames) {
  const std::filesystem::path path = out / FrameLog::kFileName;
  const std::string file = path.string();
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error("cannot open the frame records a resumed run continues (missing or unreadable)", file);
  std::vector<FrameRecord> records;
  std::string line;
  for (int expected = 1; expected <= frames; ++expected) {
    const std::string where = fmt::format("{}: line {}", file, expected);
    line.clear();
    char c = 0;
    bool ended = false;
    while (in.get(c)) {
      if (c == '\n') {
        ended = true;
        break;
      }
      if (line.size() >= kMaxLine) throw Error(fmt::format("line longer than {} bytes", kMaxLine), where);
      line += c;
    }
    if (!ended)
      throw Error(fmt::format("holds {} whole frame record(s), the checkpoint is at frame {}; run again without --resume",
                              expected - 1, frames),
                  file);
    std::istringstream text(line);
    FrameRecord r;
    try {
      r = frame_from_json(parse_json(text, where), "");
    } catch (const Error& e) {
      // frame_from_json names the JSON path inside the record.
      throw e.context().rfind('/', 0) == 0 ? Error(e.message(), where + ": " + e.context()) : e;
    }
    if (r.frame != expected)
      throw Error(fmt::format("is frame {}, expected frame {} (frames 1 to {} in order)", r.frame, expected, frames),
                  where + ": /frame");
    records.push_back(std::move(r));
  }
  return records;
}

}  // namespace sinew
