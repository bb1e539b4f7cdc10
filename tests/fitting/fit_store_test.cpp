// /fits and /fit_summary in rockfit's HDF5: what is written is read back; the tables are the statistics of the
// stored fits.
#include "rockfit/fitting/fit_store.hpp"

#include <cmath>
#include <filesystem>

#include <gtest/gtest.h>

#include "rockfit/core/errors.hpp"
#include "rockfit/io/hdf5_file.hpp"
#include "synth_trial.hpp"

namespace rockfit::fitting {
namespace {

std::filesystem::path TempFile(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / ("rockfit_fit_store_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  return dir / name;
}

// One quick fit (no global stage, a small budget) of a synthetic trial.
const TrialFit& QuickFit() {
  static const TrialFit fit = [] {
    const auto trial = testing::MakeSynthTrial(0.2, 0.8, -2.0, 0.6, 31);
    TrialFitOptions options;  // the store is under test, not the fit: a small budget
    options.fit.global.enabled = false;
    options.fit.method = FitMethod::kNelderMead;
    options.fit.nelder_mead.max_evaluations = 60;
    return FitTrial(trial.block, trial.signal, ParameterSet::Defaults(), options);
  }();
  return fit;
}

TEST(FitStore, AFitReadsBackAsWritten) {
  const auto path = TempFile("one.h5");
  const TrialFit& fit = QuickFit();
  {
    io::hdf5::File file = io::hdf5::File::Create(path);
    WriteFitHdf5(file.Root(), "T1", {"B1", "A", 0.05, 0.04, 0.2}, fit, "{}", "0123456789abcdef");
    file.Close();
  }
  const io::hdf5::File file = io::hdf5::File::Open(path);
  const StoredFit s = ReadFitHdf5(file.Root(), "T1");
  EXPECT_EQ(s.status, "ok");
  EXPECT_EQ(s.labels.block_id, "B1");
  EXPECT_EQ(s.settings_hash, "0123456789abcdef");
  EXPECT_EQ(s.epsilon_rad_s, fit.summary.epsilon_rad_s);
  EXPECT_EQ(s.t_end_s, fit.summary.t_end_s);
  for (ParameterId id : kAllParameters) EXPECT_EQ(*s.Value(Name(id)), fit.summary.parameters.value(id)) << Name(id);
  ASSERT_EQ(s.time_s.size(), fit.trace.t_s.size());
  EXPECT_EQ(s.w_simulated_B, fit.trace.w_B);
  EXPECT_EQ(s.time_s.front(), fit.summary.parameters.value(ParameterId::kT0));  // the window starts at t0
  EXPECT_LE(s.time_s.back(), fit.summary.t_end_s);
  EXPECT_EQ(s.impact_time_s.size(), fit.trace.events.size());
  EXPECT_EQ(*StoredSettingsHash(file.Root(), "T1"), "0123456789abcdef");
  EXPECT_THROW(ReadFitHdf5(file.Root(), "T2"), BadInput);
}

TEST(FitStore, TablesHoldEveryTrialAndTheGroupStatisticsOfTheSuccessfulOnes) {
  const auto path = TempFile("tables.h5");
  const TrialFit& fit = QuickFit();
  TrialFit other = fit;  // a second trial of the same group with another λ_lon
  other.summary.parameters[ParameterId::kLambdaLon].value += 0.2;
  {
    io::hdf5::File file = io::hdf5::File::Create(path);
    const FitLabels labels{"B1", "A", 0.05, 0.04, 0.2};
    WriteFitHdf5(file.Root(), "T1", labels, fit, "{}", "h1");
    WriteFitHdf5(file.Root(), "T2", labels, other, "{}", "h2");
    WriteFailedFitHdf5(file.Root(), "T3", labels, "no impact found", "h3");
    WriteFitTablesHdf5(file.Root());
    file.Close();
  }
  const io::hdf5::File file = io::hdf5::File::Open(path);
  EXPECT_FALSE(StoredSettingsHash(file.Root(), "T3").has_value());  // a failed trial is fitted again on resume
  const io::hdf5::Group trials = file.Root().OpenGroup("fit_summary/trials");
  EXPECT_EQ(trials.ReadStrings("trial_id"), (std::vector<std::string>{"T1", "T2", "T3"}));
  EXPECT_EQ(trials.ReadStrings("status"), (std::vector<std::string>{"ok", "ok", "failed"}));
  const std::vector<double> lon = trials.ReadDoubles("lambda_lon");
  EXPECT_TRUE(std::isnan(lon[2]));
  const io::hdf5::Group groups = file.Root().OpenGroup("fit_summary/groups");
  EXPECT_EQ(groups.ReadInts("n_trials"), (std::vector<std::int64_t>{3}));
  EXPECT_EQ(groups.ReadInts("n_ok"), (std::vector<std::int64_t>{2}));
  const double a = fit.summary.parameters.value(ParameterId::kLambdaLon);
  const double b = other.summary.parameters.value(ParameterId::kLambdaLon);
  EXPECT_NEAR(groups.ReadDoubles("lambda_lon_mean")[0], 0.5 * (a + b), 1e-12);
  EXPECT_NEAR(groups.ReadDoubles("lambda_lon_std")[0], std::abs(a - b) / std::sqrt(2.0), 1e-12);  // n − 1
  EXPECT_EQ(groups.ReadInts("n_lambda_lon")[0], 2);
}

}  // namespace
}  // namespace rockfit::fitting
