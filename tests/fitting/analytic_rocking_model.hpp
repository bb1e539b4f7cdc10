// A cheap closed-form stand-in for the hybrid simulator, for testing the fitting machinery (objective,
// back ends, global stage, identifiability) in microseconds per evaluation. It is NOT the paper's model; it
// only shares its structure, so that every fitted parameter acts the way it does in the real model:
//
//  * phase 1: linearised planar rocking about the release edge (Housner's slender-block equation
//    ψ̈ = p²(ψ − θ_c)), ψ(t) = θ_c − (θ_c − α)·cosh(p t), ω_y = −ψ̇ > 0, facet impact at ψ = 0;
//  * longitudinal impacts multiply ω_y by the planar AVRF (6) with λ_lon (θ = Θ_yy, b = b1) and the
//    rocking continues about the opposite edge with the same closed form;
//  * the facet impact starts a lateral rocking ω_x⁺ = κ·λ_lat·ω⁻ (κ = kLateralCoupling) about x, whose
//    "edge impacts" multiply |ω_x| by (6) with λ (θ = Θ_xx, b = b2); it dies out in a Zeno cascade.
//
// So t0 and α shape phase 1, λ_lon the longitudinal jumps, λ_lat the lateral amplitude and its sign, and λ
// only acts when λ_lat ≠ 0 (no edge impact otherwise — then λ is not identifiable).
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "rockfit/core/block.hpp"
#include "rockfit/fitting/trajectory_model.hpp"

namespace rockfit::testing {

class AnalyticRockingModel final : public fitting::TrajectoryModel {
 public:
  // Lateral angular velocity per unit λ_lat and unit pre-impact ω_y.
  static constexpr double kLateralCoupling = 0.1;
  // Lateral motion below this |ω_x| [rad/s] or with half-cycles shorter than kZenoDt [s] ends (Zeno).
  static constexpr double kZenoOmega = 1e-3;
  static constexpr double kZenoDt = 1e-4;

  explicit AnalyticRockingModel(const core::Block& block, double gravity = core::kStandardGravity)
      : lon_(Channel(block, block.b1(), block.inertia_C_B()(1, 1), gravity)),
        lat_(Channel(block, block.b2(), block.inertia_C_B()(0, 0), gravity)) {}

