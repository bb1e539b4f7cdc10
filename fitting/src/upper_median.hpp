// The upper median of a set of numbers: the element at index n/2 of their sorted order (the middle one for odd n,
// the upper of the two middle ones for even n), found by selection without a full sort. Internal to the library.
#pragma once

#include <algorithm>
#include <cstddef>
#include <vector>

namespace rockfit::fitting {

// `values` must not be empty; it is taken by value and reordered.
inline double UpperMedian(std::vector<double> values) {
  const auto middle = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
  std::nth_element(values.begin(), middle, values.end());
  return *middle;
}

}  // namespace rockfit::fitting
