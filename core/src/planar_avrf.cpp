#include "rockfit/core/planar_avrf.hpp"

#include <cmath>
#include <string>

#include "rockfit/core/errors.hpp"

namespace rockfit::core {
namespace {

// θ + m h², the moment of inertia about the base point below the COM, shared by (3)–(6).
double InertiaAboutBaseCentre(const PlanarBlock& p) { return p.theta_kg_m2 + p.mass_kg * p.h_m * p.h_m; }

}  // namespace

PlanarBlock PlanarBlockAboutY(const Block& block) {
  return {block.mass(), block.inertia_C_B()(1, 1), block.h(), block.b1()};
}

PlanarBlock PlanarBlockAboutX(const Block& block) {
  return {block.mass(), block.inertia_C_B()(0, 0), block.h(), block.b2()};
}

// Each formula is written out as printed in the paper (not through (6)), so that the identities between
// them are tests, not definitions.
double AvrfHousner(const PlanarBlock& p) {
  const double j0 = InertiaAboutBaseCentre(p);
  const double mb2 = p.mass_kg * p.b_m * p.b_m;
  return (j0 - mb2) / (j0 + mb2);  // (3)
}

double AvrfKalliontzis(const PlanarBlock& p, double v) {
  const double j0 = InertiaAboutBaseCentre(p);
  const double mv2b2 = p.mass_kg * v * v * p.b_m * p.b_m;
  return (j0 - mv2b2) / (j0 + mv2b2);  // (4)
}

double AvrfTherKollar(const PlanarBlock& p) {
  const double j0 = InertiaAboutBaseCentre(p);
  return j0 / (j0 + p.mass_kg * p.b_m * p.b_m);  // (5)
}

double AvrfChatzis(const PlanarBlock& p, double lambda) {
  const double j0 = InertiaAboutBaseCentre(p);
  const double mb2 = p.mass_kg * p.b_m * p.b_m;
  return (j0 - lambda * mb2) / (j0 + lambda * mb2);  // (6)
}

double LambdaFromAvrf(const PlanarBlock& p, double r) {
  if (!std::isfinite(r) || r == -1.0) {
    throw InvalidArgument("the inverse of (6) needs a finite AVRF r ≠ −1, got " + std::to_string(r));
  }
  // (6) solved for λ: r(J0 + λ m b²) = J0 − λ m b²  ⇒  λ = J0 (1 − r) / (m b² (1 + r)).
  const double j0 = InertiaAboutBaseCentre(p);
  return j0 * (1.0 - r) / (p.mass_kg * p.b_m * p.b_m * (1.0 + r));
}

}  // namespace rockfit::core
