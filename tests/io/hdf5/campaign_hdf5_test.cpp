#include "rockfit/io/campaign_hdf5.hpp"

#include <cmath>

#include <gtest/gtest.h>

#include "python_h5py.hpp"
#include "rocking_signals.hpp"
#include "rockfit/core/errors.hpp"
#include "rockfit/io/hdf5_transaction.hpp"
#include "scratch_dir.hpp"

namespace rockfit::io {
namespace {

using testing::ScratchDir;

struct Trial {
  Recording recording;
  MetricsSummary metrics;
};

Trial MakeTrial() {
  const core::Block block = testing::PaperLikeBlock();
  testing::PlanarRockingSpec spec;
  spec.duration_s = 6.0;
  const auto motion = testing::SimulatePlanarRocking(block, spec);
  Trial t;
  t.recording = testing::MeasurePlanar(motion, spec.rate_hz, testing::RealisticImu()).recording;
  t.recording.accel_B.assign(t.recording.size(), Eigen::Vector3d(0, 0, 9.81));
  t.recording.gaps.push_back({100, 100 / 256.0, 3 / 256.0, 2});
  t.recording.columns = {"x_CalInertialAndMag.csv: Gyroscope X (deg/s)"};
  t.metrics = ComputeTrialMetrics(t.recording, block, {});
  return t;
}

void WriteCampaign(const std::filesystem::path& path, const Trial& trial) {
  hdf5::Transaction tx(path, {"/blocks/B3", "/trials/B3-A-1"});
  WriteFileAttributes(tx.Root(), "0.1.0");
  WriteBlockHdf5(tx.Root(), "B3", testing::PaperLikeBlock(), "granite");
  WriteTrialHdf5(tx.Root(), "B3-A-1", {"B3", "A", "first"}, trial.recording, trial.metrics, {});
  tx.Commit();
}

TEST(CampaignHdf5, TrialRoundTripsIntoARecording) {
  const ScratchDir dir("campaign_hdf5");
  const Trial trial = MakeTrial();
  WriteCampaign(dir / "c.h5", trial);
  const StoredTrial stored = ReadTrialHdf5(dir / "c.h5", "");  // the only trial
  EXPECT_EQ(stored.id, "B3-A-1");
  EXPECT_EQ(stored.labels.block_id, "B3");
  EXPECT_EQ(stored.labels.position, "A");
  const Recording& r = stored.recording;
  EXPECT_EQ(r.format, "rockfit-hdf5");
  EXPECT_EQ(r.rate_hz, 256.0);
  EXPECT_EQ(r.t_s, trial.recording.t_s);
  EXPECT_EQ(r.w_B, trial.recording.w_B);
  EXPECT_EQ(r.euler_zyx, trial.recording.euler_zyx);
  EXPECT_EQ(r.accel_B, trial.recording.accel_B);
  ASSERT_EQ(r.gaps.size(), 1u);
  EXPECT_EQ(r.gaps[0].missing, 2u);
  EXPECT_EQ(r.columns, trial.recording.columns);
  EXPECT_EQ(stored.euler_corrected_zyx, trial.metrics.correction.euler_corrected_zyx);
  ASSERT_EQ(stored.impact_times_s.size(), trial.metrics.correction.impacts_y.size());
  EXPECT_EQ(stored.status, MetricsStatus::kOk);
  EXPECT_EQ(stored.avrf, trial.metrics.avrf.avrf);
  EXPECT_EQ(stored.opmf, trial.metrics.opmf.opmf);
  // Processing the stored recording again gives the same metrics.
  const MetricsSummary again = ComputeTrialMetrics(ReadRecordingHdf5(dir / "c.h5", "B3-A-1"), testing::PaperLikeBlock(), {});
  EXPECT_EQ(again.avrf.avrf, trial.metrics.avrf.avrf);
}

// The schema of io/README.md ("HDF5 layout"), checked from Python.
std::string SchemaScript(std::size_t n, std::size_t k, std::size_t peaks) {
  return "N, K, P = " + std::to_string(n) + ", " + std::to_string(k) + ", " + std::to_string(peaks) + R"(
import sys, math, h5py
f = h5py.File(sys.argv[1], 'r')
assert f.attrs['rockfit_schema_version'] == 1
assert f.attrs['rockfit_version'] == '0.1.0'
b = f['blocks/B3']
for name, unit_value in [('b1_m', 0.05), ('b2_m', 0.05), ('h_m', 0.2)]:
    assert abs(b.attrs[name] - unit_value) < 1e-15, name
assert b['inertia_com_B_kg_m2'].shape == (3, 3) and b['inertia_com_B_kg_m2'].attrs['units'] == 'kg*m^2'
assert b.attrs['mass_kg'] > 0 and abs(b.attrs['density_kg_m3'] - 2692) < 1e-9
t = f['trials/B3-A-1']
assert t.attrs['block_id'] == 'B3' and t.attrs['position'] == 'A' and t.attrs['rate_hz'] == 256
expect = {
  'time_s': ((N,), 's'), 'w_B_rad_s': ((N, 3), 'rad/s'), 'euler_zyx_raw_rad': ((N, 3), 'rad'),
  'euler_zyx_corrected_rad': ((N, 3), 'rad'), 'accel_B_m_s2': ((N, 3), 'm/s^2'),
  'impacts/time_s': ((K,), 's'), 'impacts/sample_index': ((K,), '1'), 'impacts/phi_y_anchor_rad': ((K,), 'rad'),
  'impacts/omega_peak_rad_s': ((K,), 'rad/s'), 'gaps/sample_index': ((1,), '1'), 'gaps/missing_samples': ((1,), '1'),
  'metrics/avrf_ratios': ((P - 1,), '1'), 'metrics/avrf_peak_time_s': ((P,), 's'),
  'metrics/avrf_peak_angle_rad': ((P,), 'rad'), 'metrics/avrf_uplift_m': ((P,), 'm'),
}
for name, (shape, units) in expect.items():
    assert t[name].shape == shape, (name, t[name].shape, shape)
    assert t[name].attrs['units'] == units, (name, t[name].attrs['units'])
    assert t[name].dtype.kind in 'fi', name
assert t['w_B_rad_s'].attrs['columns'] == 'x, y, z'
assert t['euler_zyx_raw_rad'].attrs['columns'] == 'phi_z, phi_y, phi_x'
m = t['metrics'].attrs
assert m['status'] == 'ok' and m['avrf_status'] == 'ok' and m['opmf_status'] == 'ok'
assert 0.9 < m['avrf'] < 1.0 and m['opmf'] >= 0 and m['avrf_peaks_used'] == P
assert m['uplift_formula'] == 'com' and m['anchor_method'] == 'subsample'
assert list(t['impacts/source'].asstr()[...]) == ['omega_y'] * K
import numpy as np
assert np.all(np.diff(t['time_s'][...]) > 0)
print('ok')
)";
}

TEST(CampaignHdf5, H5pyFindsTheDocumentedNamesShapesAndUnits) {
  ROCKFIT_REQUIRE_H5PY();
  const ScratchDir dir("campaign_hdf5");
  const Trial trial = MakeTrial();
  WriteCampaign(dir / "c.h5", trial);
  const std::size_t n = trial.recording.size();
  const std::size_t k = trial.metrics.correction.impacts_y.size();
  const std::size_t peaks = trial.metrics.avrf.peaks_used;
  const auto result = testing::RunH5pyScript(SchemaScript(n, k, peaks), dir / "c.h5");
  EXPECT_EQ(result.exit_code, 0) << result.out;
  EXPECT_EQ(result.out, "ok\n");
}

TEST(CampaignHdf5, SummaryTablesRoundTripWithMissingValuesAsNaN) {
  const ScratchDir dir("campaign_hdf5");
  CampaignSummary summary;
  TrialRow a;
  a.trial_id = "T1", a.block_id = "B1", a.position = "A", a.status = MetricsStatus::kOk, a.b2_m = 0.03;
  a.opmf = 0.05, a.avrf = 0.93, a.lambda_equivalent = 0.8, a.avrf_peaks_used = 10, a.impacts = 30;
  TrialRow b = a;
  b.trial_id = "T2", b.status = MetricsStatus::kTooFewPeaks, b.message = "only 2 peaks", b.avrf.reset(), b.lambda_equivalent.reset();
  b.mounting = "-x,-y,z";
  b.mounting_check.status = MountingStatus::kOk;
  b.mounting_check.angles_deg = {0.1, -0.2, 1.5};
  summary.trials = {a, b};
  summary.groups = GroupTrials(summary.trials);
  {
    hdf5::Transaction tx(dir / "s.h5", {"/summary"});
    WriteFileAttributes(tx.Root(), "0.1.0");
    WriteSummaryHdf5(tx.Root(), summary);
    tx.Commit();
  }
  const CampaignSummary back = ReadSummaryHdf5(dir / "s.h5");
  ASSERT_EQ(back.trials.size(), 2u);
  EXPECT_EQ(back.trials[1].message, "only 2 peaks");
  EXPECT_FALSE(back.trials[1].avrf.has_value());
  EXPECT_DOUBLE_EQ(*back.trials[0].avrf, 0.93);
  EXPECT_EQ(back.trials[0].mounting, "identity");
  EXPECT_TRUE(std::isnan(back.trials[0].mounting_check.angles_deg.z()));
  EXPECT_EQ(back.trials[1].mounting, "-x,-y,z");
  EXPECT_EQ(back.trials[1].mounting_check.angles_deg, Eigen::Vector3d(0.1, -0.2, 1.5));
  ASSERT_EQ(back.groups.size(), 1u);
  EXPECT_EQ(back.groups[0].n_avrf, 1u);
  EXPECT_FALSE(back.groups[0].avrf_std.has_value());
  EXPECT_DOUBLE_EQ(*back.groups[0].opmf_mean, 0.05);
  if (!testing::HaveH5py()) return;
  const auto result = testing::RunH5pyScript(R"(
import sys, math, h5py
g = h5py.File(sys.argv[1], 'r')['summary/groups']
assert g['n_trials'][0] == 2 and g['n_avrf'][0] == 1
assert math.isnan(g['avrf_std'][0]) and g['avrf_mean'].attrs['units'] == '1'
assert g['b2_m'].attrs['units'] == 'm'
assert list(h5py.File(sys.argv[1], 'r')['summary/trials/status'].asstr()[...]) == ['ok', 'too_few_peaks']
print('ok')
)", dir / "s.h5");
  EXPECT_EQ(result.out, "ok\n");
}

TEST(CampaignHdf5, ReadingNamesTheTrialsThatExist) {
  const ScratchDir dir("campaign_hdf5");
  const Trial trial = MakeTrial();
  WriteCampaign(dir / "c.h5", trial);
  try {
    ReadRecordingHdf5(dir / "c.h5", "B3-A-2");
    FAIL();
  } catch (const BadInput& e) {
    EXPECT_NE(std::string(e.what()).find("no trial 'B3-A-2'; the file holds: B3-A-1"), std::string::npos) << e.what();
  }
  EXPECT_EQ(ListTrialsHdf5(dir / "c.h5"), (std::vector<std::string>{"B3-A-1"}));
}

TEST(CampaignHdf5, FilesWithoutOrWithANewerSchemaAreBadInput) {
  const ScratchDir dir("campaign_hdf5");
  {
    hdf5::File f = hdf5::File::Create(dir / "plain.h5");
    f.Root().CreateGroup("trials/T1");
    f.Close();
  }
  EXPECT_THROW(ReadRecordingHdf5(dir / "plain.h5", "T1"), BadInput);
  {
    hdf5::File f = hdf5::File::Create(dir / "future.h5");
    f.Root().SetInt("rockfit_schema_version", kHdf5SchemaVersion + 1);
    f.Close();
  }
  try {
    ListTrialsHdf5(dir / "future.h5");
    FAIL();
  } catch (const BadInput& e) {
    EXPECT_NE(std::string(e.what()).find("update rockfit"), std::string::npos);
  }
}

TEST(CampaignHdf5, DamagedTrialDataIsBadInputNotACrash) {
  const ScratchDir dir("campaign_hdf5");
  const Trial trial = MakeTrial();
  WriteCampaign(dir / "c.h5", trial);
  {
    hdf5::Transaction tx(dir / "c.h5", {"/trials/B3-A-1/time_s"});
    std::vector<double> t = trial.recording.t_s;
    std::swap(t[10], t[11]);  // non-increasing time
    tx.Root().OpenGroup("trials/B3-A-1").WriteDoubles("time_s", t, "s");
    tx.Commit();
  }
  try {
    ReadRecordingHdf5(dir / "c.h5", "B3-A-1");
    FAIL();
  } catch (const BadInput& e) {
    EXPECT_NE(std::string(e.what()).find("time_s is not finite and strictly increasing at row 11"), std::string::npos)
        << e.what();
  }
  {
    hdf5::Transaction tx(dir / "c.h5", {"/trials/B3-A-1/w_B_rad_s"});
    tx.Root().OpenGroup("trials/B3-A-1").WriteVectors("w_B_rad_s", {Eigen::Vector3d::Zero()}, "rad/s");
    tx.Commit();
  }
  EXPECT_THROW(ReadRecordingHdf5(dir / "c.h5", "B3-A-1"), BadInput);
}

}  // namespace
}  // namespace rockfit::io

