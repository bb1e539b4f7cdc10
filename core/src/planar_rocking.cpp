#include "rockfit/core/planar_rocking.hpp"

#include <cmath>
#include <memory>
#include <string>

#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>

#include "rockfit/core/edge_dynamics.hpp"
#include "rockfit/core/errors.hpp"
#include "rockfit/core/gsl_setup.hpp"

namespace rockfit::core {
namespace {

// Quadrature accuracy: T is about 0.1–0.5 s, so this is far below the simulator's 1e-9 s target.
constexpr double kQuadratureRelTol = 1e-13;
constexpr double kQuadratureAbsTol = 1e-15;  // [s]
constexpr std::size_t kQuadratureIntervals = 200;

struct IntegrandParams {
  double alpha;
  double theta_c;
  double K;
};

// The smooth factor g(ψ) = √(α − ψ)·f(ψ) of the integrand f(ψ) = 1/√(K[cos(θ_c−α) − cos(θ_c−ψ)]).
// With cos A − cos B = 2 sin((A+B)/2)·sin((B−A)/2) and u = (α − ψ)/2:
//   g(ψ) = √( (u / sin u) / (K sin(θ_c − (α+ψ)/2)) ),  well conditioned up to ψ = α.
double SmoothFactor(double psi, void* raw) {
  const auto* p = static_cast<const IntegrandParams*>(raw);
  const double u = 0.5 * (p->alpha - psi);
  const double u_over_sin = u == 0.0 ? 1.0 : u / std::sin(u);
  return std::sqrt(u_over_sin / (p->K * std::sin(p->theta_c - 0.5 * (p->alpha + psi))));
}

}  // namespace

PlanarRocker PlanarRockerAboutEdge(const Block& block, int i, int j, double gravity_m_s2) {
  const EdgeDynamics edge(block, i, j, gravity_m_s2);
  PlanarRocker rocker;
  rocker.mass_kg = block.mass();
  rocker.inertia_kg_m2 = edge.inertia_kg_m2();
  rocker.arm_m = edge.arm_m();
  rocker.critical_angle_rad = edge.critical_angle_rad();
  rocker.gravity_m_s2 = gravity_m_s2;
  return rocker;
}

double FallTime(const PlanarRocker& rocker, double alpha_rad) {
  if (!std::isfinite(alpha_rad) || alpha_rad < 0.0 || alpha_rad >= rocker.critical_angle_rad) {
    throw InvalidArgument("the fall time needs a tilt 0 ≤ α < θ_c = " + std::to_string(rocker.critical_angle_rad) +
                          " rad, got " + std::to_string(alpha_rad));
  }
  if (alpha_rad == 0.0) return 0.0;
  EnsureGslErrorHandlerOff();
  IntegrandParams params{alpha_rad, rocker.critical_angle_rad, rocker.K()};
  gsl_function f;
  f.function = &SmoothFactor;
  f.params = &params;
  // Weight (ψ − 0)^0 (α − ψ)^(−1/2): QAWS integrates the endpoint singularity exactly.
  std::unique_ptr<gsl_integration_qaws_table, decltype(&gsl_integration_qaws_table_free)> table(
      gsl_integration_qaws_table_alloc(0.0, -0.5, 0, 0), &gsl_integration_qaws_table_free);
  std::unique_ptr<gsl_integration_workspace, decltype(&gsl_integration_workspace_free)> workspace(
      gsl_integration_workspace_alloc(kQuadratureIntervals), &gsl_integration_workspace_free);
  if (!table || !workspace) throw NumericalFailure("cannot allocate the GSL quadrature workspace for T(α)");
  double result = 0.0;
  double abs_error = 0.0;
  const int status = gsl_integration_qaws(&f, 0.0, alpha_rad, table.get(), kQuadratureAbsTol, kQuadratureRelTol,
                                          kQuadratureIntervals, workspace.get(), &result, &abs_error);
  // A round-off status with a tiny error estimate still gives the integral to the working precision.
  constexpr double kAcceptableRelError = 1e-11;
  if ((status != GSL_SUCCESS && !(status == GSL_EROUND && abs_error <= kAcceptableRelError * result)) ||
      !std::isfinite(result)) {
    throw NumericalFailure(std::string("the quadrature T(α) failed for α = ") + std::to_string(alpha_rad) + ": " +
                           gsl_strerror(status));
  }
  return result;
}

double LandingRate(const PlanarRocker& rocker, double alpha_rad) {
  const double drop = std::cos(rocker.critical_angle_rad - alpha_rad) - std::cos(rocker.critical_angle_rad);
  return std::sqrt(rocker.K() * std::max(drop, 0.0));
}

std::optional<double> AmplitudeFromLandingRate(const PlanarRocker& rocker, double rate_rad_s) {
  // cos(θ_c − α) = cos θ_c + ψ̇²/K; beyond 1 the COM passes over the edge.
  const double cos_value = std::cos(rocker.critical_angle_rad) + rate_rad_s * rate_rad_s / rocker.K();
  if (!(cos_value < 1.0)) return std::nullopt;
  return rocker.critical_angle_rad - std::acos(cos_value);
}

}  // namespace rockfit::core
