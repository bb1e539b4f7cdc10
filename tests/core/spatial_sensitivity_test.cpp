// The exact derivatives of a 3D run's samples (vertex rocking, edge and facet impacts) against central differences
// of the simulator itself, on random cases with a fixed seed, and the cases where they are (rightly) not given.
#include "rockfit/core/spatial_sensitivity.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "rockfit/core/edge_dynamics.hpp"
#include "rockfit/core/simulator.hpp"
#include "simulation_cases.hpp"

namespace rockfit::core {
namespace {

// Agreement of an exact derivative column with central differences, relative to the column's largest entry (the
// agreement the fitting's Jacobian check asks for).
constexpr double kRelativeAgreement = 1e-6;
// Steps of the stencils: the simulator's noise (its 1e-12 tolerance and event location) over the step stays ~1e-7 of
// the columns, and the five-point stencil's O(h⁴) truncation far below (its three-point form reached 1e-6 here).
constexpr double kParameterStep = 1e-6;
constexpr double kTimeStep_s = 1e-7;
constexpr double kRate_hz = 256.0;
constexpr double kWindow_s = 1.0;
// Random cases (fixed seed).
constexpr int kCases = 16;

SimulationOptions Options(double time_shift_s = 0.0) {
  return testing::SampledRateOptions(kWindow_s, kRate_hz, time_shift_s);
}

// True when the impacts of two runs pair up one to one (same kinds and contacts): the same sequence of modes. A
// case whose stencil changes the sequence (an impact appears, vanishes or changes its contact: a grazing case) is
// skipped.
bool SameModes(const Trajectory& a, const Trajectory& b) {
  if (a.impacts.size() != b.impacts.size() || a.t_s.size() != b.t_s.size()) return false;
  for (std::size_t i = 0; i < a.impacts.size(); ++i) {
    const ImpactRecord& ia = a.impacts[i];
    const ImpactRecord& ib = b.impacts[i];
    if (ia.kind != ib.kind || ia.contact_before != ib.contact_before || ia.contact_after != ib.contact_after) {
      return false;
    }
  }
  return true;
}

// Marks the samples that lie before an impact in one run of a stencil and after it in another (their ω jumps
// within the stencil, and the difference says nothing about the derivative there). Runs with the same modes.
void MarkStraddledSamples(const std::vector<const Trajectory*>& runs,
                          const std::vector<const std::vector<double>*>& times, std::vector<bool>* straddled) {
  const Trajectory& first = *runs.front();
  for (std::size_t i = 0; i < first.impacts.size(); ++i) {
    for (std::size_t k = 0; k < straddled->size(); ++k) {
      const bool before = (*times.front())[k] < first.impacts[i].t_s;
      for (std::size_t r = 1; r < runs.size(); ++r) {
        if (((*times[r])[k] < runs[r]->impacts[i].t_s) != before) (*straddled)[k] = true;
      }
    }
  }
}

// The largest difference of a column relative to the column's largest entry.
double WorstRelativeDifference(const std::vector<Eigen::Vector3d>& exact, const std::vector<Eigen::Vector3d>& central) {
  double scale = 0.0;
  for (const Eigen::Vector3d& d : exact) scale = std::max(scale, d.norm());
  double worst = 0.0;
  for (std::size_t k = 0; k < exact.size(); ++k) worst = std::max(worst, (exact[k] - central[k]).norm());
  return scale > 0.0 ? worst / scale : worst;
}

ModelParameters With(const ModelParameters& p, SensitivityColumn column, double delta) {
  ModelParameters q = p;
  switch (column) {
    case SensitivityColumn::kAlpha: q.alpha_rad += delta; break;
    case SensitivityColumn::kLambda: q.lambda += delta; break;
    case SensitivityColumn::kLambdaLat: q.lambda_lat += delta; break;
    case SensitivityColumn::kLambdaLon: q.lambda_lon += delta; break;
    case SensitivityColumn::kTime: break;
  }
  return q;
}

TEST(SpatialSensitivity, DerivativesMatchCentralDifferencesOfTheSimulatorOnRandom3dRuns) {
  const Block block = testing::Fig14Block();
  const double theta_c = EdgeDynamics(block, 1, 2, kStandardGravity).critical_angle_rad();
  std::mt19937 rng(20261127);
  std::uniform_real_distribution<double> alpha_fraction(0.3, 0.9), lambda_draw(0.3, 2.2), lat_draw(0.2, 2.0),
      lon_draw(0.15, 0.9);
  std::bernoulli_distribution negative_lat(0.5);
  int checked = 0, grazing = 0, not_available = 0;
  std::size_t samples_compared = 0, samples_straddled = 0;
  const SimulationOptions options = Options();
  const std::vector<double>& times = options.sample_times_s;
  for (int trial = 0; trial < kCases; ++trial) {
    ModelParameters p;
    p.alpha_rad = alpha_fraction(rng) * theta_c;
    p.lambda = lambda_draw(rng);
    p.lambda_lat = (negative_lat(rng) ? -1.0 : 1.0) * lat_draw(rng);  // ≠ 0: the motion leaves the plane
    p.lambda_lon = lon_draw(rng);
    const Trajectory base = Simulate(block, p, options);
    const SpatialSensitivitySummary s = SpatialSampleSensitivities(block, p, options, base);
    if (!s.available) {
      ++not_available;
      std::printf("case %d: no derivatives (%s)\n", trial, s.reason.c_str());
      continue;
    }
    ASSERT_EQ(s.dw_B.size(), base.w_B.size());
    // The five-point stencils (error O(h⁴): the derivatives of 3D runs grow fast along the run, and the O(h²)
    // truncation of the three-point stencil reaches 1e-6 of them with any step above the noise) in each parameter,
    // and the three-point one in the sample time (a shift of the release time t0).
    const std::array<double, 4> offsets{-2.0, -1.0, 1.0, 2.0};
    const std::array<SensitivityColumn, 4> columns{SensitivityColumn::kAlpha, SensitivityColumn::kLambda,
                                                   SensitivityColumn::kLambdaLat, SensitivityColumn::kLambdaLon};
    std::array<std::array<Trajectory, 4>, 4> runs;
    std::vector<const Trajectory*> all{&base};
    std::vector<const std::vector<double>*> all_times{&times};
    bool same_modes = true;
    for (std::size_t c = 0; c < columns.size(); ++c) {
      for (std::size_t r = 0; r < offsets.size(); ++r) {
        runs[c][r] = Simulate(block, With(p, columns[c], offsets[r] * kParameterStep), options);
        same_modes = same_modes && SameModes(runs[c][r], base);
        all.push_back(&runs[c][r]);
        all_times.push_back(&times);
      }
    }
    const SimulationOptions later = Options(kTimeStep_s), earlier = Options(-kTimeStep_s);
    const Trajectory t_plus = Simulate(block, p, later);
    const Trajectory t_minus = Simulate(block, p, earlier);
    same_modes = same_modes && SameModes(t_plus, base) && SameModes(t_minus, base);
    if (!same_modes) {
      ++grazing;
      continue;
    }
    all.push_back(&t_plus);
    all_times.push_back(&later.sample_times_s);
    all.push_back(&t_minus);
    all_times.push_back(&earlier.sample_times_s);
    std::vector<bool> straddled(times.size(), false);
    MarkStraddledSamples(all, all_times, &straddled);
    // The release is an event too (held before, free after): samples whose time stencil reaches it are left out.
    for (std::size_t k = 0; k < times.size(); ++k) straddled[k] = straddled[k] || !(earlier.sample_times_s[k] > 0.0);

    double worst = 0.0;
    auto compare = [&](const char* what, auto exact_of, auto central_of) {
      std::vector<Eigen::Vector3d> exact, central;
      for (std::size_t k = 0; k < times.size(); ++k) {
        if (straddled[k]) continue;
        exact.push_back(exact_of(k));
        central.push_back(central_of(k));
      }
      const double difference = WorstRelativeDifference(exact, central);
      worst = std::max(worst, difference);
      EXPECT_LT(difference, kRelativeAgreement) << "case " << trial << ", " << what;
    };
    const char* names[] = {"alpha", "lambda", "lambda_lat", "lambda_lon"};
    for (std::size_t c = 0; c < columns.size(); ++c) {
      const std::array<Trajectory, 4>& r = runs[c];
      compare(
          names[c], [&](std::size_t k) { return Eigen::Vector3d(s.dw_B[k].col(static_cast<int>(columns[c]))); },
          [&](std::size_t k) {
            return Eigen::Vector3d((r[0].w_B[k] - 8.0 * r[1].w_B[k] + 8.0 * r[2].w_B[k] - r[3].w_B[k]) /
                                   (12.0 * kParameterStep));
          });
    }
    constexpr int kTimeColumn = static_cast<int>(SensitivityColumn::kTime);
    compare(
        "time", [&](std::size_t k) { return Eigen::Vector3d(s.dw_B[k].col(kTimeColumn)); },
        [&](std::size_t k) { return Eigen::Vector3d((t_plus.w_B[k] - t_minus.w_B[k]) / (2.0 * kTimeStep_s)); });
    const auto straddled_here = static_cast<std::size_t>(std::count(straddled.begin(), straddled.end(), true));
    samples_straddled += straddled_here;
    samples_compared += times.size() - straddled_here;
    int facet = 0, to_edge = 0, zeno = 0;
    for (const ImpactRecord& r : base.impacts) {
      facet += r.kind == ImpactKind::kFacet ? 1 : 0;
      to_edge += r.kind == ImpactKind::kEdge && r.contact_after.is_edge() ? 1 : 0;
      zeno += r.kind == ImpactKind::kZeno ? 1 : 0;
    }
    std::printf("case %d: %zu impacts (%d facet, %d edge impacts to edge contact, %d Zeno switches), %d vertex and "
                "%d edge phases, %zu samples left out, worst relative difference %.2e\n",
                trial, base.impacts.size(), facet, to_edge, zeno, s.vertex_phases, s.edge_phases, straddled_here,
                worst);
    ++checked;
  }
  std::printf("%d cases checked (%zu samples compared, %zu left out next to an impact or the release), %d skipped as "
              "grazing (the modes change within a stencil), %d without derivatives\n",
              checked, samples_compared, samples_straddled, grazing, not_available);
  EXPECT_GE(checked, kCases * 2 / 3) << grazing << " grazing, " << not_available << " without derivatives";
  EXPECT_EQ(not_available, 0);
}

// The pass over a run of the Fig. 14 block with parameters p, sampled as the fitting samples it.
SpatialSensitivitySummary PassOverItsOwnRun(const ModelParameters& p) {
  const Block block = testing::Fig14Block();
  const SimulationOptions options = Options();
  return SpatialSampleSensitivities(block, p, options, Simulate(block, p, options));
}

TEST(SpatialSensitivity, NotAvailableWhenAFacetImpactKeepsTwoVerticesDown) {
  // λ_lat = 0: every facet impact leaves edge contact (two candidates with the same ω⁺), whose derivative in λ_lat
  // is one-sided; the planar pass covers these runs.
  ModelParameters p;
  p.alpha_rad = 0.15;
  p.lambda_lat = 0.0;
  p.lambda_lon = 0.6;
  const SpatialSensitivitySummary s = PassOverItsOwnRun(p);
  EXPECT_FALSE(s.available);
  EXPECT_NE(s.reason.find("two vertices down"), std::string::npos) << s.reason;
}

TEST(SpatialSensitivity, NotAvailableWhenTheSamplesAreNotThoseOfTheRun) {
  const Block block = testing::Fig14Block();
  const SimulationOptions options = Options();
  ModelParameters p;
  p.alpha_rad = 0.15;
  p.lambda_lat = 0.5;
  p.lambda_lon = 0.6;
  ModelParameters other = p;
  other.alpha_rad = 0.14;
  const SpatialSensitivitySummary s = SpatialSampleSensitivities(block, p, options, Simulate(block, other, options));
  EXPECT_FALSE(s.available);
  EXPECT_FALSE(s.reason.empty());
}

TEST(SpatialSensitivity, NotAvailableForTheFixedTauFacetRule) {
  ModelParameters p;
  p.lambda_lat = 0.5;
  p.facet_tau_rule = FacetTauRule::kFixed;
  const SpatialSensitivitySummary s = PassOverItsOwnRun(p);
  EXPECT_FALSE(s.available);
  EXPECT_NE(s.reason.find("no-spin"), std::string::npos) << s.reason;
}

TEST(SpatialSensitivity, NotAvailableForARolledRelease) {
  // The pass starts its first phase about the release edge; a rolled release starts about a corner.
  ModelParameters p;
  p.alpha_rad = 0.15;
  p.lambda_lat = 0.5;
  p.lambda_lon = 0.6;
  p.release_roll_rad = 0.005;
  const SpatialSensitivitySummary s = PassOverItsOwnRun(p);
  EXPECT_FALSE(s.available);
  EXPECT_NE(s.reason.find("rolled"), std::string::npos) << s.reason;
}

}  // namespace
}  // namespace rockfit::core
