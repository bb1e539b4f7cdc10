#include "ximu/rotation_matrix_row.hpp"

#include <string>

#include <fmt/format.h>

#include "recording/attitude.hpp"

namespace rockfit::io {

Eigen::Quaterniond RotationMatrixRow(const CsvTable& table, std::size_t row,
                                     const std::vector<std::optional<std::size_t>>& c, std::size_t first) {
  Eigen::Matrix3d M;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) M(i, j) = table.Real(row, *c[first + static_cast<std::size_t>(3 * i + j)]);
  }
  double error = 0.0;
  double determinant = 0.0;
  const Eigen::Matrix3d R_WS = NearestRotation(M, &error, &determinant);
  if (!(error <= kRotationMatrixOrthogonalityTolerance) || determinant <= 0.0) {
    table.ThrowBadCell(
        row, *c[first], fmt::format("a matrix with max |MᵀM − I| = {:.3g} and determinant {:.4g}", error, determinant),
        "a rotation matrix", "The row is damaged; correct or delete line " + std::to_string(table.Line(row)) + ".");
  }
  return Eigen::Quaterniond(R_WS).normalized();
}

}  // namespace rockfit::io
