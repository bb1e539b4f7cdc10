// One row of a rotation-matrix file of either x-IMU family (Element 11 … Element 33 in the x-IMU GUI's
// _RotationMatrix.csv, the matrix columns of the x-IMU3's AHRS file): the printed matrix to an attitude. Internal.
#pragma once

#include <cstddef>
#include <optional>
#include <vector>

#include <Eigen/Geometry>

#include "text/csv_table.hpp"

namespace rockfit::io {

// Largest max |MᵀM − I| of a printed rotation matrix [-]: 7 printed digits give ~1e-6, and the x-IMU3 prints
// diagonals such as 1.000486; anything beyond this is a damaged row, not round-off.
constexpr double kRotationMatrixOrthogonalityTolerance = 0.01;

// q_WS of `row` from the nine columns c[first], …, c[first + 8] (row-major M11 … M33): the rotation nearest to the
// printed matrix. A row that is no rotation (beyond the tolerance, or a reflection) is bad input at its first element.
Eigen::Quaterniond RotationMatrixRow(const CsvTable& table, std::size_t row,
                                     const std::vector<std::optional<std::size_t>>& c, std::size_t first);

}  // namespace rockfit::io
