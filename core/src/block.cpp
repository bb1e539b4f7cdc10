#include "rockfit/core/block.hpp"

#include <cmath>
#include <string>

#include "rockfit/core/checks.hpp"
#include "rockfit/core/errors.hpp"

namespace rockfit::core {

Block::Block(double b1, double b2, double h, double mass) : b1_(b1), b2_(b2), h_(h), mass_(mass) {
  inertia_C_B_ = Eigen::Vector3d(b2 * b2 + h * h, b1 * b1 + h * h, b1 * b1 + b2 * b2).asDiagonal();
  inertia_C_B_ *= mass / 3.0;
}

Block Block::FromDensity(double b1_m, double b2_m, double h_m, double density_kg_m3) {
  RequirePositive(b1_m, "block b1", "metres");
  RequirePositive(b2_m, "block b2", "metres");
  RequirePositive(h_m, "block h", "metres");
  RequirePositive(density_kg_m3, "block density", "kg/m³");
  const double mass_kg = 8.0 * density_kg_m3 * b1_m * b2_m * h_m;
  RequirePositive(mass_kg, "block mass (from density)", "kg");
  return Block(b1_m, b2_m, h_m, mass_kg);
}

Block Block::FromMass(double b1_m, double b2_m, double h_m, double mass_kg) {
  RequirePositive(b1_m, "block b1", "metres");
  RequirePositive(b2_m, "block b2", "metres");
  RequirePositive(h_m, "block h", "metres");
  RequirePositive(mass_kg, "block mass", "kg");
  return Block(b1_m, b2_m, h_m, mass_kg);
}

Eigen::Vector3d Block::p_BV_B(int k) const {
  switch (WrapVertex(k)) {
    case 1: return {-b1_, -b2_, 0.0};
    case 2: return {-b1_, +b2_, 0.0};
    case 3: return {+b1_, +b2_, 0.0};
    default: return {+b1_, -b2_, 0.0};
  }
}

bool Block::AreNeighbours(int i, int j) {
  const int d = (WrapVertex(i) - WrapVertex(j) + 4) % 4;
  return d == 1 || d == 3;
}

}  // namespace rockfit::core
