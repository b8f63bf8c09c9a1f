// write_file_atomically: whole files or nothing, no temporary files left behind, errors that
// name the path and the reason.
#include <gtest/gtest.h>

#include <sys/resource.h>

#include <csignal>
#include <stdexcept>

#include "io_test_support.hpp"
#include "sinew/io/atomic_file.hpp"

namespace sinew {
namespace {

using test::error_message;
using test::expect_contains;
using test::read_file;
using test::TempDir;

TEST(IoAtomicFile, WritesTheContentAndLeavesOnlyTheTarget) {
  TempDir dir;
  const auto path = dir / "out.txt";
  write_file_atomically(path, [](std::ostream& os) { os << "hello\n" << 42 << '\n'; });
  EXPECT_EQ(read_file(path), "hello\n42\n");
  EXPECT_EQ(dir.entries(), std::vector<std::string>{"out.txt"});
}

TEST(IoAtomicFile, ReplacesAnExistingFile) {
  TempDir dir;
  const auto path = dir.write("out.txt", "old content that is longer than the new one");
  write_file_atomically(path, [](std::ostream& os) { os << "new"; });
  EXPECT_EQ(read_file(path), "new");
  EXPECT_EQ(dir.entries(), std::vector<std::string>{"out.txt"});
}

TEST(IoAtomicFile, LargeWritesGoThroughWhole) {
  TempDir dir;
  const auto path = dir / "big.bin";
  std::string block(200000, 'x');
  for (std::size_t i = 0; i < block.size(); ++i) block[i] = static_cast<char>('a' + i % 26);
  write_file_atomically(path, [&](std::ostream& os) {
    os << "head";
    os.write(block.data(), static_cast<std::streamsize>(block.size()));  // bypasses the buffer
    os << "tail";
  });
  EXPECT_EQ(read_file(path), "head" + block + "tail");
  // Many small writes crossing the internal buffer boundary several times.
  write_file_atomically(path, [&](std::ostream& os) {
    for (const char c : block) os.put(c);
  });
  EXPECT_EQ(read_file(path), block);
}

TEST(IoAtomicFile, ThrowingWriterKeepsTheOldFileAndLeavesNoTemporary) {
  TempDir dir;
  const auto path = dir.write("out.txt", "previous");
  const std::string message = error_message([&] {
    write_file_atomically(path, [](std::ostream& os) {
      os << std::string(100000, 'y');  // some of it already reached the temporary file
      throw std::runtime_error("writer gave up");
    });
  });
  expect_contains(message, {"out.txt", "writer gave up"});
  EXPECT_EQ(read_file(path), "previous");
  EXPECT_EQ(dir.entries(), std::vector<std::string>{"out.txt"});
}

TEST(IoAtomicFile, WriterSinewErrorKeepsItsContextUnderThePath) {
  TempDir dir;
  const auto path = dir / "new.txt";
  const std::string message = error_message([&] {
    write_file_atomically(path, [](std::ostream&) { throw Error("bad field", "field 'J'"); });
  });
  expect_contains(message, {"new.txt", "field 'J'", "bad field"});
  EXPECT_TRUE(dir.entries().empty());
}

TEST(IoAtomicFile, StreamFailureIsAnError) {
  TempDir dir;
  const auto path = dir / "out.txt";
  const std::string message = error_message([&] {
    write_file_atomically(path, [](std::ostream& os) {
      os << "partial";
      os.setstate(std::ios::badbit);
    });
  });
  expect_contains(message, {"out.txt", "write failed"});
  EXPECT_TRUE(dir.entries().empty());
}

TEST(IoAtomicFile, MissingDirectoryIsNamed) {
  TempDir dir;
  const auto path = dir / "missing" / "out.txt";
  const std::string message = error_message([&] { write_file_atomically(path, [](std::ostream& os) { os << 1; }); });
  expect_contains(message, {"out.txt", "does not exist", "missing"});
}

TEST(IoAtomicFile, TargetThatIsADirectoryIsAnError) {
  TempDir dir;
  std::filesystem::create_directory(dir / "sub");
  const std::string message =
      error_message([&] { write_file_atomically(dir / "sub", [](std::ostream& os) { os << 1; }); });
  expect_contains(message, {"sub", "is a directory"});
  EXPECT_EQ(dir.entries(), std::vector<std::string>{"sub"});
}

TEST(IoAtomicFile, FailedWriteReportsTheSystemReasonAndCleansUp) {
  // A file-size limit makes write(2) fail with EFBIG the way a full disk fails with ENOSPC:
  // the message must carry the system's reason and no partial file may remain.
  TempDir dir;
  const auto path = dir.write("out.bin", "previous");
  rlimit old{};
  ASSERT_EQ(::getrlimit(RLIMIT_FSIZE, &old), 0);
  rlimit small = old;
  small.rlim_cur = 4096;
  const auto old_handler = std::signal(SIGXFSZ, SIG_IGN);
  ASSERT_EQ(::setrlimit(RLIMIT_FSIZE, &small), 0);
  const std::string message = error_message([&] {
    write_file_atomically(path, [](std::ostream& os) { os << std::string(300000, 'z'); });
  });
  ::setrlimit(RLIMIT_FSIZE, &old);
  std::signal(SIGXFSZ, old_handler);
  expect_contains(message, {"out.bin", "write failed", "File too large"});
  EXPECT_EQ(read_file(path), "previous");
  EXPECT_EQ(dir.entries(), std::vector<std::string>{"out.bin"});
}

TEST(IoAtomicFile, EnsureDirectoryCreatesParentsAndRejectsFiles) {
  TempDir dir;
  const auto nested = dir / "a" / "b" / "c";
  ensure_directory(nested);
  EXPECT_TRUE(std::filesystem::is_directory(nested));
  ensure_directory(nested);  // existing: fine
  const auto file = dir.write("plain", "x");
  expect_contains(error_message([&] { ensure_directory(file); }), {"plain", "not a directory"});
  expect_contains(error_message([&] { ensure_directory(file / "below"); }), {"below", "cannot create directory"});
}

}  // namespace
}  // namespace sinew
