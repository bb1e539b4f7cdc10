#include "fragility_ledger.hpp"

#include <cstring>
#include <iostream>

#include <fmt/format.h>

#include "rockfit/core/errors.hpp"

namespace rockfit::tools {
namespace {

constexpr const char* kJournalKind = "fragility";

std::string Bytes(const quake::SampleOutcome& o) { return std::string(reinterpret_cast<const char*>(&o), sizeof(o)); }

quake::SampleOutcome FromBytes(const std::string& bytes) {
  quake::SampleOutcome o;
  std::memcpy(&o, bytes.data(), sizeof(o));
  return o;
}

}  // namespace

std::filesystem::path FragilityJournalPath(const std::string& output) { return output + ".journal"; }

std::size_t FragilityLedger::Record(const std::vector<quake::SampleOutcome>& outcomes, std::size_t* overturned) {
  std::vector<std::string> records;
  for (const quake::SampleOutcome& o : outcomes) {
    const std::size_t i = static_cast<std::size_t>(o.index);
    if (i >= done.size() || done[i]) continue;
    by_index[i] = o;
    done[i] = 1;
    records.push_back(Bytes(o));
    if (overturned) *overturned += static_cast<std::size_t>(o.overturned);
  }
  journal->Append(records);
  return records.size();
}

std::vector<std::int64_t> FragilityLedger::Remaining() const {
  std::vector<std::int64_t> remaining;
  for (std::size_t i = 0; i < done.size(); ++i) {
    if (!done[i]) remaining.push_back(static_cast<std::int64_t>(i));
  }
  return remaining;
}

FragilityLedger OpenLedger(const std::filesystem::path& path, const quake::FragilityStudyOptions& study,
                           const std::string& settings_hash, bool resume) {
  FragilityLedger ledger;
  const std::size_t n = static_cast<std::size_t>(study.num_samples());
  ledger.by_index.resize(n);
  ledger.done.assign(n, 0);
  std::optional<io::JournalContents> old = io::ReadJournal(path, kJournalKind, sizeof(quake::SampleOutcome), n);
  if (old && !resume) {
    std::cerr << fmt::format("rockfit: {} holds {} samples of an interrupted study; starting over (--resume would "
                             "continue it)\n", path.string(), old->records.size());
    old.reset();
  }
  if (old && old->key != settings_hash) {
    throw BadInput(fmt::format("{}: the journal belongs to a study with other settings (hash {}, this study {}); "
                               "--resume continues only the same study: repeat its options, or drop --resume to start "
                               "over", path.string(), old->key, settings_hash));
  }
  if (!old) {
    ledger.journal.emplace(io::JournalWriter::Create(path, kJournalKind, sizeof(quake::SampleOutcome), settings_hash));
    return ledger;
  }
  for (const std::string& bytes : old->records) {
    const quake::SampleOutcome o = FromBytes(bytes);
    if (o.index < 0 || static_cast<std::size_t>(o.index) >= n) {
      throw BadInput(fmt::format("{}: sample index {} outside the study's {} samples; remove the journal", path.string(),
                                 o.index, n));
    }
    const std::size_t i = static_cast<std::size_t>(o.index);
    if (ledger.done[i]) continue;  // never counted twice
    ledger.by_index[i] = o;
    ledger.done[i] = 1;
    ++ledger.resumed;
  }
  if (old->discarded_bytes > 0) {
    std::cerr << fmt::format("rockfit: {}: {} bytes of a torn last write discarded\n", path.string(), old->discarded_bytes);
  }
  ledger.journal.emplace(io::JournalWriter::Continue(path, *old, sizeof(quake::SampleOutcome)));
  return ledger;
}

}  // namespace rockfit::tools
