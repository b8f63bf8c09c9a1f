#pragma once
// Point caches in the PC2 format that Blender's Mesh Cache modifier (and 3ds Max, Houdini, ...)
// reads: a 32-byte little-endian header "POINTCACHE2\0", int32 version 1, int32 point count,
// float32 start frame, float32 sample rate (frames between samples), int32 sample count, then
// float32 x y z per point per sample. The cache's point order is the vertex order of the rest
// OBJ written beside it (docs/file-formats.md, "Point cache").
#include <Eigen/Core>
#include <filesystem>
#include <vector>

namespace sinew {

struct PointCache {
  float start_frame = 0.0f;
  float sample_rate = 1.0f;
  std::vector<Eigen::MatrixX3f> samples;  // each: one row per point
  Eigen::Index num_points() const { return samples.empty() ? 0 : samples.front().rows(); }
};

// Writes the whole cache atomically. A sinew::Error names the file when there is no sample, the
// samples differ in size, a value is not finite or the sample rate is not positive.
void write_pc2(const std::filesystem::path& path, const PointCache& cache);

// Reads and checks a PC2 file (header, version, sizes against the file length).
PointCache read_pc2(const std::filesystem::path& path);

// A cache that grows by one sample per simulated frame without rewriting the earlier ones:
// each append writes the sample at the end and then the new sample count into the header, so
// a reader (or a crash) between two appends sees a complete cache of the samples so far.
class Pc2Appender {
 public:
  // A new cache (replacing `path`) holding no sample yet.
  Pc2Appender(const std::filesystem::path& path, Eigen::Index points, float start_frame, float sample_rate);
  // An existing cache cut back to its first `keep_samples` samples (e.g. a resumed run); a
  // sinew::Error names the file if it is not a PC2 of `points` points holding that many.
  static Pc2Appender resume(const std::filesystem::path& path, Eigen::Index points, int keep_samples);

  void append(const Eigen::MatrixX3d& positions);
  int samples() const { return samples_; }
  const std::filesystem::path& path() const { return path_; }

 private:
  Pc2Appender() = default;
  std::filesystem::path path_;
  Eigen::Index points_ = 0;
  int samples_ = 0;
};

}  // namespace sinew
