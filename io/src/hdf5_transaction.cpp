#include "rockfit/io/hdf5_transaction.hpp"

#include <fcntl.h>
#include <signal.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>

#include <fmt/format.h>

#include "rockfit/core/errors.hpp"

namespace rockfit::io::hdf5 {

namespace {

std::atomic<unsigned> g_serial{0};

const char* kTemporaryMarker = ".rockfit-tmp-";

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

void RemoveStaleTemporaries(const std::filesystem::path& target) {
  const std::filesystem::path dir = target.has_parent_path() ? target.parent_path() : ".";
  const std::string prefix = "." + target.filename().string() + kTemporaryMarker;
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(dir, ec)) {
    const std::string name = entry.path().filename().string();
    if (name.rfind(prefix, 0) != 0) continue;
    const std::string rest = name.substr(prefix.size());  // "<pid>-<serial>"
    const std::size_t dash = rest.find('-');
    if (dash == std::string::npos) continue;
    char* end = nullptr;
    const long pid = std::strtol(rest.substr(0, dash).c_str(), &end, 10);
    if (pid <= 0 || pid == static_cast<long>(::getpid())) continue;
    if (::kill(static_cast<pid_t>(pid), 0) == -1 && errno == ESRCH) std::filesystem::remove(entry.path(), ec);
  }
}

void SyncPath(const std::filesystem::path& path, int flags) {
  const int fd = ::open(path.c_str(), flags);
  if (fd < 0) return;
  ::fsync(fd);
  ::close(fd);
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
  file_.emplace(File::Create(temporary_));
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
  file_->Close();
  file_.reset();
  SyncPath(temporary_, O_RDONLY);
  if (std::rename(temporary_.c_str(), target_.c_str()) != 0) {
    const std::string reason = std::strerror(errno);
    std::error_code ec;
    std::filesystem::remove(temporary_, ec);
    throw OutputError(fmt::format("cannot rename {} to {}: {}; the previous file is unchanged", temporary_.string(),
                                  target_.string(), reason));
  }
  committed_ = true;
  SyncPath(target_.has_parent_path() ? target_.parent_path() : std::filesystem::path("."), O_RDONLY | O_DIRECTORY);
}

}  // namespace rockfit::io::hdf5
