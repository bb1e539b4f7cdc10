// The fragility study (fragility_study.hpp): the sample plan and its seeds, thread-independent outcomes, the
// reduction to probabilities, and the physics the issue asks for — exact 0 and 1 around the overturning scale of
// one record (found by bisection with Respond), the size effect, and fewer overturns with more dissipation at the facet impacts — on a
// planar case (record along x, λ_lat = 0) with generated Clough–Penzien records. A larger λ_lon dissipates
// more ((6)): the direction checked is the one (6) gives.
#include <cmath>
#include <cstring>
#include <numeric>
#include <set>
#include <vector>

#include <gtest/gtest.h>

#include "build_type.hpp"
#include "generated_records.hpp"
#include "rockfit/core/errors.hpp"
#include "rockfit/core/planar_avrf.hpp"
#include "rockfit/core/response.hpp"
#include "rockfit/quake/fragility_study.hpp"

namespace rockfit::quake {
namespace {

FragilityRecord Generated(std::uint64_t seed, double duration_s) {
  return {"synthetic:" + std::to_string(seed), rockfit::testing::GeneratedRecordAlongX(seed, duration_s)};
}

// A granite block of slenderness b1/h = 0.25 rocking in the xz plane (b2 > b1 is not needed: the record acts
// along x, so only the edges along y lift).
FragilityBlock PlanarBlock(double h_m, double lambda_lon) {
  FragilityBlock b;
  b.id = "h" + std::to_string(h_m);
  b.block = core::Block::FromDensity(0.25 * h_m, 0.2 * h_m, h_m, 2692.0);
  b.lambda = {1.0, 0.0};
  b.lambda_lat = {0.0, 0.0};
  b.lambda_lon = {lambda_lon, 0.0};
  return b;
}

FragilityStudyOptions PlanarStudy(std::vector<FragilityBlock> blocks, int records, double duration_s,
                                  std::vector<double> levels, std::int64_t samples) {
  FragilityStudyOptions s;
  s.blocks = std::move(blocks);
  for (int r = 0; r < records; ++r) s.records.push_back(Generated(100 + static_cast<std::uint64_t>(r), duration_s));
  s.levels = std::move(levels);
  s.samples_per_level = samples;
  s.angle_rad = 0.0;
  s.seed = 7;
  s.response.tail_s = rockfit::testing::kOptimisedBuild ? 2.0 : 0.5;  // Debug/sanitizer runs are ~150× slower
  return s;
}

std::vector<std::int64_t> AllIndices(const FragilityStudyOptions& s) {
  std::vector<std::int64_t> all(static_cast<std::size_t>(s.num_samples()));
  std::iota(all.begin(), all.end(), 0);
  return all;
}

TEST(FragilityStudy, SamplePlanUsesEveryRecordEquallyAndGivesEachSampleItsOwnSeed) {
  FragilityStudyOptions s = PlanarStudy({PlanarBlock(0.2, 0.8), PlanarBlock(0.6, 0.8)}, 3, 2.0, {0.2, 0.4}, 6);
  s.angle_rad.reset();
  s.blocks[0].lambda = {1.0, 0.1};
  std::set<std::uint64_t> seeds;
  for (std::int64_t i = 0; i < s.num_samples(); ++i) {
    const SampleInputs in = DrawSample(s, i);
    EXPECT_EQ(in.block, i / 12);
    EXPECT_EQ(in.level, (i % 12) / 6);
    EXPECT_EQ(in.record, (i % 6) % 3);
    EXPECT_GE(in.angle_rad, 0.0);
    EXPECT_LT(in.angle_rad, 2.0 * M_PI);
    seeds.insert(in.seed);
    // A pure function of (study, index): the same draw whenever and wherever it is made.
    const SampleInputs again = DrawSample(s, i);
    EXPECT_EQ(again.seed, in.seed);
    EXPECT_EQ(again.params.lambda, in.params.lambda);
    EXPECT_EQ(again.angle_rad, in.angle_rad);
  }
  EXPECT_EQ(seeds.size(), static_cast<std::size_t>(s.num_samples()));
  // The seed depends on the study seed.
  FragilityStudyOptions other = s;
  other.seed = 8;
  EXPECT_NE(DrawSample(other, 0).seed, DrawSample(s, 0).seed);
  EXPECT_THROW(DrawSample(s, s.num_samples()), InvalidArgument);
}

TEST(FragilityStudy, SampleGroundMotionIsTheRecordRotatedThenScaledBitForBit) {
  FragilityStudyOptions s = PlanarStudy({PlanarBlock(0.2, 0.8)}, 2, 2.0, {0.2, 0.4}, 4);
  s.angle_rad.reset();  // a random angle per sample: the rotation is not the identity
  for (std::int64_t index = 0; index < s.num_samples(); ++index) {
    const SampleInputs in = DrawSample(s, index);
    double scale = 0.0;
    const core::GroundMotion sampled = SampleGroundMotion(s, in, &scale);
    const core::GroundMotion rotated = s.records[static_cast<std::size_t>(in.record)].ground.Rotated(in.angle_rad);
    const core::GroundMotion expected = rotated.Scaled(in.intensity * core::kRecordGravity / rotated.PeakHorizontal());
    ASSERT_EQ(sampled.size(), expected.size());
    EXPECT_EQ(sampled.dt_s(), expected.dt_s());
    EXPECT_EQ(std::memcmp(sampled.samples_W().data(), expected.samples_W().data(),
                          sizeof(Eigen::Vector3d) * sampled.size()), 0) << "sample " << index;
  }
}

TEST(FragilityStudy, ParametersFollowTheirNormalDistributions) {
  FragilityStudyOptions s = PlanarStudy({PlanarBlock(0.2, 0.8)}, 1, 2.0, {0.3}, 20000);
  s.blocks[0].lambda = {0.9, 0.05};
  s.blocks[0].lambda_lat = {-1.5, 0.3};
  s.blocks[0].lambda_lon = {0.25, 0.02};
  s.angle_rad.reset();
  double sum[4] = {}, sq[4] = {};
  const double mean[4] = {0.9, -1.5, 0.25, M_PI}, sd[4] = {0.05, 0.3, 0.02, M_PI / std::sqrt(3.0)};
  const auto n = static_cast<double>(s.num_samples());
  for (std::int64_t i = 0; i < s.num_samples(); ++i) {
    const SampleInputs in = DrawSample(s, i);
    const double v[4] = {in.params.lambda, in.params.lambda_lat, in.params.lambda_lon, in.angle_rad};
    for (int k = 0; k < 4; ++k) sum[k] += v[k], sq[k] += v[k] * v[k];
  }
  for (int k = 0; k < 4; ++k) {
    const double m = sum[k] / n, var = sq[k] / n - m * m;
    EXPECT_NEAR(m, mean[k], 4.0 * sd[k] / std::sqrt(n)) << k;  // 4 standard errors of the mean
    EXPECT_NEAR(std::sqrt(var), sd[k], 0.03 * sd[k]) << k;
  }
}

TEST(FragilityStudy, OutcomesAreTheSameBytesOnOneAndTwoThreadsAndInAnyOrder) {
  const FragilityStudyOptions s = PlanarStudy({PlanarBlock(0.2, 0.8)}, 2, rockfit::testing::kOptimisedBuild ? 8.0 : 1.5,
                                              {0.3, 0.6}, rockfit::testing::kOptimisedBuild ? 3 : 2);
  const std::vector<std::int64_t> all = AllIndices(s);
  const std::vector<SampleOutcome> one = RunSamples(s, all, 1);
  const std::vector<SampleOutcome> two = RunSamples(s, all, 2);
  std::vector<std::int64_t> reversed(all.rbegin(), all.rend());
  const std::vector<SampleOutcome> backwards = RunSamples(s, reversed, 2);
  ASSERT_EQ(one.size(), all.size());
  for (std::size_t i = 0; i < all.size(); ++i) {
    EXPECT_EQ(std::memcmp(&one[i], &two[i], sizeof(SampleOutcome)), 0) << i;
    EXPECT_EQ(std::memcmp(&one[i], &backwards[all.size() - 1 - i], sizeof(SampleOutcome)), 0) << i;
  }
}

TEST(FragilityStudy, SummaryCountsOverturnsAndTiltExceedancesPerLevel) {
  FragilityStudyOptions s = PlanarStudy({PlanarBlock(0.2, 0.8)}, 1, 2.0, {0.2, 0.4}, 4);
  s.tilt_fractions = {0.5};
  std::vector<SampleOutcome> outcomes(8);
  for (std::size_t i = 0; i < 8; ++i) {
    SampleOutcome& o = outcomes[i];
    std::memset(&o, 0, sizeof(o));
    o.index = static_cast<std::int64_t>(i);
    o.counted = 1;
    o.critical_tilt_rad = 0.2;
  }
  outcomes[1].peak_tilt_rad = 0.11;  // level 0: one tilt exceedance, no overturn
  outcomes[2].counted = 0;           // level 0: a failed run, not counted
  outcomes[4].overturned = 1;        // level 1: two overturns (which exceed every tilt), one tilt exceedance
  outcomes[5].overturned = 1;
  outcomes[6].peak_tilt_rad = 0.15;
  const FragilitySummary sum = SummariseFragility(s, outcomes);
  ASSERT_EQ(sum.blocks.size(), 1u);
  const FragilityBlockResult& b = sum.blocks[0];
  ASSERT_EQ(b.limit_states, (std::vector<std::string>{"overturning", "tilt_0.5"}));
  EXPECT_EQ(b.levels[0].counted, 3);
  EXPECT_EQ(b.levels[0].not_counted, 1);
  EXPECT_EQ(b.levels[0].limit_states[0].exceeded, 0);
  EXPECT_EQ(b.levels[0].limit_states[0].probability, 0.0);
  EXPECT_DOUBLE_EQ(b.levels[0].limit_states[1].probability, 1.0 / 3.0);
  EXPECT_DOUBLE_EQ(b.levels[1].limit_states[0].probability, 0.5);
  EXPECT_DOUBLE_EQ(b.levels[1].limit_states[1].probability, 0.75);
  EXPECT_EQ(sum.not_counted, 1);
  outcomes.pop_back();
  EXPECT_THROW(SummariseFragility(s, outcomes), InvalidArgument);
}

// Overturned or not at scale factor `scale` of record 0, by Respond itself.
bool OverturnsAt(const FragilityStudyOptions& s, double scale) {
  const core::Response r = core::Respond(s.blocks[0].block, DrawSample(s, 0).params,
                                         s.records[0].ground.Scaled(scale), s.response);
  return r.summary.overturned;
}

TEST(FragilityStudy, DeterministicBlockGivesExactlyZeroBelowAndOneAboveTheOverturningScale) {
  ROCKFIT_REQUIRE_OPTIMISED_BUILD();
  // No parameter spread, one record, a fixed angle: every sample at a level is the same run.
  FragilityStudyOptions s = PlanarStudy({PlanarBlock(0.2, 0.8)}, 1, 10.0, {1.0}, 1);
  s.measure = IntensityMeasure::kScale;
  // Bisection on the scale factor between a level that does not overturn the block and one that does.
  double low = 0.5, high = 8.0;
  ASSERT_FALSE(OverturnsAt(s, low));
  ASSERT_TRUE(OverturnsAt(s, high));
  constexpr double kRelativeBracket = 1e-4;  // the bracket's width relative to the scale
  while (high - low > kRelativeBracket * high) {
    const double mid = 0.5 * (low + high);
    (OverturnsAt(s, mid) ? high : low) = mid;
  }
  s.levels = {low, high};
  s.samples_per_level = 4;
  const FragilitySummary sum = SummariseFragility(s, RunSamples(s, AllIndices(s), 2));
  const FragilityBlockResult& b = sum.blocks[0];
  EXPECT_EQ(b.levels[0].counted, 4);
  EXPECT_EQ(b.levels[0].limit_states[0].probability, 0.0) << "scale " << low;
  EXPECT_EQ(b.levels[1].limit_states[0].probability, 1.0) << "scale " << high;
  EXPECT_EQ(b.curves[0].status, LognormalFitStatus::kSeparated);
  EXPECT_GE(b.curves[0].median, low);
  EXPECT_LE(b.curves[0].median, high);
  std::printf("overturning scale of synthetic:100 (%.0f s): between %.6f and %.6f\n",
              s.records[0].ground.t_end_s(), low, high);
}

// PGA levels [g] of the planar studies, around the overturning of the h = 0.2 m block (uplift at g·b1/h = 0.25 g).
const std::vector<double> kPlanarLevels{0.3, 0.35, 0.4, 0.45, 0.5, 0.6, 0.75, 0.9};

// The planar studies: 8 generated 10 s records along x, PGA levels, 16 samples per level.
FragilitySummary PlanarFragility(std::vector<FragilityBlock> blocks, std::vector<double> levels) {
  const FragilityStudyOptions s = PlanarStudy(std::move(blocks), 8, 10.0, std::move(levels), 16);
  return SummariseFragility(s, RunSamples(s, AllIndices(s), 0));
}

std::int64_t TotalOverturns(const FragilityBlockResult& b) {
  std::int64_t k = 0;
  for (const FragilityLevel& l : b.levels) k += l.limit_states[0].exceeded;
  return k;
}

TEST(FragilityStudy, LargerBlockOfTheSameSlendernessOverturnsLess) {
  ROCKFIT_REQUIRE_OPTIMISED_BUILD();
  const std::vector<double>& levels = kPlanarLevels;
  const FragilitySummary sum = PlanarFragility({PlanarBlock(0.2, 0.8), PlanarBlock(0.6, 0.8)}, levels);
  const FragilityBlockResult &small = sum.blocks[0], &large = sum.blocks[1];
  std::printf("size effect (b1/h = 0.25, λ_lon = 0.8): PGA [g] / overturned of 16, h = 0.2 m | h = 0.6 m\n");
  for (std::size_t l = 0; l < levels.size(); ++l) {
    std::printf("  %.2f  %2lld | %2lld\n", levels[l], static_cast<long long>(small.levels[l].limit_states[0].exceeded),
                static_cast<long long>(large.levels[l].limit_states[0].exceeded));
    EXPECT_LE(large.levels[l].limit_states[0].exceeded, small.levels[l].limit_states[0].exceeded) << levels[l];
  }
  std::printf("  medians: %.4g g (%s) | %.4g g (%s)\n", small.curves[0].median, ToString(small.curves[0].status),
              large.curves[0].median, ToString(large.curves[0].status));
  EXPECT_LT(TotalOverturns(large), TotalOverturns(small));
  EXPECT_GT(large.curves[0].median, small.curves[0].median);
}

TEST(FragilityStudy, LargerLambdaLonDissipatesMoreAndOverturnsLess) {
  ROCKFIT_REQUIRE_OPTIMISED_BUILD();
  // (6): the planar AVRF r = (J0 − λ m b²)/(J0 + λ m b²) falls as λ grows — a larger λ_lon loses more energy at
  // each facet impact (λ_lon = 0 loses none).
  const core::PlanarBlock planar = core::PlanarBlockAboutY(PlanarBlock(0.2, 0.8).block);
  const double lambda_low = 0.3, lambda_high = 1.5;
  ASSERT_GT(core::AvrfChatzis(planar, lambda_low), core::AvrfChatzis(planar, lambda_high));
  FragilityBlock dissipative = PlanarBlock(0.2, lambda_high), elastic = PlanarBlock(0.2, lambda_low);
  dissipative.id = "lambda_lon_high";
  elastic.id = "lambda_lon_low";
  const FragilitySummary sum = PlanarFragility({elastic, dissipative}, kPlanarLevels);
  const FragilityBlockResult &low = sum.blocks[0], &high = sum.blocks[1];
  std::printf("λ_lon (h = 0.2 m): AVRF (6) %.3f at %.1f, %.3f at %.1f; PGA [g] / overturned of 16, %.1f | %.1f\n",
              core::AvrfChatzis(planar, lambda_low), lambda_low, core::AvrfChatzis(planar, lambda_high), lambda_high,
              lambda_low, lambda_high);
  for (std::size_t l = 0; l < kPlanarLevels.size(); ++l) {
    std::printf("  %.2f  %2lld | %2lld\n", kPlanarLevels[l], static_cast<long long>(low.levels[l].limit_states[0].exceeded),
                static_cast<long long>(high.levels[l].limit_states[0].exceeded));
    EXPECT_LE(high.levels[l].limit_states[0].exceeded, low.levels[l].limit_states[0].exceeded) << kPlanarLevels[l];
  }
  std::printf("  medians: %.4g g (%s) | %.4g g (%s)\n", low.curves[0].median, ToString(low.curves[0].status),
              high.curves[0].median, ToString(high.curves[0].status));
  EXPECT_LT(TotalOverturns(high), TotalOverturns(low));
  EXPECT_GT(high.curves[0].median, low.curves[0].median);
}

}  // namespace
}  // namespace rockfit::quake
