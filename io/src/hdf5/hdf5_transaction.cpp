#include "rockfit/io/hdf5_transaction.hpp"

#include <fcntl.h>
#include <signal.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>

#include <fmt/format.h>

#include "rockfit/core/errors.hpp"
#include "rockfit/io/atomic_file.hpp"

namespace rockfit::io::hdf5 {

namespace {

std::atomic<unsigned> g_serial{0};

// "/trials/T1" → {"trials", "T1"}.
std::vector<std::string> Split(const std::string& path) {
  std::vector<std::string> parts;
  std::size_t start = 0;
  while (start < path.size()) {
    const std::size_t slash = path.find('/', start);
    const std::size_t end = slash == std::string::npos ? path.size() : slash;
    if (end > start) parts.push_back(path.substr(start, end - start));
    start = end + 1;
  }
  return parts;
}

// Copies the children of `from` into `to`, skipping replaced objects and descending into groups that contain one.
void CopyExcept(const Group& from, const Group& to, const std::vector<std::vector<std::string>>& replaced,
                std::size_t depth) {
  CopyAttributes(from, to);
  for (const std::string& child : from.Children()) {
    // `replaced` holds only paths below `from`: their first `depth` parts name `from` itself.
    std::vector<std::vector<std::string>> below;
    bool skip = false;
    for (const auto& parts : replaced) {
      if (parts[depth] != child) continue;
      if (parts.size() == depth + 1) skip = true;
      else below.push_back(parts);
    }
    if (skip) continue;
    if (!below.empty() && from.IsGroup(child)) {
      CopyExcept(from.OpenGroup(child), to.CreateGroup(child), below, depth + 1);
      continue;
    }
    CopyObject(from, child, to);
  }
}

}  // namespace

std::filesystem::path TemporaryPathFor(const std::filesystem::path& target, long pid, unsigned serial) {
  const std::filesystem::path dir = target.has_parent_path() ? target.parent_path() : std::filesystem::path();
  return dir / fmt::format(".{}{}{}-{}", target.filename().string(), kTemporaryMarker, pid, serial);
}

Transaction::Transaction(std::filesystem::path target, std::vector<std::string> replaced)
    : target_(std::move(target)) {
  if (target_.filename().empty()) throw OutputError(fmt::format("'{}' is not a file name", target_.string()));
  std::error_code ec;
  const bool exists = std::filesystem::exists(target_, ec);
  if (exists && !File::IsHdf5(target_)) {
    throw OutputError(fmt::format("{} exists and is not an HDF5 file; rockfit will not overwrite it. Choose another "
                                  "output name or move that file away",
                                  target_.string()));
  }
  RemoveStaleTemporaries(target_);
  temporary_ = TemporaryPathFor(target_, static_cast<long>(::getpid()), g_serial++);
  {
    // The new version is built in memory (File::CreateInMemory) and written by Commit(); a file created and
    // removed here makes an unwritable directory an error before any work is done.
    std::ofstream probe(temporary_, std::ios::binary);
    if (!probe) {
      throw OutputError(fmt::format("cannot write {}: cannot create a file in {}: {}; check that the directory exists "
                                    "and is writable",
                                    target_.string(),
                                    target_.has_parent_path() ? target_.parent_path().string() : std::string("."),
                                    std::strerror(errno)));
    }
  }
  std::filesystem::remove(temporary_, ec);
  file_.emplace(File::CreateInMemory(temporary_));
  if (exists) {
    std::vector<std::vector<std::string>> parts;
    for (const auto& path : replaced) {
      if (!Split(path).empty()) parts.push_back(Split(path));
    }
    try {
      const File existing = File::Open(target_, false);
      CopyExcept(existing.Root(), file_->Root(), parts, 0);
    } catch (const BadInput& e) {
      file_.reset();
      std::filesystem::remove(temporary_, ec);
      throw OutputError(fmt::format("cannot carry over the content of {} into the new version: {}", target_.string(),
                                    e.what()));
    } catch (...) {
      file_.reset();
      std::filesystem::remove(temporary_, ec);
      throw;
    }
  }
}

Transaction::~Transaction() {
  if (committed_) return;
  file_.reset();
  std::error_code ec;
  std::filesystem::remove(temporary_, ec);
}

Group Transaction::Root() const {
  if (!file_) throw OutputError(fmt::format("{}: the transaction is closed", target_.string()));
  return file_->Root();
}

void Transaction::Commit() {
  if (!file_) throw OutputError(fmt::format("{}: the transaction is closed", target_.string()));
  const std::string image = file_->Image();
  file_->Close();
  file_.reset();
  // Temporary file beside the target, flushed, fsync'ed and renamed; OutputError (target unchanged) otherwise.
  WriteFileAtomically(target_, [&image](std::ostream& out) { out.write(image.data(), static_cast<std::streamsize>(image.size())); });
  committed_ = true;
}

}  // namespace rockfit::io::hdf5
