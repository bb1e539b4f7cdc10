// Rank 0's record of a fragility study (`rockfit fragility`): the outcome of every sample done so far, by index,
// and the journal (io/record_journal.hpp) they are appended to, from which an interrupted study resumes.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "rockfit/quake/fragility_study.hpp"
#include "rockfit/io/record_journal.hpp"

namespace rockfit::tools {

// OUTPUT.journal beside the output.
std::filesystem::path FragilityJournalPath(const std::string& output);

struct FragilityLedger {
  std::vector<quake::SampleOutcome> by_index;
  std::vector<char> done;
  std::size_t resumed = 0;  // samples taken from the journal
  std::optional<io::JournalWriter> journal;

  // Takes the outcomes of samples not done yet (a sample already done is never counted twice) and appends them
  // to the journal; returns how many were new and adds their overturns to `*overturned`. OutputError when the
  // journal cannot be written.
  std::size_t Record(const std::vector<quake::SampleOutcome>& outcomes, std::size_t* overturned);
  // The indices not done yet, ascending.
  std::vector<std::int64_t> Remaining() const;
};

// With `resume`, continues the journal at `path` if it holds samples of this study (BadInput when it belongs to
// another: its hash differs); otherwise starts a new one (a note on stderr when an old journal is discarded).
FragilityLedger OpenLedger(const std::filesystem::path& path, const quake::FragilityStudyOptions& study,
                           const std::string& settings_hash, bool resume);

}  // namespace rockfit::tools
