// The results of a fragility study (fitting/quake/include/rockfit/quake/fragility_study.hpp) as rockfit writes them: the /fragility group of
// the HDF5 file (layout in docs/file-formats.md), the `--json` object and the terminal table of `rockfit
// fragility`.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "rockfit/quake/fragility_study.hpp"
#include "rockfit/io/hdf5_file.hpp"

namespace rockfit::app {

// Writes /fragility under `root` (which must not hold it yet). Only the study's inputs and outcomes go into it, so
// the same study gives the same datasets whatever the threads, ranks or interruptions.
void WriteFragilityHdf5(const io::hdf5::Group& root, const quake::FragilityStudyOptions& study,
                        const std::string& settings_hash, const std::vector<quake::SampleOutcome>& outcomes,
                        const quake::FragilitySummary& summary);

// "rest", "t_max", "overturned", "failed", "lift_off", … for an outcome's end_reason, "invalid" for
// quake::kSampleInvalid.
std::string EndReasonName(std::int32_t code);

// The settings hash of the study stored in a file, empty when it holds none.
std::string StoredFragilityHash(const std::filesystem::path& path);

// blocks: id, limit_states, levels (intensity, samples, counted, not_counted, then per limit state exceeded,
// probability, wilson_95, clopper_pearson_95), curves (per limit state: status, message, median,
// median_std_error, median_interval_95, beta, beta_std_error, correlation, log_likelihood).
nlohmann::json FragilitySummaryJson(const quake::FragilityStudyOptions& study, const quake::FragilitySummary& summary);

// Per block: one row per level with P(overturning) and each tilt exceedance with 95 % Clopper–Pearson intervals,
// then the fitted curves.
std::string FragilityTable(const quake::FragilityStudyOptions& study, const quake::FragilitySummary& summary);

// "g" for PGA levels, "" for scale factors.
std::string IntensityUnit(quake::IntensityMeasure measure);

}  // namespace rockfit::app
