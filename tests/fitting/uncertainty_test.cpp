// Intervals of the fitted parameters (uncertainty.hpp) and the pooled range of a group (group_pooling.hpp):
// the effective noise level against closed forms for white and AR(1) series, the determination rule, pooling
// against hand-computed values, and the profile intervals on the analytic test model (cheap enough for the
// sanitizer build): they hold the fitted value, nest, and hold the truth over independent noise realisations.
#include "rockfit/fitting/uncertainty.hpp"

#include <cmath>
#include <limits>
#include <random>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "analytic_trial.hpp"
#include "build_type.hpp"
#include "differenced_sensitivity_model.hpp"
#include "rockfit/fitting/fitter.hpp"
#include "rockfit/fitting/group_pooling.hpp"

namespace rockfit::fitting {
namespace {

using testing::MakeAnalyticTrial;
using testing::RealisticDisturbances;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

std::vector<Eigen::Vector3d> Ar1Series(double rho, std::size_t n, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  std::vector<Eigen::Vector3d> r(n);
  Eigen::Vector3d x = Eigen::Vector3d::Zero();
  for (std::size_t k = 0; k < n; ++k) {
    x = rho * x + std::sqrt(1.0 - rho * rho) * Eigen::Vector3d(normal(rng), normal(rng), normal(rng));
    r[k] = x;
  }
  return r;
}

TEST(LongRunVarianceFactor, IsOneForWhiteNoise) {
  EXPECT_NEAR(LongRunVarianceFactor(Ar1Series(0.0, 20000, 1), 25), 1.0, 0.1);
}

TEST(LongRunVarianceFactor, MatchesTheAr1ClosedForm) {
  // The long-run variance of an AR(1) series over its variance is (1 + ρ)/(1 − ρ); the Bartlett window
  // underestimates it by about 2ρ/((1 − ρ)²·(L + 1)) (L the largest lag).
  for (double rho : {0.5, 0.8}) {
    const int lags = 100;
    const double expected = (1.0 + rho) / (1.0 - rho) - 2.0 * rho / ((1.0 - rho) * (1.0 - rho) * (lags + 1));
    EXPECT_NEAR(LongRunVarianceFactor(Ar1Series(rho, 40000, 2), lags), expected, 0.1 * expected) << rho;
  }
}

TEST(LongRunVarianceFactor, NeverShrinksTheNoiseLevel) {
  // An alternating series (negative lag-1 correlation) has a long-run variance near 0; κ stays 1.
  std::vector<Eigen::Vector3d> r(1000);
  for (std::size_t k = 0; k < r.size(); ++k) r[k] = Eigen::Vector3d::Constant(k % 2 == 0 ? 1.0 : -1.0);
  EXPECT_EQ(LongRunVarianceFactor(r, 10), 1.0);
}

TEST(Lag1InflationFactor, MatchesTheAr1ClosedForm) {
  // An AR(1) series with lag-1 correlation ρ has a long-run variance (1 + ρ)/(1 − ρ) times its variance.
  for (double rho : {0.0, 0.5, 0.8}) {
    const std::vector<Eigen::Vector3d> r = Ar1Series(rho, 40000, 3);
    const double expected = (1.0 + rho) / (1.0 - rho);
    EXPECT_NEAR(Lag1InflationFactor(r.front().data(), r.size(), 3), expected, 0.05 * expected) << rho;
  }
}

TEST(Lag1InflationFactor, NeverShrinksTheNoiseLevel) {
  std::vector<Eigen::Vector3d> r(1000);
  for (std::size_t k = 0; k < r.size(); ++k) r[k] = Eigen::Vector3d::Constant(k % 2 == 0 ? 1.0 : -1.0);
  EXPECT_EQ(Lag1InflationFactor(r.front().data(), r.size(), 3), 1.0);
  const std::vector<double> zeros(30, 0.0);
  EXPECT_EQ(Lag1InflationFactor(zeros.data(), 10, 3), 1.0);
}

TEST(Determine, ClosedNarrowIntervalsDetermineTheParameter) {
  EXPECT_EQ(Determine({0.9, 1.1}, -0.5, 4.0, 0.5), Determination::kYes);
  EXPECT_EQ(Determine({-0.1, 0.1}, -6.0, 6.0, 0.5), Determination::kYes);  // "near zero" is an answer too
}

TEST(Determine, AnOpenOrWideIntervalThatExcludesZeroFixesOnlyTheSign) {
  EXPECT_EQ(Determine({0.05, kNaN}, -6.0, 6.0, 0.5), Determination::kSignOnly);
  EXPECT_EQ(Determine({kNaN, -0.2}, -6.0, 6.0, 0.5), Determination::kSignOnly);
  EXPECT_EQ(Determine({0.1, 3.9}, -0.5, 4.0, 0.5), Determination::kSignOnly);  // wider than half of λ's range
}

TEST(Determine, OpenIntervalsAcrossZeroOrWithoutSignDetermineNothing) {
  EXPECT_EQ(Determine({kNaN, kNaN}, -6.0, 6.0, 0.5), Determination::kNo);
  EXPECT_EQ(Determine({-0.3, kNaN}, -6.0, 6.0, 0.5), Determination::kNo);
  EXPECT_EQ(Determine({0.1, kNaN}, 0.01, 0.3, 0.5), Determination::kNo);  // α: no sign to fix
}

TEST(PoolTrials, AgreeingTrialsGiveTheInverseVarianceMean) {
  // σ = 0.1 and 0.2 (95 % half-widths 1.96 σ): weights 100 and 25.
  const double z = 1.959963984540054;
  const PooledEstimate p = PoolTrials({{1.0, {1.0 - z * 0.1, 1.0 + z * 0.1}, true},
                                       {1.1, {1.1 - z * 0.2, 1.1 + z * 0.2}, true},
                                       {7.0, {kNaN, kNaN}, false}});
  EXPECT_EQ(p.n_trials, 3);
  EXPECT_EQ(p.n_pooled, 2);
  EXPECT_NEAR(p.pooled, (100.0 * 1.0 + 25.0 * 1.1) / 125.0, 1e-12);
  const double chi2 = 100.0 * std::pow(1.0 - p.pooled, 2) + 25.0 * std::pow(1.1 - p.pooled, 2);
  EXPECT_NEAR(p.chi2_per_dof, chi2, 1e-12);
  EXPECT_NEAR(p.consistency_p, std::erfc(std::sqrt(chi2 / 2.0)), 1e-9);  // χ²₁ survival
  EXPECT_NEAR(p.interval_95[1] - p.pooled, z / std::sqrt(125.0), 1e-12);  // χ²/dof < 1: not widened
  const double mean = (1.0 + 1.1 + 7.0) / 3.0;
  EXPECT_NEAR(p.spread, std::sqrt((std::pow(1.0 - mean, 2) + std::pow(1.1 - mean, 2) + std::pow(7.0 - mean, 2)) / 2.0),
              1e-12);
}

TEST(PoolTrials, DisagreeingTrialsAreFlaggedAndTheIntervalWidened) {
  const double z = 1.959963984540054;
  const PooledEstimate p = PoolTrials({{1.0, {1.0 - z, 1.0 + z}, true}, {5.0, {5.0 - z, 5.0 + z}, true}});
  EXPECT_NEAR(p.pooled, 3.0, 1e-12);
  EXPECT_NEAR(p.chi2_per_dof, 8.0, 1e-12);
  EXPECT_LT(p.consistency_p, 0.01);
  // σ_pooled = 1/√2 widened by the Birge ratio √8.
  EXPECT_NEAR(p.interval_95[1] - p.pooled, z * std::sqrt(8.0) / std::sqrt(2.0), 1e-12);
}

TEST(PoolTrials, NoDeterminedTrialGivesNoPooledValue) {
  const PooledEstimate p = PoolTrials({{0.3, {0.1, kNaN}, false}});
  EXPECT_EQ(p.n_pooled, 0);
  EXPECT_TRUE(std::isnan(p.pooled));
  EXPECT_TRUE(std::isnan(p.spread));
}

// Nelder–Mead from the truth without the global stage: the intervals, not the search, are under test.
FitOptions AnalyticFitOptions(IntervalMethod method) {
  FitOptions options;
  options.global.enabled = false;
  options.method = FitMethod::kNelderMead;
  options.intervals.method = method;
  return options;
}

FitSummary FitAnalytic(const testing::AnalyticTrial& trial, IntervalMethod method) {
  const Objective objective = trial.MakeObjective(trial.Bounded(BoundsSet::kEmpirical));
  return Fit(objective, trial.truth, AnalyticFitOptions(method));
}

TEST(Intervals, HoldTheFittedValueAndNest) {
  const auto trial = MakeAnalyticTrial(0.2, 0.8, -2.0, 0.6, RealisticDisturbances(21));
  for (IntervalMethod method : {IntervalMethod::kFast, IntervalMethod::kThorough}) {
    const FitSummary s = FitAnalytic(trial, method);
    ASSERT_TRUE(s.feasible);
    EXPECT_EQ(s.uncertainty.method, method);
    EXPECT_GE(s.uncertainty.correlation_factor, 1.0);
    for (ParameterId id : s.parameters.FreeIds()) {
      const std::size_t k = static_cast<std::size_t>(id);
      const Interval& i68 = s.uncertainty.interval_68[k];
      const Interval& i95 = s.uncertainty.interval_95[k];
      ASSERT_TRUE(std::isfinite(i68[0]) && std::isfinite(i68[1])) << Name(id) << "\n" << s.FullReport();
      ASSERT_TRUE(std::isfinite(i95[0]) && std::isfinite(i95[1])) << Name(id) << "\n" << s.FullReport();
      EXPECT_LE(i95[0], i68[0]) << Name(id);
      EXPECT_LE(i68[0], s.parameters.value(id)) << Name(id);
      EXPECT_LE(s.parameters.value(id), i68[1]) << Name(id);
      EXPECT_LE(i68[1], i95[1]) << Name(id);
      EXPECT_EQ(s.uncertainty.determined[k], Determination::kYes) << Name(id) << "\n" << s.FullReport();
    }
    EXPECT_FALSE(s.uncertainty.determined[static_cast<std::size_t>(ParameterId::kTauEdge)].has_value());  // fixed
    EXPECT_EQ(s.uncertainty.correlation(0, 0), 1.0);
  }
}

TEST(Intervals, NoneComputesNoIntervalsButTheCorrelation) {
  const auto trial = MakeAnalyticTrial(0.2, 0.8, -2.0, 0.6, RealisticDisturbances(22));
  const FitSummary s = FitAnalytic(trial, IntervalMethod::kNone);
  EXPECT_TRUE(std::isnan(s.uncertainty.interval_95[0][0]));
  EXPECT_NEAR(s.uncertainty.correlation(1, 1), 1.0, 1e-12);
  const auto j = nlohmann::json::parse(s.ToJson());
  EXPECT_EQ(j["uncertainty_method"], "none");
  EXPECT_TRUE(j["parameters"]["t0"]["interval_95"][0].is_null());
  EXPECT_TRUE(j["parameters"]["tau_edge"]["interval_95"].is_null());
  EXPECT_EQ(j["correlation"]["parameters"].size(), 5u);
}

TEST(Intervals, ANonIdentifiableParameterIsOpenAndNotDetermined) {
  // λ_lat = 0 held fixed (as the paper did for its blocks 7 and 8): no edge impact, λ does not act on (28).
  const auto trial = MakeAnalyticTrial(0.2, 0.8, 0.0, 0.6, RealisticDisturbances(7));
  ParameterSet parameters = trial.Bounded(BoundsSet::kEmpirical);
  parameters[ParameterId::kLambdaLat] = {0.0, -6.0, 6.0, true};
  const FitSummary s = Fit(trial.MakeObjective(parameters), trial.truth, AnalyticFitOptions(IntervalMethod::kThorough));
  const std::size_t k = static_cast<std::size_t>(ParameterId::kLambda);
  ASSERT_FALSE(s.identifiable[k]) << s.FullReport();
  EXPECT_TRUE(std::isnan(s.uncertainty.interval_95[k][0]) && std::isnan(s.uncertainty.interval_95[k][1]));
  EXPECT_EQ(s.uncertainty.determined[k], Determination::kNo);
}

// The thorough 95 % interval is the hull of the profile's and the linearised one: it contains the profile
// interval (the same fit with the hull switched off) and the value ± the fast interval's half-widths.
TEST(Intervals, ThoroughNinetyFivePercentIntervalIsTheHullOfProfileAndLinearised) {
  const auto trial = MakeAnalyticTrial(0.2, 0.8, -2.0, 0.6, RealisticDisturbances(23));
  const Objective objective = trial.MakeObjective(trial.Bounded(BoundsSet::kEmpirical));
  FitOptions options = AnalyticFitOptions(IntervalMethod::kFast);
  const FitSummary fast = Fit(objective, trial.truth, options);
  options.intervals.method = IntervalMethod::kThorough;
  const FitSummary hull = Fit(objective, trial.truth, options);
  options.intervals.hull_with_linearised = false;
  const FitSummary profile = Fit(objective, trial.truth, options);
  ASSERT_TRUE(fast.feasible && hull.feasible && profile.feasible);
  // The linearised σ of the hull uses the lowest sum of squares the profiles met, the fast one the fit's:
  // they differ by the profiles' improvement of S, well below a percent here.
  constexpr double kNoiseLevelTol = 0.01;
  for (ParameterId id : hull.parameters.FreeIds()) {
    const std::size_t k = static_cast<std::size_t>(id);
    const double v = hull.parameters.value(id);
    ASSERT_EQ(v, profile.parameters.value(id)) << Name(id);
    ASSERT_EQ(v, fast.parameters.value(id)) << Name(id);
    const Interval& f = fast.uncertainty.interval_95[k];
    const Interval& h = hull.uncertainty.interval_95[k];
    const Interval& p = profile.uncertainty.interval_95[k];
    ASSERT_TRUE(std::isfinite(f[0]) && std::isfinite(f[1]) && std::isfinite(h[0]) && std::isfinite(h[1]) &&
                std::isfinite(p[0]) && std::isfinite(p[1]))
        << Name(id);
    EXPECT_LE(h[0], p[0]) << Name(id);
    EXPECT_GE(h[1], p[1]) << Name(id);
    EXPECT_GE(v - h[0], (1.0 - kNoiseLevelTol) * (v - f[0])) << Name(id);
    EXPECT_GE(h[1] - v, (1.0 - kNoiseLevelTol) * (f[1] - v)) << Name(id);
    EXPECT_EQ(hull.uncertainty.interval_68[k], profile.uncertainty.interval_68[k]) << Name(id);
  }
}

// The aimed profile points (IntervalOptions::profile_aimed) find the crossings of a converged profile (the fixed
// grid with its re-fits run to 2000 evaluations) with fewer model runs than the fixed grid at its default.
TEST(Intervals, AimedProfileFindsTheConvergedCrossingsWithFewerRuns) {
  const auto trial = MakeAnalyticTrial(0.2, 0.8, -2.0, 0.6, RealisticDisturbances(23));
  const Objective objective = trial.MakeObjective(trial.Bounded(BoundsSet::kEmpirical));
  FitOptions options = AnalyticFitOptions(IntervalMethod::kThorough);
  options.intervals.hull_with_linearised = false;  // the profiles' own crossings
  options.intervals.profile_aimed = true;
  const FitSummary aimed = Fit(objective, trial.truth, options);
  options.intervals.profile_aimed = false;
  const FitSummary grid = Fit(objective, trial.truth, options);
  options.intervals.profile_evaluations = 2000;
  const FitSummary converged = Fit(objective, trial.truth, options);
  ASSERT_TRUE(aimed.feasible && grid.feasible && converged.feasible);
  // The two interpolate the crossing between different points of a profile that is not exactly quadratic,
  // re-fitted by Nelder–Mead to about 1e-7 of S: within 5 % of the half-width (measured: 1.3 % at most; the
  // fixed grid at 120 evaluations per point ends α's upper end 24 % short, its re-fits not converged).
  constexpr double kHalfWidthFraction = 0.05;
  for (ParameterId id : converged.parameters.FreeIds()) {
    const std::size_t k = static_cast<std::size_t>(id);
    const double v = converged.parameters.value(id);
    ASSERT_EQ(aimed.parameters.value(id), v) << Name(id);
    const Interval& a = aimed.uncertainty.interval_95[k];
    const Interval& c = converged.uncertainty.interval_95[k];
    ASSERT_TRUE(std::isfinite(a[0]) && std::isfinite(a[1]) && std::isfinite(c[0]) && std::isfinite(c[1])) << Name(id);
    EXPECT_NEAR(a[0], c[0], kHalfWidthFraction * (v - c[0])) << Name(id);
    EXPECT_NEAR(a[1], c[1], kHalfWidthFraction * (c[1] - v)) << Name(id);
  }
  EXPECT_LT(aimed.uncertainty.evaluations, grid.uncertainty.evaluations);
}

// The exact profile re-fits (IntervalOptions::profile_refit kExact: Ceres with the model's Jacobian, here the
// analytic model's by differences) end where a converged profile does (the fixed grid with Nelder–Mead re-fits run
// to 2000 evaluations), with fewer model runs than the Nelder–Mead re-fits at their default.
TEST(Intervals, ExactRefitsFindTheConvergedCrossings) {
  const auto trial = MakeAnalyticTrial(0.2, 0.8, -2.0, 0.6, RealisticDisturbances(23));
  const Objective objective(trial.data.signal, trial.t_end_s,
                            std::make_shared<testing::DifferencedSensitivityModel>(trial.model),
                            trial.Bounded(BoundsSet::kEmpirical));
  FitOptions options = AnalyticFitOptions(IntervalMethod::kThorough);
  options.intervals.hull_with_linearised = false;  // the profiles' own crossings
  options.intervals.profile_refit = ProfileRefit::kExact;
  const FitSummary exact = Fit(objective, trial.truth, options);
  options.intervals.refit_checked = false;
  const FitSummary unchecked = Fit(objective, trial.truth, options);
  options.intervals.refit_checked = true;
  options.intervals.profile_refit = ProfileRefit::kNelderMead;
  const FitSummary nelder_mead = Fit(objective, trial.truth, options);
  options.intervals.profile_evaluations = 2000;
  const FitSummary converged = Fit(objective, trial.truth, options);
  ASSERT_TRUE(exact.feasible && nelder_mead.feasible && converged.feasible);
  EXPECT_GT(exact.uncertainty.exact_refits, 0);
  EXPECT_GT(exact.uncertainty.sensitivity_runs, 0);
  EXPECT_EQ(nelder_mead.uncertainty.sensitivity_runs, 0);
  // The same grid, re-fitted to about 1e-7 of S where the re-fits converge; where S is rippled the re-fits end in
  // different dips (measured: within 4.9 % of the half-width, 7.3 % at t0's upper end, where the Nelder–Mead re-fits
  // at their default of 120 evaluations end at the same place; those end α's upper end 27 % short).
  constexpr double kHalfWidthFraction = 0.1;
  for (ParameterId id : converged.parameters.FreeIds()) {
    const std::size_t k = static_cast<std::size_t>(id);
    const double v = converged.parameters.value(id);
    ASSERT_EQ(exact.parameters.value(id), v) << Name(id);
    const Interval& e = exact.uncertainty.interval_95[k];
    const Interval& c = converged.uncertainty.interval_95[k];
    ASSERT_TRUE(std::isfinite(e[0]) && std::isfinite(e[1]) && std::isfinite(c[0]) && std::isfinite(c[1])) << Name(id);
    EXPECT_NEAR(e[0], c[0], kHalfWidthFraction * (v - c[0])) << Name(id);
    EXPECT_NEAR(e[1], c[1], kHalfWidthFraction * (c[1] - v)) << Name(id);
  }
  EXPECT_LT(exact.uncertainty.evaluations, nelder_mead.uncertainty.evaluations);
  // Without the checks Ceres' ends are kept wherever they lie below their starts: fewer runs still.
  ASSERT_TRUE(unchecked.feasible);
  EXPECT_LT(unchecked.uncertainty.evaluations, exact.uncertainty.evaluations);
}

// Where the model gives no exact Jacobian, the exact option falls back to Nelder–Mead from the same starts: the
// intervals are those of the Nelder–Mead re-fits to the last digit.
TEST(Intervals, ExactRefitsWithoutDerivativesAreTheNelderMeadOnes) {
  const auto trial = MakeAnalyticTrial(0.2, 0.8, -2.0, 0.6, RealisticDisturbances(23));
  const Objective objective = trial.MakeObjective(trial.Bounded(BoundsSet::kEmpirical));
  FitOptions options = AnalyticFitOptions(IntervalMethod::kThorough);
  options.intervals.profile_refit = ProfileRefit::kExact;
  const FitSummary exact = Fit(objective, trial.truth, options);
  options.intervals.profile_refit = ProfileRefit::kNelderMead;
  const FitSummary nelder_mead = Fit(objective, trial.truth, options);
  ASSERT_TRUE(exact.feasible && nelder_mead.feasible);
  EXPECT_EQ(exact.uncertainty.exact_refits, 0);
  EXPECT_GT(exact.uncertainty.nelder_mead_refits, 0);
  for (ParameterId id : nelder_mead.parameters.FreeIds()) {
    const std::size_t k = static_cast<std::size_t>(id);
    EXPECT_EQ(exact.uncertainty.interval_95[k], nelder_mead.uncertainty.interval_95[k]) << Name(id);
    EXPECT_EQ(exact.uncertainty.interval_68[k], nelder_mead.uncertainty.interval_68[k]) << Name(id);
  }
}

// The 68 % intervals use the bulk noise level of the standard errors (IntervalOptions::bulk_noise_for_68): the
// fast one is value ± std_error, and the model-error allowance widens only the 95 % ones.
TEST(Intervals, SixtyEightPercentIntervalsUseTheStandardErrorsNoiseLevel) {
  const auto trial = MakeAnalyticTrial(0.2, 0.8, -2.0, 0.6, RealisticDisturbances(24));
  const Objective objective = trial.MakeObjective(trial.Bounded(BoundsSet::kEmpirical));
  FitOptions options = AnalyticFitOptions(IntervalMethod::kFast);
  // The bulk level is capped by the 95 % one (the intervals nest); an allowance of 4 keeps it below here.
  options.intervals.model_error_allowance = 4.0;
  const FitSummary fast = Fit(objective, trial.truth, options);
  ASSERT_TRUE(fast.feasible);
  ASSERT_TRUE(std::isfinite(fast.uncertainty.bulk_inflation));
  // Both from the same residuals and (JᵀJ)⁻¹; the Ceres residual array also holds the empty rows before t0,
  // which shift the lag-1 sums by a term or two (measured: 1e-4 relative at most).
  constexpr double kRelTol = 1e-3;
  for (ParameterId id : fast.parameters.FreeIds()) {
    const std::size_t k = static_cast<std::size_t>(id);
    const double v = fast.parameters.value(id), se = fast.std_error[k];
    ASSERT_TRUE(std::isfinite(se)) << Name(id);
    ASSERT_LE(fast.uncertainty.bulk_inflation, fast.uncertainty.noise_inflation[k]) << Name(id);
    EXPECT_NEAR(fast.uncertainty.interval_68[k][1] - v, se, kRelTol * se) << Name(id);
    EXPECT_NEAR(v - fast.uncertainty.interval_68[k][0], se, kRelTol * se) << Name(id);
  }
  // The allowance widens the 95 % intervals only.
  options.intervals.model_error_allowance = 8.0;
  const FitSummary wider = Fit(objective, trial.truth, options);
  ASSERT_TRUE(wider.feasible);
  for (ParameterId id : fast.parameters.FreeIds()) {
    const std::size_t k = static_cast<std::size_t>(id);
    EXPECT_EQ(wider.uncertainty.interval_68[k], fast.uncertainty.interval_68[k]) << Name(id);
    EXPECT_GT(wider.uncertainty.interval_95[k][1], fast.uncertainty.interval_95[k][1]) << Name(id);
    EXPECT_LT(wider.uncertainty.interval_95[k][0], fast.uncertainty.interval_95[k][0]) << Name(id);
  }
}

// A bound of λ just beyond the fitted value (0.3 standard errors; the "at bound" distance made small):
// no 68 % end lies outside the bounds (an end beyond one is open, or the 95 % interval's end), and the 68 %
// interval stays inside the 95 % one, for both methods.
TEST(Intervals, SixtyEightPercentEndsRespectTheBoundsAndNest) {
  const auto trial = MakeAnalyticTrial(0.2, 0.8, -2.0, 0.6, RealisticDisturbances(25));
  for (IntervalMethod method : {IntervalMethod::kFast, IntervalMethod::kThorough}) {
    FitOptions options = AnalyticFitOptions(method);
    options.at_bound_fraction = 1e-7;
    ParameterSet parameters = trial.Bounded(BoundsSet::kEmpirical);
    const FitSummary free = Fit(trial.MakeObjective(parameters), trial.truth, options);
    ASSERT_TRUE(free.feasible);
    const std::size_t lambda = static_cast<std::size_t>(ParameterId::kLambda);
    const double value = free.parameters.value(ParameterId::kLambda);
    ASSERT_TRUE(std::isfinite(free.std_error[lambda]));
    parameters[ParameterId::kLambda].value = value;
    parameters[ParameterId::kLambda].upper = value + 0.3 * free.std_error[lambda];
    const FitSummary s = Fit(trial.MakeObjective(parameters), free.parameters, options);
    ASSERT_TRUE(s.feasible);
    for (ParameterId id : s.parameters.FreeIds()) {
      const std::size_t k = static_cast<std::size_t>(id);
      const Parameter& p = parameters[id];
      const Interval& i68 = s.uncertainty.interval_68[k];
      const Interval& i95 = s.uncertainty.interval_95[k];
      for (double end : i68) {
        if (!std::isnan(end)) {
          EXPECT_TRUE(p.lower <= end && end <= p.upper) << Name(id) << " " << end << " in [" << p.lower << ", " << p.upper << "]";
        }
      }
      if (!std::isnan(i95[0])) {
        EXPECT_TRUE(!std::isnan(i68[0]) && i68[0] >= i95[0]) << Name(id);
      }
      if (!std::isnan(i95[1])) {
        EXPECT_TRUE(!std::isnan(i68[1]) && i68[1] <= i95[1]) << Name(id);
      }
    }
  }
}

// Over independent noise realisations (white noise and ringing, as synth makes them) the 95 % profile
// intervals hold the truth for nearly every parameter value: 5 parameters × kRealisations.
TEST(Intervals, ProfileIntervalsHoldTheTruthOverNoiseRealisations) {
  const int realisations = rockfit::testing::kOptimisedBuild ? 12 : 3;
  int held = 0, total = 0;
  std::string misses;
  for (int seed = 0; seed < realisations; ++seed) {
    const auto trial = MakeAnalyticTrial(0.2, 0.9, 1.6, 0.7, RealisticDisturbances(100 + seed));
    const FitSummary s = FitAnalytic(trial, IntervalMethod::kThorough);
    for (ParameterId id : s.parameters.FreeIds()) {
      const Interval& i = s.uncertainty.interval_95[static_cast<std::size_t>(id)];
      const double truth = trial.truth.value(id);
      ++total;
      if ((std::isnan(i[0]) || i[0] <= truth) && (std::isnan(i[1]) || truth <= i[1])) {
        ++held;
      } else {
        misses += fmt::format("seed {} {}: truth {:.6g} outside [{:.6g}, {:.6g}]\n", seed, Name(id), truth, i[0], i[1]);
      }
    }
  }
  EXPECT_GE(held, static_cast<int>(std::floor(0.9 * total))) << misses;
}

}  // namespace
}  // namespace rockfit::fitting
