#include "rockfit/io/mounting.hpp"

#include <array>
#include <cmath>
#include <vector>

#include <fmt/format.h>

#include "rockfit/core/errors.hpp"
#include "text/header_matching.hpp"
#include "text/number_parsing.hpp"

namespace rockfit::io {
namespace {

constexpr std::string_view kSyntax =
    "expected an axis permutation with signs such as 'x,-y,-z' (entry i = the sensor axis along block axis i), "
    "a unit quaternion 'w,x,y,z' (q_BS, scalar first) or 'identity'";

std::vector<std::string_view> SplitComma(std::string_view text) {
  std::vector<std::string_view> parts;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = text.find(',', start);
    parts.push_back(TrimSpaces(text.substr(start, comma == std::string_view::npos ? std::string_view::npos : comma - start)));
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
  return parts;
}

[[noreturn]] void Refuse(std::string_view text, const std::string& why) {
  throw InvalidArgument("mounting '" + std::string(text) + "': " + why);
}

// "x", "-y", "+z" → (axis index, sign); nullopt for anything else.
bool ParseAxis(std::string_view token, int& axis, double& sign) {
  sign = 1.0;
  if (!token.empty() && (token.front() == '-' || token.front() == '+')) {
    sign = token.front() == '-' ? -1.0 : 1.0;
    token.remove_prefix(1);
  }
  token = TrimSpaces(token);
  if (token.size() != 1) return false;
  const char c = static_cast<char>(token.front() | 0x20);  // lower case
  if (c < 'x' || c > 'z') return false;
  axis = c - 'x';
  return true;
}

struct AxisEntry {
  int axis = 0;      // 0, 1, 2 for sensor x, y, z
  double sign = 1.0;
};

std::string PermutationText(const std::array<AxisEntry, 3>& entries) {
  std::string text;
  for (std::size_t i = 0; i < 3; ++i) {
    text += (i ? "," : "") + std::string(entries[i].sign < 0 ? "-" : "") + static_cast<char>('x' + entries[i].axis);
  }
  return text;
}

std::array<AxisEntry, 3> ParsePermutation(std::string_view text, const std::vector<std::string_view>& parts) {
  std::array<AxisEntry, 3> entries{};
  std::array<bool, 3> used{false, false, false};
  for (std::size_t i = 0; i < 3; ++i) {
    if (!ParseAxis(parts[i], entries[i].axis, entries[i].sign)) {
      Refuse(text, "entry " + std::to_string(i + 1) + " is '" + std::string(parts[i]) + "'; " + std::string(kSyntax));
    }
    const auto axis = static_cast<std::size_t>(entries[i].axis);
    if (used[axis]) {
      Refuse(text, std::string("sensor axis ") + static_cast<char>('x' + axis) +
                       " appears twice; each of x, y and z must appear exactly once (with a sign)");
    }
    used[axis] = true;
  }
  return entries;
}

}  // namespace

Mounting Mounting::Parse(std::string_view text) {
  const std::string normalized = NormalizeHeader(text);
  if (normalized.empty() || normalized == "identity") return Mounting();
  const std::vector<std::string_view> parts = SplitComma(text);
  if (parts.size() == 3) {
    const std::array<AxisEntry, 3> entries = ParsePermutation(text, parts);
    Eigen::Matrix3d R_BS = Eigen::Matrix3d::Zero();
    for (std::size_t i = 0; i < 3; ++i) R_BS(static_cast<Eigen::Index>(i), entries[i].axis) = entries[i].sign;
    if (R_BS.determinant() < 0.0) {
      std::array<AxisEntry, 3> flipped = entries;
      flipped[2].sign = -flipped[2].sign;
      Refuse(text, "this is a mirror image (determinant -1), not a rotation, so no sensor can be mounted that way; "
                   "flip the sign of one more entry, e.g. '" + PermutationText(flipped) + "', and check the axes");
    }
    if (R_BS.isIdentity(0.0)) return Mounting();
    return Mounting(Eigen::Quaterniond(R_BS).normalized(), PermutationText(entries));
  }
  if (parts.size() == 4) {
    std::array<double, 4> wxyz{};
    for (std::size_t i = 0; i < 4; ++i) {
      const ParsedNumber number = ParseReal(parts[i]);
      if (number.status != NumberStatus::kOk) {
        Refuse(text, "component " + std::to_string(i + 1) + " '" + std::string(parts[i]) +
                         "' is not a finite number; " + std::string(kSyntax));
      }
      wxyz[i] = number.value;
    }
    Eigen::Quaterniond q(wxyz[0], wxyz[1], wxyz[2], wxyz[3]);
    constexpr double kUnitNormTolerance = 1e-3;  // typed-in quaternions with ~4 digits; more is a mistake
    if (std::abs(q.norm() - 1.0) > kUnitNormTolerance) {
      Refuse(text, fmt::format("the quaternion has norm {:.6g}, expected a unit quaternion (norm 1 within {:g})",
                               q.norm(), kUnitNormTolerance));
    }
    q.normalize();
    return Mounting(q, fmt::format("{:.9g},{:.9g},{:.9g},{:.9g}", q.w(), q.x(), q.y(), q.z()));
  }
  Refuse(text, "found " + std::to_string(parts.size()) + " comma-separated entries, " + std::string(kSyntax));
}

Mounting Mounting::FromRotation(const Eigen::Matrix3d& R_BS) {
  constexpr double kOrthonormalTolerance = 1e-9;  // max |RᵀR − I|; exact for permutations, tight for computed ones
  const double error = (R_BS.transpose() * R_BS - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
  if (!(error <= kOrthonormalTolerance)) {
    throw InvalidArgument(fmt::format("mounting rotation is not orthonormal (max |RᵀR − I| = {:.3g})", error));
  }
  if (R_BS.determinant() < 0.0) {
    throw InvalidArgument("mounting rotation is a mirror image (determinant −1), not a rotation");
  }
  const Eigen::Quaterniond q(R_BS);
  if (R_BS.isIdentity(0.0)) return Mounting();
  const Eigen::Quaterniond unit = q.normalized();
  return Mounting(unit, fmt::format("{:.9g},{:.9g},{:.9g},{:.9g}", unit.w(), unit.x(), unit.y(), unit.z()));
}

MountingOption MountingOption::Parse(std::string_view text) {
  const std::string_view trimmed = TrimSpaces(text);
  constexpr std::string_view kAuto = "auto";
  MountingOption option;
  if (trimmed.size() >= kAuto.size() && NormalizeHeader(trimmed.substr(0, kAuto.size())) == kAuto) {
    std::string_view rest = TrimSpaces(trimmed.substr(kAuto.size()));
    if (!rest.empty() && rest.front() != ':') {
      Refuse(text, "expected 'auto' or 'auto:SPEC' with SPEC the starting mounting, e.g. 'auto:x,-y,-z'");
    }
    if (!rest.empty()) rest.remove_prefix(1);
    option.estimate = true;
    option.given = Mounting::Parse(TrimSpaces(rest));
    return option;
  }
  option.given = Mounting::Parse(trimmed);
  return option;
}

std::string MountingOption::text() const {
  if (!estimate) return given.text();
  return given.is_identity() ? "auto" : "auto:" + given.text();
}

}  // namespace rockfit::io
