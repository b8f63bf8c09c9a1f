// PC2 point caches: the header Blender's Mesh Cache modifier reads, byte for byte; samples
// round trip as float32; the appender keeps the header's sample count true after every
// append and cuts a cache back for a resumed run; damaged files are named.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <fstream>

#include "io_test_support.hpp"
#include "sinew/io/point_cache.hpp"

namespace sinew {
namespace {

using test::error_message;
using test::expect_contains;

template <class T>
T at(const std::string& bytes, size_t offset) {
  T value;
  std::memcpy(&value, bytes.data() + offset, sizeof value);
  return value;
}

Eigen::MatrixX3d sample(int points, double shift) {
  Eigen::MatrixX3d p(points, 3);
  for (int i = 0; i < points; ++i) p.row(i) << i + shift, -0.5 * i, 0.25 + shift;
  return p;
}

TEST(IoPointCache, HeaderAndLayoutAreWhatBlenderReads) {
  test::TempDir dir;
  PointCache cache;
  cache.start_frame = 1.0f;
  cache.sample_rate = 2.0f;
  for (int s = 0; s < 3; ++s) cache.samples.emplace_back(sample(5, 0.5 * s).cast<float>());
  write_pc2(dir / "c.pc2", cache);
  const std::string bytes = test::read_file(dir / "c.pc2");
  ASSERT_EQ(bytes.size(), 32u + 3u * 5u * 12u);
  EXPECT_EQ(std::memcmp(bytes.data(), "POINTCACHE2\0", 12), 0);
  EXPECT_EQ(at<std::int32_t>(bytes, 12), 1);   // version
  EXPECT_EQ(at<std::int32_t>(bytes, 16), 5);   // points
  EXPECT_EQ(at<float>(bytes, 20), 1.0f);       // start frame
  EXPECT_EQ(at<float>(bytes, 24), 2.0f);       // sample rate
  EXPECT_EQ(at<std::int32_t>(bytes, 28), 3);   // samples
  // Sample 2, point 3, y: x y z per point, points per sample.
  EXPECT_EQ(at<float>(bytes, 32 + (2 * 5 + 3) * 12 + 4), -1.5f);
  const PointCache back = read_pc2(dir / "c.pc2");
  ASSERT_EQ(back.samples.size(), 3u);
  for (int s = 0; s < 3; ++s) EXPECT_EQ(back.samples[s], cache.samples[s]);
  EXPECT_EQ(back.start_frame, 1.0f);
  EXPECT_EQ(back.sample_rate, 2.0f);
}

TEST(IoPointCache, AppenderGrowsAndResumes) {
  test::TempDir dir;
  const auto path = dir / "grow.pc2";
  {
    Pc2Appender a(path, 4, 0.0f, 1.0f);
    for (int s = 0; s < 3; ++s) {
      a.append(sample(4, s));
      const PointCache now = read_pc2(path);  // complete after every append
      ASSERT_EQ(now.samples.size(), static_cast<size_t>(s + 1));
      EXPECT_EQ(now.samples.back(), sample(4, s).cast<float>());
    }
  }
  Pc2Appender resumed = Pc2Appender::resume(path, 4, 2);  // frames 0 and 1 kept, 2 redone
  resumed.append(sample(4, 7.0));
  const PointCache c = read_pc2(path);
  ASSERT_EQ(c.samples.size(), 3u);
  EXPECT_EQ(c.samples[1], sample(4, 1).cast<float>());
  EXPECT_EQ(c.samples[2], sample(4, 7.0).cast<float>());
  EXPECT_EQ(std::filesystem::file_size(path), 32u + 3u * 4u * 12u);

  expect_contains(error_message([&] { Pc2Appender::resume(path, 5, 1); }), {"grow.pc2", "the cache has 4 points, the surface 5"});
  expect_contains(error_message([&] { Pc2Appender::resume(path, 4, 5); }), {"grow.pc2", "cannot keep 5 samples: the cache holds 3"});
  expect_contains(error_message([&] { Pc2Appender::resume(dir / "none.pc2", 4, 1); }), {"none.pc2", "no point cache to resume"});
}

TEST(IoPointCache, BadInputIsNamed) {
  test::TempDir dir;
  expect_contains(error_message([&] { write_pc2(dir / "e.pc2", PointCache{}); }), {"e.pc2", "at least one sample"});
  PointCache uneven;
  uneven.samples = {sample(3, 0).cast<float>(), sample(4, 0).cast<float>()};
  expect_contains(error_message([&] { write_pc2(dir / "e.pc2", uneven); }), {"e.pc2", "sample 1 has 4 points"});
  PointCache rate;
  rate.sample_rate = 0.0f;
  rate.samples = {sample(3, 0).cast<float>()};
  expect_contains(error_message([&] { write_pc2(dir / "e.pc2", rate); }), {"sample rate must be positive"});
  EXPECT_FALSE(std::filesystem::exists(dir / "e.pc2"));

  expect_contains(error_message([&] { read_pc2(dir.write("short.pc2", "POINTCACHE2")); }), {"short.pc2", "32-byte"});
  expect_contains(error_message([&] { read_pc2(dir.write("magic.pc2", std::string(32, 'x'))); }), {"magic.pc2", "POINTCACHE2"});
  PointCache ok;
  ok.samples = {sample(3, 0).cast<float>(), sample(3, 1).cast<float>()};
  write_pc2(dir / "cut.pc2", ok);
  std::filesystem::resize_file(dir / "cut.pc2", 32 + 3 * 12 + 5);
  expect_contains(error_message([&] { read_pc2(dir / "cut.pc2"); }), {"cut.pc2", "promises 2 samples"});
  Pc2Appender a(dir / "a.pc2", 3, 0.0f, 1.0f);
  expect_contains(error_message([&] { a.append(sample(2, 0)); }), {"a.pc2", "sample has 2 points, the cache 3"});
  Eigen::MatrixX3d huge = sample(3, 0);
  huge(1, 1) = 1e300;
  expect_contains(error_message([&] { a.append(huge); }), {"point 1 coordinate 1", "float32"});
  EXPECT_EQ(read_pc2(dir / "a.pc2").samples.size(), 0u);
}

}  // namespace
}  // namespace sinew
