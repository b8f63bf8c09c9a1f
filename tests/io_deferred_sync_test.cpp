// Batched durability (io/deferred_sync.hpp): inside a scope, write_file_atomically still puts
// whole files in place at once, and leaves their fsync to the batch; outside one it syncs each.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <thread>

#include "io_test_support.hpp"
#include "sinew/io/atomic_file.hpp"
#include "sinew/io/deferred_sync.hpp"

namespace sinew {
namespace {

using test::read_file;
using test::TempDir;

void write_text(const std::filesystem::path& path, const std::string& text) {
  write_file_atomically(path, [&](std::ostream& os) { os << text; });
}

TEST(IoDeferredSync, FilesInAScopeAreInPlaceAndWaitForTheBatch) {
  TempDir dir;
  DeferredSync batch;
  {
    DeferredSync::Scope scope(batch);
    EXPECT_EQ(DeferredSync::current(), &batch);
    write_text(dir / "a.txt", "first");
    write_text(dir / "a.txt", "second");  // replaced whole, like any atomic write
    write_text(dir / "b.txt", "other");
  }
  EXPECT_EQ(DeferredSync::current(), nullptr);
  EXPECT_EQ(batch.pending(), 3u);
  EXPECT_EQ(read_file(dir / "a.txt"), "second");
  EXPECT_EQ(dir.entries(), (std::vector<std::string>{"a.txt", "b.txt"}));  // no temporaries
  batch.sync();
  EXPECT_EQ(batch.pending(), 0u);
  batch.sync();  // an empty batch is fine
  write_text(dir / "c.txt", "synced at once");  // no scope: not handed to any batch
  EXPECT_EQ(batch.pending(), 0u);
}

TEST(IoDeferredSync, ScopesNestAndBelongToTheirThread) {
  TempDir dir;
  DeferredSync outer, inner;
  DeferredSync::Scope a(outer);
  {
    DeferredSync::Scope b(inner);
    write_text(dir / "inner.txt", "x");
    // Another thread has no scope: its write is synced at once.
    std::thread([&] { write_text(dir / "thread.txt", "y"); }).join();
  }
  write_text(dir / "outer.txt", "z");
  EXPECT_EQ(inner.pending(), 1u);
  EXPECT_EQ(outer.pending(), 1u);
  EXPECT_EQ(read_file(dir / "thread.txt"), "y");
}

TEST(IoDeferredSync, ABatchNeverHoldsMoreThanItsLimitOfDescriptors) {
  TempDir dir;
  DeferredSync batch;
  DeferredSync::Scope scope(batch);
  const int files = static_cast<int>(DeferredSync::kMaxPending) + 10;
  for (int i = 0; i < files; ++i) write_text(dir / fmt::format("f{}.txt", i), std::to_string(i));
  EXPECT_LE(batch.pending(), DeferredSync::kMaxPending);
  EXPECT_GT(batch.pending(), 0u);
  EXPECT_EQ(read_file(dir / fmt::format("f{}.txt", files - 1)), std::to_string(files - 1));
}

TEST(IoDeferredSync, AFailedWriteInAScopeKeepsTheOldFileAndAddsNothing) {
  TempDir dir;
  const auto path = dir.write("keep.txt", "previous");
  DeferredSync batch;
  DeferredSync::Scope scope(batch);
  const std::string message = test::error_message([&] {
    write_file_atomically(path, [](std::ostream&) { throw std::runtime_error("no values"); });
  });
  test::expect_contains(message, {"keep.txt", "no values"});
  EXPECT_EQ(read_file(path), "previous");
  EXPECT_EQ(batch.pending(), 0u);
  EXPECT_EQ(dir.entries(), std::vector<std::string>{"keep.txt"});
}

}  // namespace
}  // namespace sinew
