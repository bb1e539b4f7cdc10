// Latin hypercube: one point per stratum and dimension, inside the box, reproducible from the seed.
#include "rockfit/fitting/latin_hypercube.hpp"

#include <set>

#include <gtest/gtest.h>

#include "rockfit/core/errors.hpp"

namespace rockfit::fitting {
namespace {

TEST(LatinHypercube, EveryStratumOfEveryDimensionHoldsExactlyOnePoint) {
  Eigen::VectorXd lower(3), upper(3);
  lower << -1.0, 0.0, 10.0;
  upper << 1.0, 0.5, 10.0;  // a degenerate dimension is allowed
  const int n = 37;
  const auto points = LatinHypercube(lower, upper, n, 42);
  ASSERT_EQ(points.size(), 37u);
  for (Eigen::Index d = 0; d < 2; ++d) {
    std::set<int> strata;
    for (const auto& p : points) {
      ASSERT_GE(p[d], lower[d]);
      ASSERT_LT(p[d], upper[d]);
      strata.insert(static_cast<int>((p[d] - lower[d]) / (upper[d] - lower[d]) * n));
    }
    EXPECT_EQ(strata.size(), 37u) << "dimension " << d;
  }
  for (const auto& p : points) EXPECT_EQ(p[2], 10.0);
}

TEST(LatinHypercube, IsReproducibleFromTheSeedAndChangesWithIt) {
  const Eigen::VectorXd lower = Eigen::VectorXd::Zero(4), upper = Eigen::VectorXd::Ones(4);
  const auto a = LatinHypercube(lower, upper, 10, 7);
  const auto b = LatinHypercube(lower, upper, 10, 7);
  const auto c = LatinHypercube(lower, upper, 10, 8);
  for (std::size_t i = 0; i < a.size(); ++i) EXPECT_EQ(a[i], b[i]);
  bool differs = false;
  for (std::size_t i = 0; i < a.size(); ++i) differs = differs || a[i] != c[i];
  EXPECT_TRUE(differs);
}

TEST(LatinHypercube, RejectsBadArguments) {
  const Eigen::VectorXd lower = Eigen::VectorXd::Zero(2), upper = Eigen::VectorXd::Ones(2);
  EXPECT_THROW(LatinHypercube(lower, upper, 0, 1), InvalidArgument);
  EXPECT_THROW(LatinHypercube(upper, lower, 3, 1), InvalidArgument);
  EXPECT_THROW(LatinHypercube(lower, Eigen::VectorXd::Ones(3), 3, 1), InvalidArgument);
}

}  // namespace
}  // namespace rockfit::fitting
