// Fuzz target body: rockfit's HDF5 store, read as `rockfit inspect FILE.h5`, `rockfit correct FILE.h5
// --trial ID` and `rockfit plot summary FILE.h5` read it (io::ListTrialsHdf5, io::ReadTrialHdf5,
// io::ReadRecordingHdf5, io::ReadSummaryHdf5). The input is the whole file; the seed corpus holds
// files rockfit wrote, so mutations land in real superblocks, object headers and datasets.
// The HDF5 library itself (Debian's libhdf5, not instrumented) is outside what this target proves:
// see tests/fuzz/README.md for how its own crashes are told apart from rockfit's.
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzz_input.hpp"
#include "recording_invariants.hpp"
#include "rockfit/io/campaign_hdf5.hpp"
#include "rockfit/io/load_recording.hpp"

namespace rockfit::fuzz {

namespace rockfit_hdf5_detail {

// A few trials are enough to reach every code path; a mutated file may list thousands of groups.
constexpr std::size_t kMaxTrialsRead = 4;

}  // namespace rockfit_hdf5_detail

inline void RockfitHdf5(std::string_view input) {
  static const ScratchDir dir;
  const auto file = dir.Write("campaign.h5", input);
  ExpectDocumentedOutcome([&] {
    io::LoadOptions options;
    options.format = io::RecordingFormat::kRockfitHdf5;
    CheckRecording(io::LoadRecording(file, options));
  });
  ExpectDocumentedOutcome([&] {
    const auto ids = io::ListTrialsHdf5(file);
    for (std::size_t k = 0; k < ids.size() && k < rockfit_hdf5_detail::kMaxTrialsRead; ++k) {
      ExpectDocumentedOutcome([&] { (void)io::ReadTrialHdf5(file, ids[k]); });
      ExpectDocumentedOutcome([&] { CheckRecording(io::ReadRecordingHdf5(file, ids[k])); });
    }
  });
  ExpectDocumentedOutcome([&] { (void)io::ReadSummaryHdf5(file); });
}

}  // namespace rockfit::fuzz
