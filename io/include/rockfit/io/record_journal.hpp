// An append-only journal of fixed-size binary records, for long computations that must survive a kill
// (`rockfit fragility`, docs/design.md §8). The file starts with one text line naming the kind of journal, the
// record size and a key (the settings hash of the computation); each record is followed by its FNV-1a
// checksum (content_hash.hpp). An append is one write(): once it returns, the records are in the kernel and survive
// a kill -9 of the process; Sync() also puts them on the disk (fdatasync), against a power failure, and costs
// milliseconds, so callers sync now and then. A crash leaves at most a torn tail, which reading discards and
// continuing cuts off.
//
//   JournalWriter journal = JournalWriter::Create(path, "fragility", sizeof(Record), settings_hash);
//   journal.Append({bytes_of_record_1, bytes_of_record_2});
//   journal.Sync();  // now and then
//   ...
//   if (auto old = ReadJournal(path, "fragility", sizeof(Record), max_records)) { /* old->key, old->records */ }
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace rockfit::io {

struct JournalContents {
  std::string key;                    // the key of the header line
  std::vector<std::string> records;   // complete records with a valid checksum, in file order
  std::uint64_t valid_bytes = 0;      // header and complete records
  std::uint64_t discarded_bytes = 0;  // after them: a torn or damaged tail (a kill or crash during an append)
};

// None when `path` does not exist or holds no complete header line (a kill while the journal was created).
// BadInput (naming the file, what was found and what to do) when it is not a regular file, is longer than a
// journal of `max_records` records, or is not a journal of this kind and record size.
std::optional<JournalContents> ReadJournal(const std::filesystem::path& path, const std::string& kind,
                                           std::size_t record_bytes, std::uint64_t max_records);

class JournalWriter {
 public:
  // A new, empty journal (an existing file is replaced); the header is written atomically. OutputError when
  // the file cannot be written.
  static JournalWriter Create(const std::filesystem::path& path, const std::string& kind, std::size_t record_bytes,
                              const std::string& key);
  // Appends after the valid part of an existing journal read by ReadJournal (a torn tail is cut off).
  static JournalWriter Continue(const std::filesystem::path& path, const JournalContents& contents,
                                std::size_t record_bytes);
  JournalWriter(JournalWriter&& other) noexcept;
  JournalWriter& operator=(JournalWriter&&) = delete;
  JournalWriter(const JournalWriter&) = delete;
  JournalWriter& operator=(const JournalWriter&) = delete;
  ~JournalWriter();

  // Each record must have the journal's record size (InvalidArgument otherwise). OutputError when the write fails
  // (a full disk): the journal then ends at its last complete record.
  void Append(const std::vector<std::string>& records);
  // fdatasync: what was appended is on the disk. OutputError when it fails.
  void Sync();
  const std::filesystem::path& path() const { return path_; }

 private:
  JournalWriter(std::filesystem::path path, int fd, std::size_t record_bytes)
      : path_(std::move(path)), fd_(fd), record_bytes_(record_bytes) {}
  std::filesystem::path path_;
  int fd_ = -1;
  std::size_t record_bytes_ = 0;
};

}  // namespace rockfit::io
