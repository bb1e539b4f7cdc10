// Planar angular-velocity reduction factors (AVRF) of Sect. 2 of the paper: Housner (3), Kalliontzis (4),
// Ther–Kollár (5), Chatzis (6), and the inverse of (6).
#pragma once

#include "rockfit/core/block.hpp"

namespace rockfit::core {

// A planar rocking block: mass m, moment of inertia θ about the COM (planar), COM height h and half-length b
// of the impacting base.
struct PlanarBlock {
  double mass_kg;
  double theta_kg_m2;
  double h_m;
  double b_m;
};
// Rocking in the xz plane (about y): θ = Θ_yy, b = b1.
PlanarBlock PlanarBlockAboutY(const Block& block);
// Rocking in the yz plane (about x): θ = Θ_xx, b = b2.
PlanarBlock PlanarBlockAboutX(const Block& block);

double AvrfHousner(const PlanarBlock& p);                   // (3)
double AvrfKalliontzis(const PlanarBlock& p, double v);     // (4)
double AvrfTherKollar(const PlanarBlock& p);                // (5)
double AvrfChatzis(const PlanarBlock& p, double lambda);    // (6)
// Inverse of (6): the λ whose AVRF is r. Defined for every finite r ≠ −1; throws InvalidArgument otherwise.
double LambdaFromAvrf(const PlanarBlock& p, double r);

}  // namespace rockfit::core
