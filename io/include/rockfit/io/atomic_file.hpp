// Files replaced atomically (docs/design.md §8): the new content goes to a temporary file in the same directory,
// which is flushed to disk (fsync), renamed over the target, and the directory flushed in turn, so that a crash,
// a kill or a full disk never leaves a half-written file or damages an existing one. This is the one
// implementation: the HDF5 files, the CSV and JSON outputs, the x-IMU files of synthetic recordings and the
// figures all go through it.
#pragma once

#include <filesystem>
#include <functional>
#include <ostream>
#include <string>
#include <vector>

namespace rockfit::io {

// Every rockfit writer names its temporary file ".<name>.rockfit-tmp-<pid>-<serial>" beside the target.
inline constexpr const char* kTemporaryMarker = ".rockfit-tmp-";

// The temporary file that process `pid` uses for `target` in its `serial`-th write.
std::filesystem::path TemporaryPathFor(const std::filesystem::path& target, long pid, unsigned serial);

// Removes the temporary files of `target` left by rockfit processes that no longer run (killed before they
// could rename or remove them). Temporaries of running processes, this one included, are kept. Called by
// every writer before it starts, so a kill -9 leaves at most one stale file until the next write.
void RemoveStaleTemporaries(const std::filesystem::path& target);

// One file being replaced. A target that is a symbolic link is followed: the file it points to is replaced (or
// created) and the link stays. The constructor refuses a target that is a directory, a device, a FIFO or a
// socket (the rename would put a regular file in its place) or has no file name, removes
// the stale temporaries of the target and picks a fresh temporary name beside it; the caller (or a program it
// runs) writes the temporary; Commit() flushes it to disk, renames it over the target and flushes the
// directory. Until Commit() the target is untouched, and a replacement that is never committed removes its
// temporary file when it goes out of scope. OutputError on failure, naming the target.
class AtomicReplacement {
 public:
  explicit AtomicReplacement(std::filesystem::path target);
  ~AtomicReplacement();
  AtomicReplacement(AtomicReplacement&& other) noexcept;
  AtomicReplacement& operator=(AtomicReplacement&&) = delete;
  AtomicReplacement(const AtomicReplacement&) = delete;
  AtomicReplacement& operator=(const AtomicReplacement&) = delete;

  const std::filesystem::path& target() const { return target_; }
  const std::filesystem::path& temporary() const { return temporary_; }

  // Creates the temporary file, calls `write` with a stream to it and flushes it to disk. OutputError (temporary
  // removed) when it cannot be created, written or flushed; exceptions from `write` propagate after the temporary
  // is removed.
  void Write(const std::function<void(std::ostream&)>& write);
  // fsync the temporary, rename it over the target, fsync the directory. OutputError when the flush or the rename
  // fails (the temporary is then removed and the target unchanged).
  void Commit();
  // Removes the temporary file now (it is also removed when an uncommitted replacement is destroyed).
  void Discard() noexcept;

 private:
  std::filesystem::path target_;
  std::filesystem::path temporary_;
  bool pending_ = true;  // the temporary may exist and is ours to remove
};

// The common case: `write` fills the new content, then it replaces `path` (AtomicReplacement::Write, Commit).
void WriteFileAtomically(const std::filesystem::path& path, const std::function<void(std::ostream&)>& write);

// Several files that belong together (an x-IMU GUI set): every temporary is written and flushed before the first
// rename, so a full disk or a bad directory replaces none of them. A kill between the renames can leave a mix
// of old and new files, each one complete.
struct FileContent {
  std::filesystem::path path;
  std::string text;
};
void WriteFilesAtomically(const std::vector<FileContent>& files);

}  // namespace rockfit::io