  void Evaluate(const core::ModelParameters& params, const std::vector<double>& times,
                fitting::ModelOutput* out) const override {
    out->Clear();
    const double alpha = params.alpha_rad;
    if (!(alpha > 0.0) || alpha >= lon_.theta_c) return Fail(out, fitting::ModelFailure::kOverturned, "release tilt beyond θ_c");
    const double t_max = times.empty() ? 0.0 : times.back();

    // Longitudinal segments: [start, end) with the start velocity w0 (signed) of a rocking half-cycle;
    // segment 0 is phase 1 (release from rest at tilt α).
    struct Segment {
      double start, end, w0;
      bool phase1;
    };
    std::vector<Segment> lon;
    const double t1 = std::acosh(lon_.theta_c / (lon_.theta_c - alpha)) / lon_.p;
    lon.push_back({0.0, t1, 0.0, true});
    const double w_impact = (lon_.theta_c - alpha) * lon_.p * std::sinh(lon_.p * t1);
    out->events.push_back({t1, core::ImpactKind::kFacet});
    const double r_lon = lon_.Avrf(params.lambda_lon);
    double w = r_lon * w_impact;  // keeps rotating the same way about the opposite edge
    double t = t1;
    bool lon_rest = false;
    while (t <= t_max) {
      if (std::abs(w) < kZenoOmega) {
        lon_rest = true;
        break;
      }
      if (std::abs(w) >= lon_.p * lon_.theta_c) return Fail(out, fitting::ModelFailure::kOverturned, "longitudinal overturning");
      const double half = lon_.HalfCycle(w);
      lon.push_back({t, t + half, w, false});
      t += half;
      if (t <= t_max) out->events.push_back({t, core::ImpactKind::kFacet});
      w = -r_lon * w;  // returns with −w, the impact scales it
    }
    const double lon_end = lon_rest ? t : std::numeric_limits<double>::infinity();

    // Lateral segments after the first facet impact.
    std::vector<Segment> lat;
    double wx = kLateralCoupling * params.lambda_lat * w_impact;
    const double r_lat = lat_.Avrf(params.lambda);
    t = t1;
    while (t <= t_max && std::abs(wx) >= kZenoOmega) {
      if (std::abs(wx) >= lat_.p * lat_.theta_c) return Fail(out, fitting::ModelFailure::kOverturned, "lateral overturning");
      const double half = lat_.HalfCycle(wx);
      if (half < kZenoDt) break;
      lat.push_back({t, t + half, wx, false});
      t += half;
      if (t <= t_max) out->events.push_back({t, core::ImpactKind::kEdge});
      wx = -r_lat * wx;
      if (r_lat >= 1.0 && lat.size() > 10000) {
        out->impact_status = core::ImpactStatus::kInfeasible;
        return Fail(out, fitting::ModelFailure::kFacetImpact, "lateral energy gain");
      }
    }
    std::sort(out->events.begin(), out->events.end(),
              [](const fitting::ModelEvent& a, const fitting::ModelEvent& b) { return a.t_s < b.t_s; });

    out->w_B.resize(times.size());
    std::size_t i_lon = 0, i_lat = 0;
    for (std::size_t k = 0; k < times.size(); ++k) {
      const double tk = times[k];
      Eigen::Vector3d w_B = Eigen::Vector3d::Zero();
      while (i_lon + 1 < lon.size() && tk >= lon[i_lon].end) ++i_lon;
      if (tk < lon_end) {
        const Segment& s = lon[i_lon];
        w_B.y() = s.phase1 ? (lon_.theta_c - alpha) * lon_.p * std::sinh(lon_.p * (tk - s.start))
                           : lon_.Omega(s.w0, tk - s.start);
      }
      while (i_lat < lat.size() && tk >= lat[i_lat].end) ++i_lat;
      if (i_lat < lat.size() && tk >= lat[i_lat].start) w_B.x() = lat_.Omega(lat[i_lat].w0, tk - lat[i_lat].start);
      out->w_B[k] = w_B;
    }
  }

  std::string Describe() const override { return "analytic test model (linearised planar rocking)"; }

 private:
  // Linearised rocking in one plane: θ_c = atan(b/h), p² = m g R / J, J = θ + m R².
  struct Channel {
    Channel(const core::Block& block, double b, double theta_com, double g) {
      const double R = std::hypot(b, block.h());
      theta_c = std::atan2(b, block.h());
      p = std::sqrt(block.mass() * g * R / (theta_com + block.mass() * R * R));
      const double mh2 = block.mass() * block.h() * block.h();
      num = theta_com + mh2;
      mb2 = block.mass() * b * b;
    }
    double Avrf(double lambda) const { return (num - lambda * mb2) / (num + lambda * mb2); }  // (6)
    // Duration of a half-cycle that starts at the flat position with |ω| = w and returns to it.
    double HalfCycle(double w) const { return 2.0 / p * std::atanh(std::abs(w) / (p * theta_c)); }
    // ω during a half-cycle that started with w0 (signed), τ after its start.
    double Omega(double w0, double tau) const {
      const double sign = w0 >= 0.0 ? 1.0 : -1.0;
      return w0 * std::cosh(p * tau) - sign * theta_c * p * std::sinh(p * tau);
    }
    double theta_c = 0.0, p = 0.0, num = 0.0, mb2 = 0.0;
  };

  static void Fail(fitting::ModelOutput* out, fitting::ModelFailure reason, const char* detail) {
    out->w_B.clear();
    out->failure = reason;
    out->failure_detail = detail;
  }

  Channel lon_;
  Channel lat_;
};

}  // namespace rockfit::testing
