// Atomic (re)writing of an HDF5 file (docs/design.md §8): everything is built in memory (File::CreateInMemory), and
// Commit() writes the image to a temporary file in the same directory and renames it over the target
// (atomic_file.hpp). A crash, a kill, a full disk or an exception before the rename leaves the target exactly
// as it was. The memory used is the size of the new file.
//
// Re-writing keeps what the file held: the temporary file starts as a copy of the existing target minus the
// objects the caller says it replaces (e.g. "/summary", "/trials/T1"), so a second `rockfit summary -o x.h5`
// keeps the /fits that `rockfit fit` wrote into x.h5 in between. Any writer (summary, fit, batch, simulate)
// uses it the same way:
//
//   hdf5::Transaction tx(path, {"/fits/T1"});
//   hdf5::Group fit = tx.Root().CreateGroup("fits/T1");
//   ... write ...
//   tx.Commit();
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "rockfit/io/atomic_file.hpp"
#include "rockfit/io/hdf5_file.hpp"

namespace rockfit::io::hdf5 {

class Transaction {
 public:
  // OutputError when the directory is not writable, or when `target` exists and is not an HDF5 file (rockfit
  // never overwrites a file it cannot carry over). Stale temporary files of this target left by processes that
  // no longer run are removed.
  Transaction(std::filesystem::path target, std::vector<std::string> replaced = {});
  ~Transaction();
  Transaction(const Transaction&) = delete;
  Transaction& operator=(const Transaction&) = delete;

  Group Root() const;
  // The temporary file being written (for tests and messages).
  const std::filesystem::path& temporary_path() const { return replacement_->temporary(); }
  const std::filesystem::path& target() const { return target_; }
  // Closes, flushes to disk (fsync) and renames over the target. OutputError on failure (the target is untouched).
  void Commit();

 private:
  std::filesystem::path target_;
  std::optional<AtomicReplacement> replacement_;  // the one atomic-replace helper (atomic_file.hpp)
  std::optional<File> file_;
};

}  // namespace rockfit::io::hdf5
