#include "rockfit/io/record_journal.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>

#include <fmt/format.h>

#include "rockfit/core/errors.hpp"
#include "rockfit/io/atomic_file.hpp"
#include "rockfit/io/content_hash.hpp"
#include "text/text_file.hpp"

namespace rockfit::io {
namespace {

constexpr const char* kMagic = "rockfit-journal";
constexpr std::size_t kChecksumBytes = 8;
// The header line: magic, version, kind, record size and a key of a few dozen characters.
constexpr std::uint64_t kMaxHeaderBytes = 4096;

// Bytes of a file that may be anything, for a message: printable ASCII as it is, the rest as \xNN.
std::string Printable(const std::string& bytes) {
  std::string text;
  for (char c : bytes) {
    const auto byte = static_cast<unsigned char>(c);
    text += byte >= 0x20 && byte < 0x7f ? std::string(1, c) : fmt::format("\\x{:02x}", byte);
  }
  return text;
}

std::string HeaderLine(const std::string& kind, std::size_t record_bytes, const std::string& key) {
  return fmt::format("{} 1 {} {} {}\n", kMagic, kind, record_bytes, key);
}

std::string ChecksumBytes(const std::string& record) {
  const std::uint64_t h = Fnv1a64(record);
  std::string out(kChecksumBytes, '\0');
  for (std::size_t b = 0; b < kChecksumBytes; ++b) out[b] = static_cast<char>((h >> (8 * b)) & 0xffu);
  return out;
}

}  // namespace

std::optional<JournalContents> ReadJournal(const std::filesystem::path& path, const std::string& kind,
                                           std::size_t record_bytes, std::uint64_t max_records) {
  std::error_code ec;
  if (!std::filesystem::exists(std::filesystem::symlink_status(path, ec))) return std::nullopt;
  const std::uint64_t max_bytes = kMaxHeaderBytes + max_records * (record_bytes + kChecksumBytes);
  const std::string bytes = ReadRegularFile(path, "a rockfit journal or no file", max_bytes);
  const std::size_t newline = bytes.find('\n');
  if (newline == std::string::npos) {
    if (bytes.rfind(kMagic, 0) == 0 || std::string(kMagic).rfind(bytes, 0) == 0) return std::nullopt;
    throw BadInput(fmt::format("{}: not a rockfit journal (no header line); remove the file or choose another output",
                               path.string()));
  }
  std::istringstream header(bytes.substr(0, newline));
  std::string magic, found_kind, key;
  int version = 0;
  std::size_t found_bytes = 0;
  header >> magic >> version >> found_kind >> found_bytes >> key;
  if (magic != kMagic || version != 1 || !header) {
    throw BadInput(fmt::format("{}:1:1: not a rockfit journal, found '{}', expected '{} 1 {} …'; remove the file or "
                               "choose another output",
                               path.string(), Printable(bytes.substr(0, std::min<std::size_t>(newline, 60))), kMagic,
                               kind));
  }
  if (found_kind != kind || found_bytes != record_bytes) {
    throw BadInput(fmt::format("{}:1:1: a {} journal with {}-byte records, expected a {} journal with {}-byte records "
                               "(written by another rockfit version?); remove it to start the computation over",
                               path.string(), found_kind, found_bytes, kind, record_bytes));
  }
  JournalContents out;
  out.key = key;
  std::size_t at = newline + 1;
  const std::size_t stride = record_bytes + kChecksumBytes;
  while (at + stride <= bytes.size()) {
    std::string record = bytes.substr(at, record_bytes);
    if (bytes.compare(at + record_bytes, kChecksumBytes, ChecksumBytes(record)) != 0) break;
    out.records.push_back(std::move(record));
    at += stride;
  }
  out.valid_bytes = at;
  out.discarded_bytes = bytes.size() - at;
  return out;
}

JournalWriter JournalWriter::Create(const std::filesystem::path& path, const std::string& kind,
                                    std::size_t record_bytes, const std::string& key) {
  if (key.empty() || key.find_first_of(" \n") != std::string::npos || kind.find_first_of(" \n") != std::string::npos) {
    throw InvalidArgument("a journal kind and key are single words");
  }
  WriteFileAtomically(path, [&](std::ostream& out) { out << HeaderLine(kind, record_bytes, key); });
  const int fd = ::open(path.c_str(), O_WRONLY | O_APPEND | O_CLOEXEC);
  if (fd < 0) throw OutputError(fmt::format("cannot open {} for appending: {}", path.string(), std::strerror(errno)));
  return JournalWriter(path, fd, record_bytes);
}

JournalWriter JournalWriter::Continue(const std::filesystem::path& path, const JournalContents& contents,
                                      std::size_t record_bytes) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_APPEND | O_CLOEXEC);
  if (fd < 0) throw OutputError(fmt::format("cannot open {} for appending: {}", path.string(), std::strerror(errno)));
  if (contents.discarded_bytes > 0 && ::ftruncate(fd, static_cast<off_t>(contents.valid_bytes)) != 0) {
    const int error = errno;
    ::close(fd);
    throw OutputError(fmt::format("cannot cut the torn end off {}: {}", path.string(), std::strerror(error)));
  }
  return JournalWriter(path, fd, record_bytes);
}

JournalWriter::JournalWriter(JournalWriter&& other) noexcept
    : path_(std::move(other.path_)), fd_(other.fd_), record_bytes_(other.record_bytes_) {
  other.fd_ = -1;
}

JournalWriter::~JournalWriter() {
  if (fd_ >= 0) ::close(fd_);
}

void JournalWriter::Append(const std::vector<std::string>& records) {
  if (records.empty()) return;
  std::string bytes;
  bytes.reserve(records.size() * (record_bytes_ + kChecksumBytes));
  for (const std::string& r : records) {
    if (r.size() != record_bytes_) {
      throw InvalidArgument(fmt::format("journal record of {} bytes, expected {}", r.size(), record_bytes_));
    }
    bytes += r;
    bytes += ChecksumBytes(r);
  }
  const off_t before = ::lseek(fd_, 0, SEEK_END);
  std::size_t written = 0;
  while (written < bytes.size()) {
    const ssize_t n = ::write(fd_, bytes.data() + written, bytes.size() - written);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      const int error = errno;
      if (before >= 0 && ::ftruncate(fd_, before) != 0) {
        // The torn tail stays; the next reading discards it.
      }
      throw OutputError(fmt::format("cannot append to {}: {}; check free space (the journal keeps every record "
                                    "written before)",
                                    path_.string(), std::strerror(error)));
    }
    written += static_cast<std::size_t>(n);
  }
}

void JournalWriter::Sync() {
  if (::fdatasync(fd_) != 0) {
    throw OutputError(fmt::format("cannot flush {} to disk: {}", path_.string(), std::strerror(errno)));
  }
}

}  // namespace rockfit::io
