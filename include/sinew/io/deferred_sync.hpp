#pragma once
// Batched durability for write_file_atomically (io/atomic_file.hpp). A file written while a
// DeferredSync::Scope is open on the writing thread is still whole or absent (temporary file,
// then rename), but its fsync waits for DeferredSync::sync(), which makes every file written
// since the last sync durable at once: one journal commit for the batch instead of one per file.
// A run syncs a batch right before the checkpoint that refers to those files (run_scene), so
// resuming after a crash never depends on a file that did not reach the disk.
#include <filesystem>
#include <set>
#include <vector>

namespace sinew {

class DeferredSync {
 public:
  // While alive, write_file_atomically on this thread hands its files to `sync` instead of
  // fsyncing each. Scopes nest; the innermost one wins.
  class Scope {
   public:
    explicit Scope(DeferredSync& sync);
    ~Scope();
    Scope(const Scope&) = delete;
    Scope& operator=(const Scope&) = delete;

   private:
    DeferredSync* previous_;
  };

  DeferredSync() = default;
  ~DeferredSync();  // closes what was not synced (no fsync: durability was not asked for)
  DeferredSync(const DeferredSync&) = delete;
  DeferredSync& operator=(const DeferredSync&) = delete;

  // fsyncs every file handed over since the last sync, then their folders (so the renames are
  // durable too). A sinew::Error names the first file that fails and the system's reason; the
  // batch is emptied either way.
  void sync();

  std::size_t pending() const { return files_.size(); }  // descriptors held

  // The scope's batch on this thread, or nullptr (write_file_atomically then fsyncs at once).
  static DeferredSync* current();

  // Takes ownership of `fd`, the descriptor of the file just renamed to `path`. A batch that
  // holds kMaxPending descriptors syncs itself first, so a long stretch between checkpoints
  // never runs out of descriptors.
  void adopt(int fd, const std::filesystem::path& path);
  static constexpr std::size_t kMaxPending = 256;

  // Records a new name given to a file whose content is already synced or in the batch (a hard
  // link): only its folder must be synced.
  void adopt_name(const std::filesystem::path& path);

 private:
  struct File {
    int fd;
    std::filesystem::path path;
  };
  std::vector<File> files_;
  std::set<std::filesystem::path> folders_;  // of files_ and of the names adopted
};

}  // namespace sinew
