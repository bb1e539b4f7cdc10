#include "rockfit/io/hdf5_transaction.hpp"

#include <filesystem>
#include <ostream>

#include <fmt/format.h>

#include "rockfit/core/errors.hpp"
#include "rockfit/io/atomic_file.hpp"

namespace rockfit::io::hdf5 {

namespace {

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
  // The new version is built in memory (File::CreateInMemory) and written by Commit(); the temporary file is
  // created and removed here so that an unwritable directory is an error before any work is done.
  replacement_.emplace(target_);
  replacement_->Write([](std::ostream&) {});
  replacement_->Discard();
  file_.emplace(File::CreateInMemory(replacement_->temporary()));
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
      throw OutputError(fmt::format("cannot carry over the content of {} into the new version: {}", target_.string(),
                                    e.what()));
    } catch (...) {
      file_.reset();
      throw;
    }
  }
}

Transaction::~Transaction() {
  file_.reset();  // closes the in-memory file; an uncommitted replacement removes its temporary
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
  // Temporary file beside the target, flushed (fsync) and renamed; OutputError (target unchanged) otherwise.
  replacement_->Write(
      [&image](std::ostream& out) { out.write(image.data(), static_cast<std::streamsize>(image.size())); });
  replacement_->Commit();
}

}  // namespace rockfit::io::hdf5
