#include "rockfit/fitting/latin_hypercube.hpp"

#include <cmath>
#include <numeric>
#include <random>
#include <utility>

#include <fmt/format.h>

#include "rockfit/core/errors.hpp"

namespace rockfit::fitting {
namespace {

// Uniform in [0, 1) from the top 53 bits.
double Uniform01(std::mt19937_64& rng) { return static_cast<double>(rng() >> 11) * 0x1.0p-53; }

}  // namespace

std::vector<Eigen::VectorXd> LatinHypercube(const Eigen::VectorXd& lower, const Eigen::VectorXd& upper, int n,
                                            std::uint64_t seed) {
  if (n <= 0) throw InvalidArgument(fmt::format("Latin hypercube: the number of points must be positive, got {}", n));
  if (lower.size() != upper.size()) throw InvalidArgument("Latin hypercube: lower and upper bounds differ in size");
  for (Eigen::Index d = 0; d < lower.size(); ++d) {
    if (!std::isfinite(lower[d]) || !std::isfinite(upper[d]) || lower[d] > upper[d]) {
      throw InvalidArgument(
          fmt::format("Latin hypercube: dimension {} needs finite bounds lower ≤ upper, got [{}, {}]", d, lower[d], upper[d]));
    }
  }
  std::mt19937_64 rng(seed);
  const auto count = static_cast<std::size_t>(n);
  std::vector<Eigen::VectorXd> points(count, Eigen::VectorXd(lower.size()));
  std::vector<std::size_t> strata(count);
  for (Eigen::Index d = 0; d < lower.size(); ++d) {
    std::iota(strata.begin(), strata.end(), 0);
    for (std::size_t i = count - 1; i > 0; --i) std::swap(strata[i], strata[rng() % (i + 1)]);  // Fisher–Yates
    for (std::size_t i = 0; i < count; ++i) {
      const double u = (static_cast<double>(strata[i]) + Uniform01(rng)) / static_cast<double>(count);
      points[i][d] = lower[d] + u * (upper[d] - lower[d]);
    }
  }
  return points;
}

}  // namespace rockfit::fitting
