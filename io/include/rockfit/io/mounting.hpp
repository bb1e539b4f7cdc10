// How the IMU sits on the block (docs/design.md §2): the rotation R_BS from sensor axes S to block axes B.
// Applied by every reader: w_B = R_BS·w_S, a_B = R_BS·a_S, R_WB = R_WS·R_BSᵀ.
//
// Text forms (io/README.md, "Mounting"):
//  * an axis permutation with signs, "x,-y,-z": entry i names the sensor axis that points along
//    block axis i (here block x = sensor x, block y = −sensor y, block z = −sensor z, i.e. the IMU
//    upside down). Each of x, y, z once; the result must be a rotation (determinant +1), so mirror
//    images such as "x,y,-z" are refused.
//  * a unit quaternion "w,x,y,z" = q_BS (scalar first, Hamilton); a norm within 1e-3 of 1 is
//    normalised, anything else is refused.
//  * "identity" or "" (the default): sensor axes are block axes.
// A mounting *option* (MountingOption) may also be "auto" or "auto:SPEC": estimate the mounting from the
// recording (mounting_estimate.hpp), starting at SPEC (identity without it).
#pragma once

#include <string>
#include <string_view>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace rockfit::io {

class Mounting {
 public:
  Mounting() = default;  // identity

  // Throws rockfit::InvalidArgument with a message that quotes `text` and shows the syntax. (A
  // manifest reader may catch it and re-throw BadInput with the manifest's line.)
  static Mounting Parse(std::string_view text);
  // Throws InvalidArgument unless R_BS is a rotation (orthonormal to 1e-9, determinant +1).
  static Mounting FromRotation(const Eigen::Matrix3d& R_BS);

  const Eigen::Quaterniond& q_BS() const { return q_BS_; }
  Eigen::Matrix3d R_BS() const { return q_BS_.toRotationMatrix(); }
  bool is_identity() const { return text_ == "identity"; }
  // Canonical text: "identity", a permutation "x,-y,-z", or "w,x,y,z" with 9 significant digits.
  const std::string& text() const { return text_; }

  // A sensor-frame vector (angular velocity, specific force) in block axes: R_BS·v_S.
  Eigen::Vector3d ToBlock(const Eigen::Vector3d& v_S) const { return q_BS_ * v_S; }
  // The block's attitude from the sensor's: q_WB = q_WS ⊗ q_BS⁻¹ (R_WB = R_WS·R_BSᵀ).
  Eigen::Quaterniond BlockAttitude(const Eigen::Quaterniond& q_WS) const { return q_WS * q_BS_.conjugate(); }

 private:
  Mounting(const Eigen::Quaterniond& q_BS, std::string text) : q_BS_(q_BS), text_(std::move(text)) {}

  Eigen::Quaterniond q_BS_ = Eigen::Quaterniond::Identity();
  std::string text_ = "identity";
};

// What --mounting and the manifest's `mounting` say: a mounting, and whether to estimate it from the data
// starting there ("auto", "auto:x,-y,-z", "auto:0.999,0,0,0.0436").
struct MountingOption {
  Mounting given;         // the mounting as given (identity for plain "auto")
  bool estimate = false;  // "auto": the readers estimate the mounting from the recording, starting at `given`

  // Throws InvalidArgument like Mounting::Parse.
  static MountingOption Parse(std::string_view text);
  // "auto", "auto:SPEC" or the mounting's canonical text.
  std::string text() const;
};

}  // namespace rockfit::io
