#include "rockfit/io/mounting_estimate.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <fmt/format.h>

#include "rockfit/core/checks.hpp"
#include "rockfit/core/errors.hpp"
#include "rockfit/io/units.hpp"

namespace rockfit::io {
namespace {

constexpr double kDegPerRad = 1.0 / kRadPerDeg;
constexpr const char* kAxisNames[3] = {"x", "y", "z"};
// The fake yaw β/sin α is taken at α of at least this [rad] (a block released nearly upright shows no fall to judge).
constexpr double kSmallestTilt_rad = 0.01;

Eigen::Matrix3d Exp(const Eigen::Vector3d& theta) {
  const double angle = theta.norm();
  if (angle == 0.0) return Eigen::Matrix3d::Identity();
  return Eigen::AngleAxisd(angle, theta / angle).toRotationMatrix();
}

Eigen::Vector3d Log(const Eigen::Matrix3d& R) {
  const Eigen::AngleAxisd aa(R);
  return aa.angle() * aa.axis();
}

Eigen::Matrix3d Skew(const Eigen::Vector3d& v) {
  Eigen::Matrix3d S;
  S << 0.0, -v.z(), v.y(), v.z(), 0.0, -v.x(), -v.y(), v.x(), 0.0;
  return S;
}

// A direction measured in the given axes with its standard error [rad].
struct Clue {
  Eigen::Vector3d direction = Eigen::Vector3d::Zero();
  double sigma_rad = 0.0;
};

// Samples [begin, end).
struct Stretch {
  std::size_t begin = 0;
  std::size_t end = 0;
  std::size_t size() const { return end > begin ? end - begin : 0; }
};

double Median(std::vector<double> values) {
  const auto mid = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
  std::nth_element(values.begin(), mid, values.end());
  return *mid;
}

// The mean specific force over a stretch at rest as a direction, its scatter giving the standard error.
Clue RestClue(const std::vector<Eigen::Vector3d>& accel, const Stretch& s, double floor_rad) {
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (std::size_t k = s.begin; k < s.end; ++k) mean += accel[k];
  const double n = static_cast<double>(s.size());
  mean /= n;
  double variance = 0.0;  // per axis, averaged over the three axes
  for (std::size_t k = s.begin; k < s.end; ++k) variance += (accel[k] - mean).squaredNorm();
  variance /= 3.0 * std::max(1.0, n - 1.0);
  const double sigma_stat = std::sqrt(variance / n) / mean.norm();
  return {mean.normalized(), std::hypot(sigma_stat, floor_rad)};
}

// The rotation axis of phase 1: the principal axis of Σ w wᵀ, signed along Σ w; its standard error from the
// scatter of w across that axis.
Clue AxisClue(const std::vector<Eigen::Vector3d>& w, double floor_rad) {
  Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& v : w) {
    scatter += v * v.transpose();
    sum += v;
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(scatter);
  Eigen::Vector3d axis = eig.eigenvectors().col(2);
  if (axis.dot(sum) < 0.0) axis = -axis;
  double across = 0.0, along = 0.0;
  for (const Eigen::Vector3d& v : w) {
    const double a = v.dot(axis);
    along += a * a;
    across += (v - a * axis).squaredNorm();
  }
  const double n = static_cast<double>(w.size());
  const double sigma_across = std::sqrt(across / (2.0 * std::max(1.0, n - 2.0)));  // per transverse axis
  return {axis, std::hypot(sigma_across / std::sqrt(along), floor_rad)};
}

// The RMS per transverse axis of w across `axis` (the spread AxisClue's standard error comes from).
double AcrossAxisRms(const std::vector<Eigen::Vector3d>& w, const Eigen::Vector3d& axis) {
  double across = 0.0;
  for (const Eigen::Vector3d& v : w) across += (v - v.dot(axis) * axis).squaredNorm();
  return std::sqrt(across / (2.0 * std::max(1.0, static_cast<double>(w.size()) - 2.0)));
}

// The gyro's noise at rest: the RMS per axis of ω − bias over the stretch.
double RestRateRms(const std::vector<Eigen::Vector3d>& w, const Stretch& s, const Eigen::Vector3d& bias) {
  double sum = 0.0;
  for (std::size_t k = s.begin; k < s.end; ++k) sum += (w[k] - bias).squaredNorm();
  return std::sqrt(sum / (3.0 * std::max(1.0, static_cast<double>(s.size()) - 1.0)));
}

// The roll the gyro sees in the fall, samples [begin, end) less the bias: the largest |∫ω'_x dt| with x' = axis × level
// (the block's x axis when `axis` is its y axis and `level` its z axis) and ω'_x = ω_x' − s·ω_y', s the regression of
// ω_x' on ω_y' = ω·axis, which takes out what a gyro leaning towards y sees of a planar fall (as the fit's release
// roll choice does, fitting/release_roll_choice.hpp).
double RollSeenInFall(const Recording& r, const Eigen::Vector3d& bias, std::size_t begin, std::size_t end,
                      const Eigen::Vector3d& axis, const Eigen::Vector3d& level, double rate_hz) {
  const Eigen::Vector3d x_axis = axis.cross(level).normalized();
  double sum_xy = 0.0, sum_yy = 0.0;
  for (std::size_t k = begin; k < end; ++k) {
    const Eigen::Vector3d w = r.w_B[k] - bias;
    sum_xy += w.dot(x_axis) * w.dot(axis);
    sum_yy += w.dot(axis) * w.dot(axis);
  }
  const double lean = sum_yy > 0.0 ? sum_xy / sum_yy : 0.0;
  double roll_rad = 0.0, largest_rad = 0.0;
  for (std::size_t k = begin; k < end; ++k) {
    const Eigen::Vector3d w = r.w_B[k] - bias;
    roll_rad += (w.dot(x_axis) - lean * w.dot(axis)) / rate_hz;
    largest_rad = std::max(largest_rad, std::abs(roll_rad));
  }
  return largest_rad;
}

// Rotation with R·e_y = y_image and R·e_z as close to z_image as that allows (TRIAD).
Eigen::Matrix3d Triad(const Eigen::Vector3d& y_image, const Eigen::Vector3d& z_image) {
  const Eigen::Vector3d y = y_image.normalized();
  const Eigen::Vector3d x = y.cross(z_image).normalized();
  Eigen::Matrix3d R;
  R.col(0) = x;
  R.col(1) = y;
  R.col(2) = x.cross(y);
  return R;
}

double AngleBetween(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::atan2(a.cross(b).norm(), a.dot(b));
}

MountingEstimate Fail(MountingEstimate e, MountingStatus status, const std::string& message) {
  e.check.status = status;
  e.check.message = message;
  return e;
}

std::string AngleList(const Eigen::Vector3d& angles_deg) {
  return fmt::format("x {:+.2f}°, y {:+.2f}°, z {:+.2f}°", angles_deg.x(), angles_deg.y(), angles_deg.z());
}

// The signed axis permutation nearest to R_BS ("-x,-y,z"), when R_BS is within `within_deg` of one.
std::optional<std::string> NearPermutation(const Eigen::Matrix3d& R_BS, double within_deg) {
  Eigen::Matrix3d P = Eigen::Matrix3d::Zero();
  std::string text;
  for (int i = 0; i < 3; ++i) {
    Eigen::Index j = 0;
    R_BS.row(i).cwiseAbs().maxCoeff(&j);
    P(i, j) = R_BS(i, j) < 0.0 ? -1.0 : 1.0;
    text += fmt::format("{}{}{}", i ? "," : "", P(i, j) < 0.0 ? "-" : "", kAxisNames[j]);
  }
  if (!(P.transpose() * P).isIdentity(1e-12) || P.determinant() < 0.0) return std::nullopt;
  if (Eigen::AngleAxisd(R_BS * P.transpose()).angle() * kDegPerRad > within_deg) return std::nullopt;
  return text;
}

// The least squares of the clues (mounting_estimate.hpp): Gauss–Newton over x = (δ (3), α) with R = R0·Exp(θ),
// θ ← Log(Exp(θ)·Exp(δ)). N = 4: the block rests on its release edge, rest before the release Rᵀ·a = (sin α, 0,
// cos α) and phase 1 Rᵀ·axis = e_y. N = 5: it rests rolled by β on one corner of that edge, x = (δ, α, β), rest
// before Rᵀ·a = (sin α cos β, −sin β, cos α cos β) (a unit vector for any α, β), and phase 1 is left out: about a
// corner the block does not turn about its y axis. Both: rest after the rocking Rᵀ·a = e_z when there is one, and a
// weak prior θ ≈ 0.
template <int N>
struct ClueSolution {
  Eigen::Vector3d theta = Eigen::Vector3d::Zero();
  double alpha_rad = 0.0;
  double beta_rad = 0.0;  // N = 5 only
  Eigen::Matrix<double, N, N> covariance;
};

template <int N>
ClueSolution<N> SolveClues(const Eigen::Matrix3d& R0, const Clue& rest_before, const Clue& axis,
                           const std::optional<Clue>& rest_after, double sigma_prior) {
  static_assert(N == 4 || N == 5, "x = (δ, α) or (δ, α, β)");
  using Jacobian = Eigen::Matrix<double, 3, N>;
  ClueSolution<N> x;
  Eigen::Vector3d& theta = x.theta;
  const Eigen::Vector3d v0 = R0.transpose() * rest_before.direction;
  double& alpha = x.alpha_rad;
  double& beta = x.beta_rad;
  alpha = std::atan2(v0.x(), v0.z());
  Eigen::Matrix<double, N, N> H = Eigen::Matrix<double, N, N>::Zero();
  constexpr int kMaxIterations = 30;
  constexpr double kStepTolerance_rad = 1e-12;  // far below any measurable angle
  for (int iteration = 0; iteration < kMaxIterations; ++iteration) {
    const Eigen::Matrix3d R = R0 * Exp(theta);
    H.setZero();
    Eigen::Matrix<double, N, 1> g = Eigen::Matrix<double, N, 1>::Zero();
    const auto add = [&](const Eigen::Vector3d& residual, const Jacobian& J, double sigma) {
      const double w = 1.0 / (sigma * sigma);
      H += w * J.transpose() * J;
      g += w * J.transpose() * residual;
    };
    // N = 5: the rotation about z is held at the given mounting (only the prior sees it), so that the lean at rest,
    // which a turn about z would mix into the tilt, is all roll.
    const auto data_clue = [&](const Eigen::Vector3d& residual, Jacobian J, double sigma) {
      if constexpr (N == 5) J.col(2).setZero();
      add(residual, J, sigma);
    };
    {  // rest before the release
      const Eigen::Vector3d v = R.transpose() * rest_before.direction;
      Jacobian J;
      J.template leftCols<3>() = Skew(v);
      if constexpr (N == 4) {
        J.col(3) = -Eigen::Vector3d(std::cos(alpha), 0.0, -std::sin(alpha));
        add(v - Eigen::Vector3d(std::sin(alpha), 0.0, std::cos(alpha)), J, rest_before.sigma_rad);
      } else {
        const double ca = std::cos(alpha), sa = std::sin(alpha), cb = std::cos(beta), sb = std::sin(beta);
        J.col(3) = -Eigen::Vector3d(ca * cb, 0.0, -sa * cb);
        J.col(4) = -Eigen::Vector3d(-sa * sb, -cb, -ca * sb);
        data_clue(v - Eigen::Vector3d(sa * cb, -sb, ca * cb), J, rest_before.sigma_rad);
      }
    }
    if constexpr (N == 4) {  // phase 1
      const Eigen::Vector3d v = R.transpose() * axis.direction;
      Jacobian J = Jacobian::Zero();
      J.template leftCols<3>() = Skew(v);
      add(v - Eigen::Vector3d::UnitY(), J, axis.sigma_rad);
    }
    if (rest_after) {  // rest after the rocking
      const Eigen::Vector3d v = R.transpose() * rest_after->direction;
      Jacobian J = Jacobian::Zero();
      J.template leftCols<3>() = Skew(v);
      data_clue(v - Eigen::Vector3d::UnitZ(), J, rest_after->sigma_rad);
    }
    {  // weak prior: θ ≈ 0
      Jacobian J = Jacobian::Zero();
      J.template leftCols<3>() = Eigen::Matrix3d::Identity();
      add(theta, J, sigma_prior);
    }
    const Eigen::Matrix<double, N, 1> step = H.ldlt().solve(-g);
    theta = Log(Exp(theta) * Exp(step.template head<3>()));
    alpha += step(3);
    if constexpr (N == 5) beta += step(4);
    if (step.norm() < kStepTolerance_rad) break;
  }
  x.covariance = H.inverse();
  return x;
}

}  // namespace

void MountingEstimateOptions::Validate() const {
  RequirePositive(rest_rate_rad_s, "mounting estimate: rest_rate_rad_s");
  RequirePositive(min_rest_s, "mounting estimate: min_rest_s");
  RequirePositive(prior_deg, "mounting estimate: prior_deg");
  RequirePositive(undetermined_std_deg, "mounting estimate: undetermined_std_deg");
  RequirePositive(direction_floor_deg, "mounting estimate: direction_floor_deg");
  RequirePositive(phase1_across_to_noise, "mounting estimate: phase1_across_to_noise");
  RequirePositive(max_roll_yaw_deg, "mounting estimate: max_roll_yaw_deg");
  RequirePositive(max_rests_apart_deg, "mounting estimate: max_rests_apart_deg");
  RequirePositive(max_fall_turn_deg, "mounting estimate: max_fall_turn_deg");
  RequireNonNegative(rest_margin_s, "mounting estimate: rest_margin_s");
  RequireNonNegative(max_turn_before_fall_deg, "mounting estimate: max_turn_before_fall_deg");
  if (!(phase1_min_fraction > 0.0 && phase1_min_fraction < 1.0) ||
      !(first_impact_fraction > 0.0 && first_impact_fraction <= 1.0)) {
    throw InvalidArgument("mounting estimate: phase1_min_fraction must lie in (0, 1), first_impact_fraction in (0, 1]");
  }
}

MountingEstimate EstimateMounting(const Recording& r, const MountingEstimateOptions& o) {
  o.Validate();
  MountingEstimate e;
  e.check.given = r.mounting;
  if (!r.has_accel()) {
    return Fail(e, MountingStatus::kNoAccelerometer, "the recording has no accelerometer, which shows the block's tilt at rest");
  }
  const std::size_t n = r.size();
  const double rate_hz = r.rate_hz > 0.0 ? r.rate_hz : 1.0;
  const auto samples = [&](double seconds) { return static_cast<std::size_t>(std::ceil(seconds * rate_hz)); };
  const std::size_t min_rest = samples(o.min_rest_s);
  const std::size_t margin = samples(o.rest_margin_s);
  if (n < 2 * min_rest + 3) return Fail(e, MountingStatus::kNoRelease, fmt::format("the recording has only {} samples", n));

  // First impact: the first local maximum of |ω| of at least a fraction of the largest.
  std::vector<double> rate(n);
  for (std::size_t k = 0; k < n; ++k) rate[k] = r.w_B[k].norm();
  const double max_rate = *std::max_element(rate.begin(), rate.end());
  if (!(max_rate > 5.0 * o.rest_rate_rad_s)) {
    return Fail(e, MountingStatus::kNoRelease,
                fmt::format("|ω| never exceeds {:.3g} rad/s: the recording shows no release", 5.0 * o.rest_rate_rad_s));
  }
  std::size_t k_impact = n;
  for (std::size_t k = 1; k + 1 < n; ++k) {
    if (rate[k] >= o.first_impact_fraction * max_rate && rate[k] >= rate[k - 1] && rate[k] >= rate[k + 1]) {
      k_impact = k;
      break;
    }
  }
  if (k_impact == n || k_impact < min_rest) {
    return Fail(e, MountingStatus::kNoRelease, "the first impact comes too early in the recording to see the block at rest before it");
  }

  // Rest before the release: the bias first from the median over everything before the impact, then the
  // stretch of small |ω − bias| that ends a margin before the motion leading to the impact.
  Eigen::Vector3d bias;
  for (int i = 0; i < 3; ++i) {
    std::vector<double> c(k_impact);
    for (std::size_t k = 0; k < k_impact; ++k) c[k] = r.w_B[k][i];
    bias[i] = Median(std::move(c));
  }
  const auto still = [&](std::size_t k) { return (r.w_B[k] - bias).norm() < o.rest_rate_rad_s; };
  std::size_t release = k_impact;
  while (release > 0 && !still(release - 1)) --release;
  // The still samples that end a margin before the motion starting at `motion`.
  const auto still_before = [&](std::size_t motion) {
    Stretch s{0, motion > margin ? motion - margin : 0};
    s.begin = s.end;
    while (s.begin > 0 && still(s.begin - 1)) --s.begin;
    return s;
  };
  Stretch before = still_before(release);
  // A hand that lets go late can lift the block a little before it falls (a push away from the fall): the block
  // stops for a few samples at the top, which is no rest, and the rest it was held in comes before the lift. Look
  // past such short stops while the block turned by at most max_turn_before_fall_deg from there to the fall.
  const double max_turn_rad = o.max_turn_before_fall_deg * kRadPerDeg;
  double turn_before_fall_rad = 0.0;
  for (Stretch earlier = before; before.size() < min_rest && earlier.begin > 0;) {
    std::size_t end = earlier.begin;  // back over the motion before the short stop
    while (end > 0 && !still(end - 1)) --end;
    // The farthest the block got from where that stretch ended: |∫(ω − bias) dt| from there, up to the fall.
    Eigen::Vector3d turn_rad = Eigen::Vector3d::Zero();
    double farthest_rad = 0.0;
    for (std::size_t k = end; k < release; ++k) {
      turn_rad += (r.w_B[k] - bias) / rate_hz;
      farthest_rad = std::max(farthest_rad, turn_rad.norm());
    }
    if (end == 0 || farthest_rad > max_turn_rad) break;
    earlier = still_before(end);
    if (earlier.size() >= min_rest) {
      before = earlier;
      turn_before_fall_rad = farthest_rad;
    }
  }
  if (before.size() < min_rest) {
    return Fail(e, MountingStatus::kNoRest,
                fmt::format("the block is still for only {:.3f} s before the motion that ends in the first impact "
                            "(from {:.3f} s); the tilt at rest needs at least {:.2f} s",
                            static_cast<double>(before.size()) / rate_hz, r.t_s[release], o.min_rest_s));
  }
  bias.setZero();
  for (std::size_t k = before.begin; k < before.end; ++k) bias += r.w_B[k];
  bias /= static_cast<double>(before.size());
  e.gyro_bias_rad_s = bias;
  e.rest_before_first = before.begin;
  e.rest_before_samples = before.size();

  // Phase 1: from the release to the sample before the first impact's peak, where |ω| is large enough.
  const double landing = (r.w_B[k_impact] - bias).norm();
  std::vector<Eigen::Vector3d> phase1;
  for (std::size_t k = release; k < k_impact; ++k) {
    const Eigen::Vector3d w = r.w_B[k] - bias;
    if (w.norm() >= o.phase1_min_fraction * landing) phase1.push_back(w);
  }
  constexpr std::size_t kMinPhase1Samples = 5;  // a direction from fewer is noise
  if (phase1.size() < kMinPhase1Samples) {
    return Fail(e, MountingStatus::kNoRelease, fmt::format("phase 1 before the first impact at {:.3f} s has only {} samples",
                                             r.t_s[k_impact], phase1.size()));
  }
  e.phase1_samples = phase1.size();
  // A block pushed over its release edge falls onto a side, not onto its base: no fall to read the mounting from.
  Eigen::Vector3d fall_turn_rad = Eigen::Vector3d::Zero();
  for (std::size_t k = release; k < k_impact; ++k) fall_turn_rad += (r.w_B[k] - bias) / rate_hz;
  if (fall_turn_rad.norm() * kDegPerRad > o.max_fall_turn_deg) {
    return Fail(e, MountingStatus::kNoRelease,
                fmt::format("the block turned by {:.0f}° between its release at {:.3f} s and its first impact at "
                            "{:.3f} s (a fall onto its base turns by its release tilt): it fell over its release edge "
                            "onto another face, which shows nothing of the mounting",
                            fall_turn_rad.norm() * kDegPerRad, r.t_s[release], r.t_s[k_impact]));
  }

  // Rest after the rocking: the trailing stretch of small |ω − bias|, after the first impact.
  Stretch after{n, n};
  while (after.begin > k_impact + 1 && still(after.begin - 1)) --after.begin;
  after.begin = std::min(n, after.begin + margin);
  const double floor_rad = o.direction_floor_deg * kRadPerDeg;
  const Clue rest_before = RestClue(r.accel_B, before, floor_rad);
  const Clue axis = AxisClue(phase1, floor_rad);
  // A block back on its base rests within its release tilt of the rest before the release; one that overturned rests
  // on another face, which is no clue to the mounting (the angle between the two rests needs no mounting).
  const bool still_after = after.size() >= min_rest;
  const double rests_apart_deg =
      still_after ? AngleBetween(RestClue(r.accel_B, after, floor_rad).direction, rest_before.direction) * kDegPerRad
                  : 0.0;
  const bool has_after = still_after && rests_apart_deg <= o.max_rests_apart_deg;
  if (has_after) e.rest_after_samples = after.size();
  const std::optional<Clue> rest_after =
      has_after ? std::optional<Clue>(RestClue(r.accel_B, after, floor_rad)) : std::nullopt;

  // Starting rotation R0 = R_B'B: the given mounting when it is roughly right, else TRIAD from the clues.
  const Eigen::Vector3d& up = rest_after ? rest_after->direction : rest_before.direction;
  constexpr double kRoughlyRight_rad = 0.5;  // ~30°: beyond this the small-angle start is not trusted
  Eigen::Matrix3d R0 = Eigen::Matrix3d::Identity();
  if (AngleBetween(axis.direction, Eigen::Vector3d::UnitY()) > kRoughlyRight_rad ||
      AngleBetween(up, Eigen::Vector3d::UnitZ()) > kRoughlyRight_rad) {
    R0 = Triad(axis.direction, up);
  }

  const double sigma_prior = o.prior_deg * kRadPerDeg;
  const ClueSolution<4> on_edge = SolveClues<4>(R0, rest_before, axis, rest_after, sigma_prior);
  // A block released on one corner of its release edge (io/README.md, "Mounting estimate") leans sideways at rest and
  // falls about the corner, off its y axis, which the clues above read as a sensor turned about z (0.3–0.4° per mrad
  // of roll on a block of the paper's). Its phase 1 does not turn about one axis: the rate strays from the mean axis
  // by far more than the gyro's noise at rest (a sensor yawed on a release about the edge turns the axis, not the
  // rate's spread about it), and the roll it shows would fake a yaw of about β/sin α. Where both are large, phase 1 is
  // left out, β is free and the rotation about z is held.
  const double rest_noise_rad_s = RestRateRms(r.w_B, before, bias);
  const double across_to_noise = rest_noise_rad_s > 0.0 ? AcrossAxisRms(phase1, axis.direction) / rest_noise_rad_s
                                                         : std::numeric_limits<double>::infinity();
  const Eigen::Vector3d& level = rest_after ? rest_after->direction : rest_before.direction;
  const double roll_seen_rad = RollSeenInFall(r, bias, release, k_impact, axis.direction, level, rate_hz);
  const double roll_yaw_deg = roll_seen_rad / std::sin(std::max(on_edge.alpha_rad, kSmallestTilt_rad)) * kDegPerRad;
  // The rolled solution starts from the edge's without its turn about z, which it then holds: a rotation vector's z
  // component is the turn about z only near the given mounting, so a mounting found far from it (a sensor on another
  // face, a block that fell onto its side) keeps the edge's solution.
  Eigen::Vector3d start_vector = Log(R0 * Exp(on_edge.theta));
  const bool near_given = start_vector.norm() < kRoughlyRight_rad;
  start_vector.z() = 0.0;
  const Eigen::Matrix3d R0_rolled = Exp(start_vector);
  std::optional<ClueSolution<5>> rolled;
  if (near_given && across_to_noise > o.phase1_across_to_noise && roll_yaw_deg > o.max_roll_yaw_deg) {
    rolled = SolveClues<5>(R0_rolled, rest_before, axis, rest_after, sigma_prior);
  }
  const double alpha = rolled ? rolled->alpha_rad : on_edge.alpha_rad;
  const Eigen::Matrix4d covariance =
      rolled ? Eigen::Matrix4d(rolled->covariance.topLeftCorner<4, 4>()) : on_edge.covariance;

  const Eigen::Matrix3d R_BgB =
      rolled ? Eigen::Matrix3d(R0_rolled * Exp(rolled->theta)) : Eigen::Matrix3d(R0 * Exp(on_edge.theta));
  e.R_BBg = R_BgB.transpose();
  MountingCheck& c = e.check;
  c.turn_before_fall_deg = turn_before_fall_rad * kDegPerRad;
  const std::string lift_note =
      turn_before_fall_rad > 0.0
          ? fmt::format("; the block turned by {:.2f}° between that rest and the fall (lifted or pushed as it was "
                        "let go)", c.turn_before_fall_deg)
          : std::string();
  c.angles_deg = Log(e.R_BBg) * kDegPerRad;
  for (int i = 0; i < 3; ++i) {
    c.std_error_deg[i] = std::sqrt(covariance(i, i)) * kDegPerRad;
    c.determined[static_cast<std::size_t>(i)] = c.std_error_deg[i] < o.undetermined_std_deg;
  }
  c.release_tilt_rad = alpha;
  c.release_tilt_std_error_rad = std::sqrt(covariance(3, 3));
  const std::string roll_note =
      rolled ? fmt::format(": the block fell rolling (a roll of {:.1f} mrad seen in the fall, its rate off the fall's "
                           "axis by {:.0f} × the gyro's noise at rest), as one released on a corner of its release "
                           "edge does, and a roll β reads as a sensor turned about z by up to about β/sin α ({:.1f}° "
                           "here)",
                           roll_seen_rad * 1e3, across_to_noise, roll_yaw_deg)
             : std::string();
  std::vector<std::string> free_axes;
  for (int i = 0; i < 3; ++i) {
    if (!c.determined[static_cast<std::size_t>(i)]) free_axes.emplace_back(kAxisNames[i]);
  }
  if (free_axes.empty()) {
    c.status = MountingStatus::kOk;
    c.message = fmt::format("from {:.2f} s at rest before the release, {} samples of phase 1{}{}",
                            static_cast<double>(before.size()) / rate_hz, phase1.size(),
                            has_after ? fmt::format(" and {:.2f} s at rest after the rocking",
                                                    static_cast<double>(after.size()) / rate_hz)
                                      : std::string(),
                            lift_note);
  } else {
    c.status = MountingStatus::kPartial;
    std::string which;
    for (const std::string& a : free_axes) which += (which.empty() ? "" : ", ") + a;
    c.message = fmt::format(
        "the data do not fix the rotation about block {} (kept at the given mounting){}{}", which,
        has_after ? roll_note
        : still_after
            ? fmt::format(": the block did not come back to rest on its base (its rest after the rocking is {:.0f}° "
                          "from its rest before the release: it overturned), and before the release a turn about y "
                          "looks like a different tilt α",
                          rests_apart_deg)
            : fmt::format(": the recording does not end at rest (at least {:.2f} s with |ω| < {:.3g} rad/s), "
                          "and before the release a turn about y looks like a different tilt α; record until "
                          "the block stands still",
                          o.min_rest_s, o.rest_rate_rad_s),
        lift_note);
  }
  return e;
}

Mounting CorrectedMounting(const Mounting& given, const MountingEstimate& estimate) {
  const Eigen::Matrix3d R_BS = estimate.R_BBg * given.R_BS();
  // Re-orthonormalise (products of rotations drift by ~1e-16 per step; FromRotation checks 1e-9).
  return Mounting::FromRotation(Eigen::Quaterniond(R_BS).normalized().toRotationMatrix());
}

double MountingDisagreementDeg(const MountingCheck& check) {
  if (!check.has_estimate()) return std::nan("");
  double sum = 0.0;
  for (int i = 0; i < 3; ++i) {
    if (check.determined[static_cast<std::size_t>(i)]) sum += check.angles_deg[i] * check.angles_deg[i];
  }
  return std::sqrt(sum);
}

std::string MountingWarning(const MountingCheck& check, const Mounting& suggested) {
  const double off_deg = MountingDisagreementDeg(check);
  if (!(off_deg > kMountingWarningDeg)) return "";
  double std_deg = 0.0;
  for (int i = 0; i < 3; ++i) {
    if (check.determined[static_cast<std::size_t>(i)]) std_deg = std::max(std_deg, check.std_error_deg[i]);
  }
  const std::string start = check.given == "identity" ? "auto" : "auto:" + check.given;
  // A sensor mounted on another face (a permutation) is told the permutation, not a quaternion.
  const std::optional<std::string> permutation = NearPermutation(suggested.R_BS(), kMountingWarningDeg);
  return fmt::format(
      "the data disagree with the mounting '{}' by {:.2f}° (rotation about block {}, each ±{:.2f}°{}): the sensor "
      "is turned on the block. Estimate the mounting with --mounting {} (manifest: mounting = \"{}\"), or give it "
      "as --mounting={}",
      check.given, off_deg, AngleList(check.angles_deg), std_deg,
      check.status == MountingStatus::kPartial ? "; " + check.message : std::string(), start, start,
      permutation ? *permutation + " (the data agree with it within 1°)" : suggested.text());
}

}  // namespace rockfit::io
