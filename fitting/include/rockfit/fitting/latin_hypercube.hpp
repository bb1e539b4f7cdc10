// Latin-hypercube samples in a box, reproducible from a seed on every platform (std::mt19937_64 has a fixed
// output sequence; the conversions to [0, 1) and to indices are our own, not the implementation-defined
// standard distributions).
#pragma once

#include <cstdint>
#include <vector>

#include <Eigen/Core>

namespace rockfit::fitting {

// n points in [lower, upper] (per dimension): each dimension's range is cut into n equal strata and every
// stratum holds exactly one point, placed uniformly inside it. Throws InvalidArgument for n = 0, size mismatch,
// non-finite or inverted bounds.
std::vector<Eigen::VectorXd> LatinHypercube(const Eigen::VectorXd& lower, const Eigen::VectorXd& upper, int n,
                                            std::uint64_t seed);

}  // namespace rockfit::fitting
