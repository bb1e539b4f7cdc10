// The append-only journal of fixed-size records (record_journal.hpp): records read back in order, a torn tail
// (a kill during an append) is discarded and cut off when the journal continues, other files are refused.
#include <sys/stat.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "rockfit/core/errors.hpp"
#include "rockfit/io/record_journal.hpp"

#include "scratch_dir.hpp"

namespace rockfit::io {
namespace {

using testing::ScratchDir;

std::string Record(char fill, std::size_t n = 16) { return std::string(n, fill); }

TEST(RecordJournal, AppendedRecordsReadBackInOrderWithTheKey) {
  const ScratchDir dir("journal");
  const auto path = dir / "j";
  {
    JournalWriter w = JournalWriter::Create(path, "test", 16, "abc123");
    w.Append({Record('a'), Record('b')});
    w.Append({Record('c')});
  }
  const auto read = ReadJournal(path, "test", 16, 100);
  ASSERT_TRUE(read.has_value());
  EXPECT_EQ(read->key, "abc123");
  ASSERT_EQ(read->records.size(), 3u);
  EXPECT_EQ(read->records[0], Record('a'));
  EXPECT_EQ(read->records[2], Record('c'));
  EXPECT_EQ(read->discarded_bytes, 0u);
}

TEST(RecordJournal, TornTailIsDiscardedAndCutOffWhenTheJournalContinues) {
  const ScratchDir dir("journal");
  const auto path = dir / "j";
  { JournalWriter::Create(path, "test", 16, "k").Append({Record('a'), Record('b')}); }
  const auto full_size = std::filesystem::file_size(path);
  // A kill in the middle of the third record's write, and a record whose checksum does not match.
  { std::ofstream(path, std::ios::app | std::ios::binary) << Record('c').substr(0, 7); }
  auto read = ReadJournal(path, "test", 16, 100);
  ASSERT_TRUE(read.has_value());
  EXPECT_EQ(read->records.size(), 2u);
  EXPECT_EQ(read->discarded_bytes, 7u);
  EXPECT_EQ(read->valid_bytes, full_size);
  {
    JournalWriter w = JournalWriter::Continue(path, *read, 16);
    w.Append({Record('d')});
  }
  read = ReadJournal(path, "test", 16, 100);
  ASSERT_EQ(read->records.size(), 3u);
  EXPECT_EQ(read->records[2], Record('d'));
  EXPECT_EQ(read->discarded_bytes, 0u);
  // Damaged bytes inside a record end the valid part there.
  std::string bytes;
  {
    std::ifstream in(path, std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  bytes[bytes.size() - 10] ^= 0x40;
  dir.Write("j", bytes);
  read = ReadJournal(path, "test", 16, 100);
  EXPECT_EQ(read->records.size(), 2u);
  EXPECT_EQ(read->discarded_bytes, 24u);
}

TEST(RecordJournal, MissingFileOrIncompleteHeaderIsNoJournal) {
  const ScratchDir dir("journal");
  EXPECT_FALSE(ReadJournal(dir / "none", "test", 16, 100).has_value());
  dir.Write("partial", "rockfit-jour");
  EXPECT_FALSE(ReadJournal(dir / "partial", "test", 16, 100).has_value());
}

TEST(RecordJournal, AnotherKindRecordSizeOrFileIsBadInput) {
  const ScratchDir dir("journal");
  { JournalWriter::Create(dir / "j", "test", 16, "k"); }
  EXPECT_THROW(ReadJournal(dir / "j", "other", 16, 100), BadInput);
  EXPECT_THROW(ReadJournal(dir / "j", "test", 24, 100), BadInput);
  dir.Write("text", "hello world\nsome text\n");
  try {
    ReadJournal(dir / "text", "test", 16, 100);
    FAIL() << "a text file read as a journal";
  } catch (const BadInput& e) {
    EXPECT_NE(std::string(e.what()).find("not a rockfit journal"), std::string::npos) << e.what();
  }
  JournalWriter w = JournalWriter::Create(dir / "k", "test", 16, "k");
  EXPECT_THROW(w.Append({Record('a', 15)}), InvalidArgument);
}

TEST(RecordJournal, DirectoryFifoOrOverlongFileIsBadInputNotACrash) {
  const ScratchDir dir("journal");
  std::filesystem::create_directory(dir / "d");
  EXPECT_THROW(ReadJournal(dir / "d", "test", 16, 100), BadInput);
  ASSERT_EQ(::mkfifo((dir / "f").c_str(), 0600), 0);
  EXPECT_THROW(ReadJournal(dir / "f", "test", 16, 100), BadInput);  // at once: a FIFO is never opened for reading
  { JournalWriter::Create(dir / "j", "test", 16, "k").Append(std::vector<std::string>(200, Record('a', 16))); }
  EXPECT_EQ(ReadJournal(dir / "j", "test", 16, 200)->records.size(), 200u);
  EXPECT_THROW(ReadJournal(dir / "j", "test", 16, 10), BadInput);  // longer than a journal of 10 records may be
}

TEST(RecordJournal, BinaryHeaderIsQuotedAsEscapesNotEchoedRaw) {
  const ScratchDir dir("journal");
  dir.Write("bin", std::string("\x01\x02\xff\x1b[2Jgarbage\n", 15));
  try {
    ReadJournal(dir / "bin", "test", 16, 100);
    FAIL() << "binary bytes read as a journal";
  } catch (const BadInput& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("\\x01\\x02\\xff\\x1b[2J"), std::string::npos) << what;
    EXPECT_EQ(what.find('\x1b'), std::string::npos) << what;
  }
}

}  // namespace
}  // namespace rockfit::io
