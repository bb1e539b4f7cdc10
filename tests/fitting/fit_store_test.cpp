// The fitting library's part of an HDF5 file (fit_store.hpp): a fit group and the campaign tables read back as
// written, the settings hash, and what older or damaged files read as.
#include "rockfit/fitting/fit_store.hpp"

#include <cmath>

#include <gtest/gtest.h>

#include "campaign_trials.hpp"
#include "rockfit/core/errors.hpp"
#include "rockfit/fitting/release_tilt_check.hpp"
#include "rockfit/io/hdf5_transaction.hpp"
#include "scratch_dir.hpp"

namespace rockfit::fitting {
namespace {

using testing::QuickFitOptions;
using testing::QuickProblem;
using testing::ScratchDir;

// Equal, or both NaN (open interval ends).
void ExpectSameValue(double stored, double written, const std::string& what) {
  if (std::isnan(written)) {
    EXPECT_TRUE(std::isnan(stored)) << what;
  } else {
    EXPECT_EQ(stored, written) << what;
  }
}

struct WrittenFit {
  FitSummary summary;
  std::string settings;
};

// Fits the trial of `seed` and commits it as /fits/<trial> of `path`.
WrittenFit WriteOneFit(const std::filesystem::path& path, const std::string& trial, const std::string& position,
                       std::uint64_t seed) {
  const TrialProblem p = QuickProblem(seed);
  WrittenFit w{Fit(p.objective, p.start, QuickFitOptions()), "quick fit; seed=" + std::to_string(seed)};
  io::hdf5::Transaction tx(path, {"/fits/" + trial});
  WriteFitGroup(tx.Root(), trial, {"b1", position, ""}, p.objective, w.settings, w.summary);
  tx.Commit();
  return w;
}

TEST(FitStore, FitGroupReadsBackItsParametersIntervalsAndLabels) {
  const ScratchDir dir("fit_store_round_trip");
  const WrittenFit w = WriteOneFit(dir / "fits.h5", "T1", "A", 3);
  const io::hdf5::File file = io::hdf5::File::Open(dir / "fits.h5");
  const io::hdf5::Group fit = file.Root().OpenGroup("fits/T1");
  const StoredParameters stored = ReadFitParameters(fit);
  // One row per reported parameter: the release roll, fixed at 0 here, has none.
  const std::vector<ParameterId> reported = w.summary.parameters.ReportedIds();
  ASSERT_EQ(stored.size(), kNumParameters - 1);
  ASSERT_EQ(stored.size(), reported.size());
  EXPECT_GE(stored.Row(Name(ParameterId::kReleaseRoll)), stored.size());
  for (std::size_t row = 0; row < reported.size(); ++row) {
    const ParameterId id = reported[row];
    const std::size_t k = static_cast<std::size_t>(id);
    EXPECT_EQ(stored.name[row], Name(id));
    EXPECT_EQ(stored.unit[row], Unit(id));
    EXPECT_EQ(stored.Row(Name(id)), row);
    EXPECT_EQ(stored.value[row], w.summary.parameters.value(id)) << Name(id);
    EXPECT_EQ(stored.lower[row], w.summary.parameters[id].lower) << Name(id);
    EXPECT_EQ(stored.upper[row], w.summary.parameters[id].upper) << Name(id);
    ExpectSameValue(stored.interval_95_lower[row], w.summary.uncertainty.interval_95[k][0], Name(id));
    ExpectSameValue(stored.interval_95_upper[row], w.summary.uncertainty.interval_95[k][1], Name(id));
    ExpectSameValue(stored.interval_68_lower[row], w.summary.uncertainty.interval_68[k][0], Name(id));
    const auto& determined = w.summary.uncertainty.determined[k];
    EXPECT_EQ(stored.determined[row], determined ? ToString(*determined) : "fixed") << Name(id);
  }
  const StoredFitLabels labels = ReadFitLabels(fit);
  EXPECT_EQ(labels.block, "b1");
  EXPECT_EQ(labels.position, "A");
  EXPECT_EQ(labels.settings_hash, SettingsHash(w.settings));
  EXPECT_EQ(labels.feasible, w.summary.feasible);
  EXPECT_EQ(labels.epsilon_rad_s, w.summary.epsilon_rad_s);
  EXPECT_EQ(labels.simulations, w.summary.simulations);
  EXPECT_EQ(StoredFitTrials(file.Root()), std::vector<std::string>{"T1"});
  EXPECT_EQ(StoredSettingsHashes(dir / "fits.h5").at("T1"), SettingsHash(w.settings));
}

TEST(FitStore, GroupTablesReadBackAsWrittenFromEveryFit) {
  const ScratchDir dir("fit_store_groups");
  const std::filesystem::path path = dir / "fits.h5";
  WriteOneFit(path, "T1", "A", 3);
  WriteOneFit(path, "T2", "A", 4);
  const WrittenFit b = WriteOneFit(path, "T3", "B", 5);
  std::vector<GroupSummary> written;
  {
    io::hdf5::Transaction tx(path, {"/summary/fits"});
    written = WriteFitSummaryTables(tx.Root());
    tx.Commit();
  }
  ASSERT_EQ(written.size(), 2u);
  EXPECT_EQ(written[0].n, 2);
  EXPECT_EQ(written[1].n, 1);
  EXPECT_EQ(written[1].mean.at("lambda"), b.summary.parameters.value(ParameterId::kLambda)) << "one trial: its value";
  EXPECT_TRUE(std::isnan(written[1].std_dev.at("lambda"))) << "no spread from one trial";
  const io::hdf5::File file = io::hdf5::File::Open(path);
  ASSERT_TRUE(HasFitGroupSummaries(file.Root()));
  EXPECT_EQ(file.Root().ReadStrings("summary/fits/per_trial/trial"), (std::vector<std::string>{"T1", "T2", "T3"}));
  const std::vector<GroupSummary> read = ReadFitGroupSummaries(file.Root());
  ASSERT_EQ(read.size(), written.size());
  for (std::size_t g = 0; g < read.size(); ++g) {
    EXPECT_EQ(read[g].block, written[g].block);
    EXPECT_EQ(read[g].position, written[g].position);
    EXPECT_EQ(read[g].n, written[g].n);
    for (const char* name : kSummaryParameters) {
      ExpectSameValue(read[g].mean.at(name), written[g].mean.at(name), name);
      ExpectSameValue(read[g].std_dev.at(name), written[g].std_dev.at(name), name);
      const PooledEstimate& r = read[g].pooled.at(name);
      const PooledEstimate& w = written[g].pooled.at(name);
      EXPECT_EQ(r.n_pooled, w.n_pooled) << name;
      if (w.n_pooled > 0) ExpectSameValue(r.pooled, w.pooled, name);
      ExpectSameValue(r.interval_95[0], w.interval_95[0], name);
      ExpectSameValue(r.interval_95[1], w.interval_95[1], name);
      ExpectSameValue(r.consistency_p, w.consistency_p, name);
    }
  }
}

// A fit compared with the tilt at rest keeps z, the verdict and the sentence in its group and in
// /summary/fits/per_trial; a fit without the comparison reads NaN, -1 and an empty sentence.
TEST(FitStore, ReleaseTiltCheckReadsBackFromTheFitAndThePerTrialTable) {
  const ScratchDir dir("fit_store_release_tilt");
  const std::filesystem::path path = dir / "fits.h5";
  WriteOneFit(path, "T1", "A", 3);
  const TrialProblem p = QuickProblem(4);
  FitSummary compared = Fit(p.objective, p.start, QuickFitOptions());
  io::MountingCheck mounting;
  mounting.status = io::MountingStatus::kOk;
  mounting.determined = {true, true, true};
  mounting.release_tilt_rad = compared.parameters.value(ParameterId::kAlpha) - 0.01;  // 10 mrad below the fit
  mounting.release_tilt_std_error_rad = 0.002;
  AttachReleaseTiltCheck(mounting, &compared);
  ASSERT_TRUE(compared.release_tilt && compared.release_tilt->available);
  ASSERT_FALSE(compared.release_tilt->consistent) << compared.release_tilt->reason;
  {
    io::hdf5::Transaction tx(path, {"/fits/T2"});
    WriteFitGroup(tx.Root(), "T2", {"b1", "A", ""}, p.objective, "quick fit; seed=4", compared);
    tx.Commit();
  }
  {
    io::hdf5::Transaction tx(path, {"/summary/fits"});
    WriteFitSummaryTables(tx.Root());
    tx.Commit();
  }
  const io::hdf5::File file = io::hdf5::File::Open(path);
  const StoredFitLabels without = ReadFitLabels(file.Root().OpenGroup("fits/T1"));
  EXPECT_TRUE(std::isnan(without.release_tilt_z));
  EXPECT_EQ(without.release_tilt_consistent, -1);
  const StoredFitLabels with = ReadFitLabels(file.Root().OpenGroup("fits/T2"));
  EXPECT_EQ(with.release_tilt_z, compared.release_tilt->z);
  EXPECT_GT(with.release_tilt_z, kReleaseTiltMaxZ);
  EXPECT_EQ(with.release_tilt_consistent, 0);
  EXPECT_EQ(with.release_tilt_check, compared.release_tilt->reason);
  const std::vector<double> z = file.Root().ReadDoubles("summary/fits/per_trial/release_tilt_z");
  ASSERT_EQ(z.size(), 2u);
  EXPECT_TRUE(std::isnan(z[0]));
  EXPECT_EQ(z[1], compared.release_tilt->z);
  EXPECT_EQ(file.Root().ReadInts("summary/fits/per_trial/release_tilt_consistent"),
            (std::vector<std::int64_t>{-1, 0}));
}

TEST(FitStore, SettingsHashIsSixteenHexDigitsThatFollowTheText) {
  const std::string a = SettingsHash("rockfit-fit v4; method=auto");
  EXPECT_EQ(a.size(), 16u);
  EXPECT_EQ(a.find_first_not_of("0123456789abcdef"), std::string::npos) << a;
  EXPECT_EQ(a, SettingsHash("rockfit-fit v4; method=auto"));
  EXPECT_NE(a, SettingsHash("rockfit-fit v4; method=ceres"));
}

TEST(FitStore, NoStoredHashesForAMissingFileAFileThatIsNotHdf5OrOneWithoutFits) {
  const ScratchDir dir("fit_store_no_hashes");
  EXPECT_TRUE(StoredSettingsHashes(dir / "missing.h5").empty());
  EXPECT_TRUE(StoredSettingsHashes(dir.Write("text.h5", "not HDF5\n")).empty());
  { io::hdf5::File::Create(dir / "empty.h5").Root().CreateGroup("trials"); }
  EXPECT_TRUE(StoredSettingsHashes(dir / "empty.h5").empty());
}

TEST(FitStore, ParameterTableWithoutIntervalsReadsThemOpenAndMismatchedColumnsAreBadInput) {
  const ScratchDir dir("fit_store_old_table");
  {
    const io::hdf5::File file = io::hdf5::File::Create(dir / "old.h5");
    const io::hdf5::Group t = file.Root().CreateGroup("fits/T1/parameters");
    t.WriteStrings("name", {"alpha", "lambda"});
    t.WriteDoubles("value", {0.2, 0.8}, "per row: see the unit dataset");
    const io::hdf5::Group bad = file.Root().CreateGroup("fits/T2/parameters");
    bad.WriteStrings("name", {"alpha", "lambda"});
    bad.WriteDoubles("value", {0.2}, "per row: see the unit dataset");
  }
  const io::hdf5::File file = io::hdf5::File::Open(dir / "old.h5");
  const StoredParameters old = ReadFitParameters(file.Root().OpenGroup("fits/T1"));
  ASSERT_EQ(old.size(), 2u);
  EXPECT_EQ(old.value[old.Row("lambda")], 0.8);
  EXPECT_EQ(old.Row("tau_edge"), old.size()) << "a parameter the table lacks";
  EXPECT_TRUE(std::isnan(old.interval_95_lower[0]));
  EXPECT_EQ(old.determined[0], "");
  EXPECT_THROW(ReadFitParameters(file.Root().OpenGroup("fits/T2")), BadInput);
}

}  // namespace
}  // namespace rockfit::fitting
