#include "rockfit/io/impact_detection.hpp"

#include <cmath>

#include <gtest/gtest.h>

#include "rocking_signals.hpp"
#include "rockfit/core/errors.hpp"

namespace rockfit::io {
namespace {

using testing::MeasurePlanar;
using testing::PaperLikeBlock;
using testing::PlanarRockingSpec;
using testing::SimulatePlanarRocking;

TEST(ImpactDetection, FindsEveryImpactWithinOneSampleOfItsTime) {
  PlanarRockingSpec spec;
  spec.duration_s = 6.0;
  const auto motion = SimulatePlanarRocking(PaperLikeBlock(), spec);
  const Recording rec = MeasurePlanar(motion, spec.rate_hz, testing::RealisticImu()).recording;
  const std::vector<Peak> peaks = DetectRatePeaks(rec, 1, {});
  // Impacts with a pre-impact rate above 4× the prominence threshold must all be found, nothing else — except
  // within the last 0.1 s, where the fall of |ω| after the impact (its prominence) is cut off by the end.
  std::size_t strong = 0;
  for (std::size_t i = 0; i < motion.impact_times_s.size(); ++i) {
    strong += std::abs(motion.omega_minus_rad_s[i]) > 0.2 && motion.impact_times_s[i] < spec.duration_s - 0.1 ? 1 : 0;
  }
  ASSERT_GE(peaks.size(), strong);
  ASSERT_LE(peaks.size(), motion.impact_times_s.size());
  const double dt = 1.0 / spec.rate_hz;
  for (std::size_t i = 0; i < peaks.size(); ++i) {
    EXPECT_NEAR(rec.t_s[peaks[i].index], motion.impact_times_s[i], dt * 1.0001) << "impact " << i;
  }
}

TEST(ImpactDetection, RingingAfterAnImpactIsNotASecondImpact) {
  PlanarRockingSpec spec;
  const auto motion = SimulatePlanarRocking(PaperLikeBlock(), spec);
  testing::MeasurementModel model;
  model.ringing_fraction = 0.4;  // strong ringing: 40 % of the impact rate at 80 Hz
  const Recording rec = MeasurePlanar(motion, spec.rate_hz, model).recording;
  ImpactDetectionOptions no_separation;
  no_separation.min_separation_s = 0.0;
  no_separation.min_prominence_rad_s = 0.0;
  EXPECT_GT(DetectRatePeaks(rec, 1, no_separation).size(), 2 * motion.impact_times_s.size());
  EXPECT_EQ(DetectRatePeaks(rec, 1, {}).size(), motion.impact_times_s.size());
}

TEST(ImpactDetection, NoiseAloneHasNoImpacts) {
  PlanarRockingSpec spec;
  spec.release_s = 100.0;  // never released within the recording
  const auto motion = SimulatePlanarRocking(PaperLikeBlock(), spec);
  const Recording rec = MeasurePlanar(motion, spec.rate_hz, testing::RealisticImu()).recording;
  EXPECT_TRUE(DetectRatePeaks(rec, 1, {}).empty());
  EXPECT_TRUE(DetectRatePeaks(rec, 0, {}).empty());
}

TEST(ImpactDetection, BadOptionsAndRatesAreRejected) {
  Recording rec;
  rec.t_s = {0.0, 0.1, 0.2};
  rec.w_B = {Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};
  EXPECT_THROW(DetectRatePeaks(rec, 1, {}), BadInput);  // rate 0
  rec.rate_hz = 10.0;
  ImpactDetectionOptions bad;
  bad.min_separation_s = -1.0;
  EXPECT_THROW(DetectRatePeaks(rec, 1, bad), InvalidArgument);
  rec.w_B[1].y() = NAN;
  EXPECT_THROW(DetectRatePeaks(rec, 1, {}), BadInput);
}

}  // namespace
}  // namespace rockfit::io
