#include "sinew/io/point_cache.hpp"

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fmt/format.h>
#include <fstream>
#include <limits>

#include "sinew/core/error.hpp"
#include "sinew/io/atomic_file.hpp"

namespace sinew {
namespace {

static_assert(std::endian::native == std::endian::little, "PC2 is little-endian; add byte swapping for this host");
static_assert(sizeof(float) == 4 && std::numeric_limits<float>::is_iec559);

constexpr char kMagic[12] = {'P', 'O', 'I', 'N', 'T', 'C', 'A', 'C', 'H', 'E', '2', '\0'};
constexpr std::streamoff kHeaderBytes = 32;
constexpr std::streamoff kSampleCountOffset = 28;

#pragma pack(push, 1)
struct Header {
  char magic[12];
  std::int32_t version;
  std::int32_t points;
  float start;
  float rate;
  std::int32_t samples;
};
#pragma pack(pop)
static_assert(sizeof(Header) == kHeaderBytes);

Header make_header(Eigen::Index points, float start, float rate, int samples, const std::string& where) {
  if (points <= 0 || points > std::numeric_limits<std::int32_t>::max())
    throw Error(fmt::format("a point cache needs 1 to 2^31 - 1 points, got {}", points), where);
  if (!std::isfinite(start)) throw Error("the start frame is not finite", where);
  if (!(rate > 0.0f) || !std::isfinite(rate)) throw Error(fmt::format("the sample rate must be positive, got {}", rate), where);
  Header h;
  std::memcpy(h.magic, kMagic, sizeof kMagic);
  h.version = 1;
  h.points = static_cast<std::int32_t>(points);
  h.start = start;
  h.rate = rate;
  h.samples = samples;
  return h;
}

std::vector<float> sample_floats(const Eigen::MatrixX3d& positions, const std::string& where) {
  std::vector<float> values(static_cast<size_t>(positions.size()));
  for (Eigen::Index p = 0; p < positions.rows(); ++p)
    for (int k = 0; k < 3; ++k) {
      const double v = positions(p, k);
      if (!std::isfinite(v) || std::abs(v) > std::numeric_limits<float>::max())
        throw Error(fmt::format("point {} coordinate {} = {} does not fit a float32", p, k, v), where);
      values[static_cast<size_t>(3 * p + k)] = static_cast<float>(v);
    }
  return values;
}

Header read_header(std::istream& in, const std::string& where) {
  Header h;
  if (!in.read(reinterpret_cast<char*>(&h), sizeof h)) throw Error("shorter than the 32-byte PC2 header", where);
  if (std::memcmp(h.magic, kMagic, sizeof kMagic) != 0) throw Error("not a PC2 file (no POINTCACHE2 signature)", where);
  if (h.version != 1) throw Error(fmt::format("PC2 version {} (only 1 exists)", h.version), where);
  if (h.points <= 0) throw Error(fmt::format("point count {} is not positive", h.points), where);
  if (h.samples < 0) throw Error(fmt::format("sample count {} is negative", h.samples), where);
  return h;
}

std::uintmax_t expected_size(const Header& h, int samples) {
  return static_cast<std::uintmax_t>(kHeaderBytes) + static_cast<std::uintmax_t>(samples) * h.points * 12u;
}

}  // namespace

void write_pc2(const std::filesystem::path& path, const PointCache& cache) {
  const std::string where = path.string();
  if (cache.samples.empty()) throw Error("a point cache needs at least one sample", where);
  const Header h = make_header(cache.num_points(), cache.start_frame, cache.sample_rate,
                               static_cast<int>(cache.samples.size()), where);
  for (size_t s = 0; s < cache.samples.size(); ++s) {
    if (cache.samples[s].rows() != cache.num_points())
      throw Error(fmt::format("sample {} has {} points, sample 0 has {}", s, cache.samples[s].rows(), cache.num_points()), where);
    if (!cache.samples[s].allFinite()) throw Error(fmt::format("sample {} has a non-finite coordinate", s), where);
  }
  write_file_atomically(path, [&](std::ostream& os) {
    os.write(reinterpret_cast<const char*>(&h), sizeof h);
    for (const auto& sample : cache.samples) {
      const Eigen::Matrix<float, Eigen::Dynamic, 3, Eigen::RowMajor> rows = sample;  // x y z per point
      os.write(reinterpret_cast<const char*>(rows.data()), static_cast<std::streamsize>(rows.size() * sizeof(float)));
    }
  });
}

PointCache read_pc2(const std::filesystem::path& path) {
  const std::string where = path.string();
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error("cannot open the point cache", where);
  const Header h = read_header(in, where);
  std::error_code ec;
  const auto size = std::filesystem::file_size(path, ec);
  if (ec || size < expected_size(h, h.samples))
    throw Error(fmt::format("header promises {} samples of {} points ({} bytes), the file has {}", h.samples, h.points,
                            expected_size(h, h.samples), ec ? 0 : size),
                where);
  PointCache cache;
  cache.start_frame = h.start;
  cache.sample_rate = h.rate;
  for (int s = 0; s < h.samples; ++s) {
    Eigen::Matrix<float, Eigen::Dynamic, 3, Eigen::RowMajor> rows(h.points, 3);
    in.read(reinterpret_cast<char*>(rows.data()), static_cast<std::streamsize>(rows.size() * sizeof(float)));
    if (!in) throw Error(fmt::format("sample {} is cut short", s), where);
    cache.samples.emplace_back(rows);
  }
  return cache;
}

Pc2Appender::Pc2Appender(const std::filesystem::path& path, Eigen::Index points, float start_frame, float sample_rate)
    : path_(path), points_(points) {
  const Header h = make_header(points, start_frame, sample_rate, 0, path.string());
  write_file_atomically(path, [&](std::ostream& os) { os.write(reinterpret_cast<const char*>(&h), sizeof h); });
}

Pc2Appender Pc2Appender::resume(const std::filesystem::path& path, Eigen::Index points, int keep_samples) {
  const std::string where = path.string();
  Header h;
  {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw Error("no point cache to resume (run without --resume first)", where);
    h = read_header(in, where);
  }
  if (h.points != points)
    throw Error(fmt::format("the cache has {} points, the surface {}", h.points, points), where);
  std::error_code ec;
  const auto size = std::filesystem::file_size(path, ec);
  if (keep_samples < 0 || keep_samples > h.samples || ec || size < expected_size(h, keep_samples))
    throw Error(fmt::format("cannot keep {} samples: the cache holds {}", keep_samples, h.samples), where);
  std::filesystem::resize_file(path, expected_size(h, keep_samples), ec);
  if (ec) throw Error(fmt::format("cannot cut the cache back: {}", ec.message()), where);
  Pc2Appender a;
  a.path_ = path;
  a.points_ = points;
  a.samples_ = keep_samples;
  std::fstream io(path, std::ios::binary | std::ios::in | std::ios::out);
  const std::int32_t count = keep_samples;
  io.seekp(kSampleCountOffset);
  io.write(reinterpret_cast<const char*>(&count), sizeof count);
  io.flush();
  if (!io) throw Error("cannot update the sample count", where);
  return a;
}

void Pc2Appender::append(const Eigen::MatrixX3d& positions) {
  const std::string where = path_.string();
  if (positions.rows() != points_)
    throw Error(fmt::format("sample has {} points, the cache {}", positions.rows(), points_), where);
  const std::vector<float> values = sample_floats(positions, where);
  std::fstream io(path_, std::ios::binary | std::ios::in | std::ios::out);
  if (!io) throw Error("cannot open the point cache to append", where);
  // Sample first, count second: the header never promises a sample that is not there.
  io.seekp(static_cast<std::streamoff>(kHeaderBytes + static_cast<std::streamoff>(samples_) * points_ * 12));
  io.write(reinterpret_cast<const char*>(values.data()), static_cast<std::streamsize>(values.size() * sizeof(float)));
  io.flush();
  const std::int32_t count = samples_ + 1;
  io.seekp(kSampleCountOffset);
  io.write(reinterpret_cast<const char*>(&count), sizeof count);
  io.flush();
  if (!io) throw Error("writing the sample failed (disk full?)", where);
  ++samples_;
}

}  // namespace sinew
