// A Monte-Carlo overturning fragility study (fitting/quake/README.md, "The fragility study"): blocks with a distribution of their
// impact parameters, a set of ground-motion records, intensity levels and incidence angles; every sample is one
// Respond() run (core/response.hpp). The study is a pure function of its options and the sample index:
//
//   index = (block · L + level) · S + j       (L levels, S samples per level, j = 0 … S − 1)
//   record = j mod R                           (every record equally often at every level)
//   seed_i = SplitMix64(SplitMix64(study seed) + index), the sample's own random stream (rockfit/io/synth_random.hpp):
//            the incidence angle (when random) and λ, λ_lat, λ_lon, in this order
//
// so a sample's outcome does not depend on which thread or MPI rank runs it, nor on when. Outcomes are fixed-size
// records (SampleOutcome) that can be journaled and sent between processes as bytes; SummariseFragility reduces
// them in index order.
//
//   quake::FragilityStudyOptions study;  // blocks, records, levels, samples_per_level, seed, …
//   study.Validate();
//   std::vector<quake::SampleOutcome> outcomes = quake::RunSamples(study, all_indices, /*threads=*/0);
//   quake::FragilitySummary summary = quake::SummariseFragility(study, outcomes);
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "rockfit/core/block.hpp"
#include "rockfit/core/ground_motion.hpp"
#include "rockfit/core/response.hpp"
#include "rockfit/quake/lognormal_fragility.hpp"
#include "rockfit/fitting/uncertainty.hpp"

namespace rockfit::quake {

enum class IntensityMeasure {
  kPga,    // level = peak horizontal ground acceleration (resultant) [g], the record scaled to it
  kScale,  // level = factor multiplying the record as read
};
const char* ToString(IntensityMeasure measure);  // "pga_g", "scale"

// A normal distribution of one impact parameter (sd = 0: fixed at the mean).
struct ParameterDistribution {
  double mean = 0.0;
  double sd = 0.0;
};

struct FragilityBlock {
  std::string id;
  core::Block block = core::Block::FromMass(0.05, 0.05, 0.2, 1.0);
  ParameterDistribution lambda{1.0, 0.0};
  ParameterDistribution lambda_lat{0.0, 0.0};
  ParameterDistribution lambda_lon{1.0, 0.0};
  double tau_edge = 0.0;
  core::FacetTauRule facet_tau_rule = core::FacetTauRule::kNoSpin;
  std::string source;  // where the distribution comes from, for the output
};

// One ground-motion record as read (incidence 0, unscaled).
struct FragilityRecord {
  std::string name;
  core::GroundMotion ground;
};

struct FragilityStudyOptions {
  std::vector<FragilityBlock> blocks;
  std::vector<FragilityRecord> records;
  IntensityMeasure measure = IntensityMeasure::kPga;
  std::vector<double> levels;  // ascending, > 0
  std::int64_t samples_per_level = 100;
  std::optional<double> angle_rad;     // incidence of every sample; none: uniform on [0, 2π) per sample
  std::vector<double> tilt_fractions;  // exceedance thresholds: peak tilt ≥ f·critical tilt, f in (0, 1)
  std::uint64_t seed = 1;
  core::ResponseOptions response;      // flat at rest, 200 Hz samples (peak tilts are taken over them), 5 s tail
  // Throws InvalidArgument naming the bad option.
  void Validate() const;
  std::int64_t num_samples() const;
  // Everything the outcomes depend on, as text (records by name, step, length and a hash of their samples): equal
  // texts give equal outcomes. Its hash identifies a study for --resume.
  std::string SettingsText() const;
};

// What DrawSample decides for one index.
struct SampleInputs {
  std::int64_t index = 0;
  int block = 0, level = 0, record = 0;
  double intensity = 0.0;
  double angle_rad = 0.0;
  core::ModelParameters params;
  std::uint64_t seed = 0;
};
SampleInputs DrawSample(const FragilityStudyOptions& study, std::int64_t index);
// The ground motion of a sample: the record rotated by the angle, then scaled to the level (for kPga: by
// level·9.80665 / its peak horizontal resultant, exactly as `rockfit respond --pga --angle` assembles it); a view
// that shares the record's samples (core::GroundMotion::RotatedAndScaled), so threads hold no copies of it.
core::GroundMotion SampleGroundMotion(const FragilityStudyOptions& study, const SampleInputs& inputs, double* scale);

// End reason code of a sample whose parameters Respond() refused (it is not simulated).
inline constexpr std::int32_t kSampleInvalid = -1;

// One sample's inputs and outcome: a fixed-size record of plain numbers (no padding), sent between MPI ranks and
// journaled as bytes.
struct SampleOutcome {
  std::int64_t index;
  std::int32_t block, level, record;
  std::int32_t end_reason;  // core::EndReason as an integer, or kSampleInvalid
  double intensity, scale, angle_rad;
  double lambda, lambda_lat, lambda_lon;
  double t_end_s;
  double t_overturn_s;  // NaN when the block did not overturn
  double peak_tilt_rad, critical_tilt_rad, peak_rotation_rad, peak_rate_rad_s, pga_horizontal_m_s2;
  double max_discarded_rate_rad_s;  // the largest |ω| a rest of the run set to zero
  std::int64_t num_impacts;
  std::uint64_t seed;
  std::int32_t overturned;  // 1 or 0
  std::int32_t counted;     // 1: enters the probabilities (ended rest, t_max or overturned); 0: failed, lift-off, invalid
};

// Runs sample `index` (never throws for what happens in the run; the end reason says it).
SampleOutcome RunSample(const FragilityStudyOptions& study, std::int64_t index);
// The samples `indices` on a TBB arena of `threads` threads (0: all cores); the result is in the order of
// `indices` and does not depend on `threads`.
std::vector<SampleOutcome> RunSamples(const FragilityStudyOptions& study, const std::vector<std::int64_t>& indices,
                                      int threads);

// One limit state at one level: samples that reached it among the counted ones.
struct LimitStateCount {
  std::int64_t exceeded = 0;
  double probability = 0.0;     // exceeded / counted; NaN when no sample counted
  fitting::Interval wilson_95{};         // WilsonInterval
  fitting::Interval clopper_pearson_95{};
};

struct FragilityLevel {
  double intensity = 0.0;
  std::int64_t samples = 0;      // S
  std::int64_t counted = 0;      // ended rest, t_max or overturned
  std::int64_t not_counted = 0;  // failed, lift-off or invalid parameters
  std::vector<LimitStateCount> limit_states;  // [0] overturning, then one per tilt threshold
};

struct FragilityBlockResult {
  std::string id;
  std::vector<std::string> limit_states;  // "overturning", "tilt_0.5" (peak tilt ≥ 0.5 θ_c or overturned), …
  std::vector<FragilityLevel> levels;
  std::vector<LognormalFragilityFit> curves;  // one per limit state
};

struct FragilitySummary {
  std::vector<FragilityBlockResult> blocks;
  std::int64_t samples = 0;
  std::int64_t not_counted = 0;
};

// `outcomes` holds every sample of the study, each once, sorted by index (InvalidArgument otherwise).
FragilitySummary SummariseFragility(const FragilityStudyOptions& study, const std::vector<SampleOutcome>& outcomes);

// The name of a tilt limit state ("tilt_0.5").
std::string TiltLimitStateName(double fraction);

}  // namespace rockfit::quake
