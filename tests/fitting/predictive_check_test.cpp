// The predictive check (predictive_check.hpp) on trials of the analytic test model, own fits taken at the truth:
// trials that share λ, λ_lat, λ_lon predict each other as well as their own fits do, a trial whose λ_lon is 50 %
// off is predicted at least twice as badly, and the leave-one-out pooling uses exactly the other trials of the group.
// Then rolled `synth` releases (the simulator and the x-IMU model): each left-out trial's release roll is fitted
// again with its t0 and α, from the data, and found; held at 0 instead, the roll shows as a poor prediction.
#include "rockfit/fitting/predictive_check.hpp"

#include <cmath>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "analytic_trial.hpp"
#include "build_type.hpp"
#include "rockfit/core/errors.hpp"
#include "rockfit/fitting/trial_problem.hpp"
#include "synth_trial.hpp"

namespace rockfit::fitting {
namespace {

struct Campaign {
  std::vector<testing::AnalyticTrial> trials;
  std::vector<OwnFit> fits;
};

// Trials of one block and position with α, t0 and noise differing; own fits at the truth with intervals of ±1 %
// (a stand-in for the fitter, whose recovery of the truth is tested elsewhere).
Campaign MakeCampaign(const std::vector<double>& lambda_lon) {
  Campaign c;
  for (std::size_t i = 0; i < lambda_lon.size(); ++i) {
    testing::SyntheticSignalOptions o = testing::RealisticDisturbances(40 + i);
    o.t0_s = 0.5 + 0.02 * static_cast<double>(i);
    c.trials.push_back(testing::MakeAnalyticTrial(0.19 + 0.007 * static_cast<double>(i), 0.8, -2.0, lambda_lon[i], o));
    const testing::AnalyticTrial& t = c.trials.back();
    OwnFit f;
    f.trial = "T" + std::to_string(i + 1);
    f.block = "B";
    f.position = "A";
    f.values = t.truth;
    f.epsilon_rad_s = t.MakeObjective(t.Bounded(BoundsSet::kEmpirical)).Evaluate(t.truth).epsilon_rad_s;
    for (ParameterId id : kAllParameters) {
      const std::size_t k = static_cast<std::size_t>(id);
      const double v = t.truth.value(id), half = 0.01 * std::max(std::abs(v), 0.01);
      f.interval_95[k] = {v - half, v + half};
      f.determined[k] = true;
    }
    c.fits.push_back(f);
  }
  return c;
}

ValidationSummary Check(const Campaign& c) {
  return RunPredictiveCheck(c.fits, [&c](std::size_t i) {
    const testing::AnalyticTrial& t = c.trials[i];
    const ParameterSet bounded = t.Bounded(BoundsSet::kEmpirical);
    return PreparedTrial{t.MakeObjective(bounded), bounded, FitOptions{}, nullptr, std::nullopt};
  });
}

TEST(PredictiveCheck, TrialsSharingTheirImpactParametersPredictEachOtherAsWellAsTheirOwnFits) {
  const ValidationSummary s = Check(MakeCampaign({0.6, 0.6, 0.6}));
  ASSERT_EQ(s.trials.size(), 3u);
  for (const TrialPrediction& t : s.trials) {
    ASSERT_TRUE(t.predicted) << t.message;
    EXPECT_EQ(t.n_others, 2);
    EXPECT_LE(t.ratio, 1.5) << t.trial;
    EXPECT_TRUE(t.transfers);
    EXPECT_TRUE(t.overlaps_all);
    EXPECT_NEAR(t.held[2], 0.6, 1e-9);
  }
  ASSERT_EQ(s.groups.size(), 1u);
  EXPECT_EQ(s.groups[0].n_predicted, 3);
  EXPECT_EQ(s.groups[0].n_transfer, 3);
  EXPECT_GT(s.simulations, 0);
}

TEST(PredictiveCheck, ATrialWhoseLambdaLonIsFiftyPercentOffIsPredictedAtLeastTwiceAsBadly) {
  const ValidationSummary s = Check(MakeCampaign({0.6, 0.6, 0.6, 0.9}));
  const TrialPrediction& off = s.trials.back();
  ASSERT_TRUE(off.predicted) << off.message;
  EXPECT_NEAR(off.held[2], 0.6, 1e-9);  // pooled from the three others only
  EXPECT_GE(off.ratio, 2.0);
  EXPECT_FALSE(off.transfers);
  EXPECT_FALSE(off.overlaps[2]);  // λ_lon: 0.9 ± 0.009 against 0.6 ± …
  EXPECT_TRUE(off.overlaps[0]);
}

TEST(PredictiveCheck, PoolingLeavesOutTheTrialAndOtherGroups) {
  Campaign c = MakeCampaign({0.6, 0.7, 0.8});
  c.fits[2].position = "B";  // alone in its group
  int n_others = -1;
  const auto pooled = PoolOthers(c.fits, 0, &n_others);
  EXPECT_EQ(n_others, 1);
  EXPECT_NEAR(pooled[2].pooled, 0.7, 1e-12);
  EXPECT_EQ(pooled[2].n_pooled, 1);

  const ValidationSummary s = Check(c);
  EXPECT_FALSE(s.trials[2].predicted);
  EXPECT_NE(s.trials[2].message.find("no other fitted trial"), std::string::npos);
  const nlohmann::json j = nlohmann::json::parse(ValidationJson(s));
  EXPECT_TRUE(j["trials"][2]["ratio"].is_null());
  EXPECT_EQ(j["groups"].size(), 2u);
}

TEST(PredictiveCheck, AnInfeasibleOwnFitIsNotPredictedAndNotPooled) {
  Campaign c = MakeCampaign({0.6, 0.6, 0.6});
  c.fits[1].feasible = false;
  c.fits[1].message = "unreadable";
  const ValidationSummary s = Check(c);
  EXPECT_FALSE(s.trials[1].predicted);
  EXPECT_NE(s.trials[1].message.find("unreadable"), std::string::npos);
  EXPECT_EQ(s.trials[0].n_others, 1);
}

TEST(PredictiveCheck, WhereTheOwnFitEndedItsWindowElsewhereBothEpsilonsAreTakenOverTheProblemsWindow) {
  Campaign c = MakeCampaign({0.6, 0.6, 0.6});
  auto problem_end_s = [&c](std::size_t i) {
    return c.trials[i].MakeObjective(c.trials[i].Bounded(BoundsSet::kEmpirical)).t_end_s();
  };
  const double own_epsilon_here_rad_s = c.fits[0].epsilon_rad_s;  // at the truth over the problem's window
  c.fits[0].t_end_s = problem_end_s(0) + 0.3;  // as if the own fit had extended its window
  c.fits[0].epsilon_rad_s = 5.0 * own_epsilon_here_rad_s;  // and its ε over that window were larger
  const ValidationSummary s = Check(c);
  ASSERT_TRUE(s.trials[0].predicted) << s.trials[0].message;
  EXPECT_DOUBLE_EQ(s.trials[0].t_end_s, problem_end_s(0));
  EXPECT_NEAR(s.trials[0].epsilon_own_rad_s, own_epsilon_here_rad_s, 1e-12 * own_epsilon_here_rad_s);
  EXPECT_LE(s.trials[0].ratio, 1.5);  // the λ's are shared: judged over the same nodes, they transfer
  EXPECT_DOUBLE_EQ(s.trials[1].t_end_s, problem_end_s(1));  // NaN own window: the problem's
  EXPECT_FALSE(s.trials[0].release_roll_fitted);          // the analytic model's β is held
  const nlohmann::json j = nlohmann::json::parse(ValidationJson(s));
  EXPECT_DOUBLE_EQ(j["trials"][0]["t_end"].get<double>(), problem_end_s(0));
  EXPECT_FALSE(j["trials"][0]["release_roll_fitted"].get<bool>());
}

// Three releases of one block with the same λ, λ_lat, λ_lon (MakeRolledSynthTrial: 0.9, 0.5, 0.8), each with its
// own tilt, roll and noise; own fits at the truth (a stand-in for the fitter) except the release, which is the data
// estimate, so that the prediction must find t0, α and β itself.
struct RolledCampaign {
  std::vector<testing::SynthTrial> trials;
  std::vector<TrialProblem> problems;
  std::vector<OwnFit> fits;
};

RolledCampaign MakeRolledCampaign(ReleaseRollMode mode) {
  struct Release {
    double alpha_rad, roll_rad;
    std::uint64_t seed;
  };
  const Release releases[] = {{0.15, 0.002, 11}, {0.18, -0.003, 12}, {0.21, -0.003, 13}};
  RolledCampaign c;
  for (const Release& r : releases) {
    c.trials.push_back(testing::MakeRolledSynthTrial(r.alpha_rad, r.roll_rad, r.seed));
    const testing::SynthTrial& t = c.trials.back();
    TrialProblemOptions options;
    options.release_roll.mode = mode;
    c.problems.push_back(PrepareTrialProblem(t.signal, t.block, ParameterSet::Defaults(), options));
    const TrialProblem& p = c.problems.back();
    OwnFit f;
    f.trial = "T" + std::to_string(c.fits.size() + 1);
    f.block = "B";
    f.position = "A";
    f.values = t.truth;
    for (ParameterId id : {ParameterId::kT0, ParameterId::kAlpha, ParameterId::kReleaseRoll}) {
      f.values[id].value = p.start.value(id);
    }
    f.epsilon_rad_s = p.objective.Evaluate(t.truth).epsilon_rad_s;
    for (ParameterId id : kPooledImpactParameters) {
      const std::size_t k = static_cast<std::size_t>(id);
      const double v = t.truth.value(id);
      f.interval_95[k] = {v - 0.01 * std::abs(v), v + 0.01 * std::abs(v)};
      f.determined[k] = true;
    }
    c.fits.push_back(f);
  }
  return c;
}

ValidationSummary Check(const RolledCampaign& c) {
  return RunPredictiveCheck(c.fits, [&c](std::size_t i) {
    return PreparedTrial{c.problems[i].objective, c.problems[i].start, FitOptions{}, nullptr, c.problems[i].release_roll};
  });
}

// The roll refitted with t0 and α, from the data estimate, with the impact parameters held at the truth: within
// 0.1 mrad, 5 % of the smallest roll here (the lateral rocking of the whole fall fixes it; measured: 1.2 µrad).
constexpr double kRollTolerance_rad = 1e-4;

TEST(PredictiveCheck, RolledReleasesSharingTheirImpactParametersPredictEachOtherWithTheirRollsRefitted) {
  ROCKFIT_REQUIRE_OPTIMISED_BUILD();  // 3 × 1200 simulations of rolled releases
  const RolledCampaign c = MakeRolledCampaign(ReleaseRollMode::kAuto);
  const ValidationSummary s = Check(c);
  for (std::size_t i = 0; i < s.trials.size(); ++i) {
    const TrialPrediction& t = s.trials[i];
    ASSERT_TRUE(t.predicted) << t.message;
    ASSERT_TRUE(c.problems[i].release_roll.fitted) << c.problems[i].release_roll.reason;
    EXPECT_TRUE(t.release_roll_fitted);
    EXPECT_LE(t.ratio, 1.5) << t.trial;
    EXPECT_NEAR(t.release_roll_rad, c.trials[i].truth.value(ParameterId::kReleaseRoll), kRollTolerance_rad) << t.trial;
  }
}

TEST(PredictiveCheck, RolledReleasesPredictedWithTheRollHeldAtZeroArePredictedAtLeastTwiceAsBadly) {
  ROCKFIT_REQUIRE_OPTIMISED_BUILD();
  // The own fits stand at the truth, roll included; the problems (mode off) hold β at 0, as a check that left the
  // roll out would: a planar release cannot make the lateral rocking of a rolled fall.
  const ValidationSummary s = Check(MakeRolledCampaign(ReleaseRollMode::kOff));
  for (const TrialPrediction& t : s.trials) {
    ASSERT_TRUE(t.predicted) << t.message;
    EXPECT_FALSE(t.release_roll_fitted);
    EXPECT_EQ(t.release_roll_rad, 0.0);
    EXPECT_GE(t.ratio, 2.0) << t.trial;
  }
}

TEST(PredictiveCheck, OptionsAreValidated) {
  PredictiveCheckOptions o;
  o.ratio_warning = 0.5;
  EXPECT_THROW(o.Validate(), InvalidArgument);
}

}  // namespace
}  // namespace rockfit::fitting