#include "rockfit/io/load_recording.hpp"

namespace rockfit::io {
namespace {

TEST(CampaignHdf5, TheMountingAndItsEstimateAreStoredWithTheTrial) {
  const testing::ScratchDir dir("campaign_hdf5");
  Trial trial = MakeTrial();
  trial.recording.mounting = "0.999657325,0,0,0.0261769483";
  MountingCheck& c = trial.recording.mounting_check;
  c.status = MountingStatus::kOk;
  c.given = "identity";
  c.estimated = true;
  c.angles_deg = {0.01, -0.02, 3.0};
  c.std_error_deg = {0.02, 0.05, 0.03};
  c.determined = {true, true, true};
  c.turn_before_fall_deg = 0.63;
  WriteCampaign(dir / "c.h5", trial);
  const hdf5::File file = hdf5::File::Open(dir / "c.h5");
  const hdf5::Group g = file.Root().OpenGroup("trials/B3-A-1");
  EXPECT_EQ(g.GetString("mounting"), trial.recording.mounting);
  EXPECT_EQ(g.GetString("mounting_given"), "identity");
  EXPECT_EQ(g.GetInt("mounting_estimated"), 1);
  EXPECT_EQ(g.GetString("mounting_status"), "ok");
  EXPECT_EQ(g.ReadDoubles("mounting_angles_deg"), (std::vector<double>{0.01, -0.02, 3.0}));
  EXPECT_EQ(g.ReadDoubles("mounting_std_error_deg"), (std::vector<double>{0.02, 0.05, 0.03}));
  EXPECT_EQ(g.ReadInts("mounting_determined"), (std::vector<std::int64_t>{1, 1, 1}));
  EXPECT_NEAR(*g.GetDouble("mounting_disagreement_deg"), std::sqrt(0.0001 + 0.0004 + 9.0), 1e-12);
  EXPECT_EQ(g.GetDouble("mounting_turn_before_fall_deg"), 0.63);
  EXPECT_EQ(ReadRecordingHdf5(dir / "c.h5", "").mounting, trial.recording.mounting);
}

TEST(CampaignHdf5, LoadRecordingReadsTheTrialOfAOneTrialFile) {
  const testing::ScratchDir dir("campaign_hdf5");
  const Trial trial = MakeTrial();
  WriteCampaign(dir / "c.h5", trial);
  const Recording r = LoadRecording(dir / "c.h5");
  EXPECT_EQ(r.format, "rockfit-hdf5");
  EXPECT_EQ(r.w_B, trial.recording.w_B);
  LoadOptions mounted;
  mounted.mounting = Mounting::Parse("x,-y,-z");
  EXPECT_THROW(LoadRecording(dir / "c.h5", mounted), InvalidArgument);
  LoadOptions wrong_rate;
  wrong_rate.rate_hz = 100.0;
  EXPECT_THROW(LoadRecording(dir / "c.h5", wrong_rate), BadInput);
}

}  // namespace
}  // namespace rockfit::io
