// `--mounting auto` as a user runs it: `rockfit synth` writes x-IMU recordings (default measurement model: gyro
// noise, quantisation, ringing, drift, plus a gyro bias) with the sensor turned by a random rotation of up to 5°
// about a random axis (fixed seed); `rockfit metrics` and `rockfit fit` read them with `--mounting auto` and are
// compared with the same trial recorded with the sensor on the block's axes:
//   * the estimated rotation is within 0.2° of the truth;
//   * the OPMF is within 5 % of the aligned trial's, or within 0.002 where that is below 0.04;
//   * every fitted parameter lies within the aligned fit's 95 % interval, value ± 1.96·std_error;
//   * ε (28) is within 2 % of the aligned fit's
// (whole fits for one misalignment per block here, for the suite's time budget; io/README.md has all twenty).
// Also the sensor upside down (a signed permutation times a small rotation), planar trials (λ_lat = 0) with and
// without rest at the end, and the warning for a wrong mounting given without `auto`. Whole fits run the
// simulator thousands of times: optimised builds only (tests/io/signal/mounting_estimate_test.cpp covers the estimate
// in every build).
#include <cmath>
#include <cstdio>
#include <iostream>
#include <random>
#include <regex>
#include <string>
#include <vector>

#include <Eigen/Geometry>
#include <fmt/format.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "build_type.hpp"
#include "cli_runner.hpp"
#include "scratch_dir.hpp"

namespace rockfit::testing {
namespace {

using ::testing::HasSubstr;

constexpr double kPi = 3.14159265358979323846;
constexpr double kDegPerRad = 180.0 / kPi;
// The acceptance criteria of `--mounting auto`.
constexpr double kEstimateTolerance_deg = 0.2;
constexpr double kOpmfRelative = 0.05;
constexpr double kOpmfAbsolute = 0.002;  // where the aligned OPMF is below kSmallOpmf
constexpr double kSmallOpmf = 0.04;
constexpr double kIntervalZ = 1.96;  // 95 % interval of today's fit summary: value ± 1.96·std_error
constexpr double kEpsilonRelative = 0.02;
constexpr double kMaxMisalignment_deg = 5.0;

struct Trial {
  double b2_m, h_m;
  double t0_s, alpha_rad, lambda, lambda_lat, lambda_lon;
  std::uint64_t seed;
  double rocking_s = 4.5;  // recorded after the release: long enough to end at rest
  double release_roll_rad = 0.0;
};

std::string Num(double v) { return fmt::format("{:.17g}", v); }

std::vector<std::string> BlockArgs(const Trial& t) {
  return {"--b1", "0.05", "--b2", Num(t.b2_m), "--h", Num(t.h_m), "--density", "2692"};
}

std::vector<std::string> Join(std::vector<std::string> a, const std::vector<std::string>& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

// "w,x,y,z" of R_BS.
std::string QuaternionText(const Eigen::Matrix3d& R_BS) {
  const Eigen::Quaterniond q(R_BS);
  return fmt::format("{:.17g},{:.17g},{:.17g},{:.17g}", q.w(), q.x(), q.y(), q.z());
}

std::string Synthesize(const ScratchDir& dir, const std::string& name, const Trial& t, const std::string& mounting) {
  const std::string prefix = (dir / name).string();
  const CommandResult r = RunRockfit(Join(
      {"synth", "-o", prefix, "--alpha", Num(t.alpha_rad), "--lambda", Num(t.lambda), "--lambda-lat",
       Num(t.lambda_lat), "--lambda-lon", Num(t.lambda_lon), "--t0", Num(t.t0_s), "--duration",
       Num(t.t0_s + t.rocking_s), "--seed", std::to_string(t.seed), "--gyro-bias-dps=0.25,-0.15,0.1",
       "--mounting=" + mounting, "--no-rotation-matrix", "--release-roll", Num(t.release_roll_rad)},
      BlockArgs(t)));
  EXPECT_EQ(r.exit_code, 0) << r.err;
  return prefix;
}

nlohmann::json RunJson(const std::vector<std::string>& args, std::string* err = nullptr) {
  const CommandResult r = RunRockfit(Join(args, {"--json"}));
  EXPECT_EQ(r.exit_code, 0) << r.err;
  if (err) *err = r.err;
  return nlohmann::json::parse(r.out);
}

nlohmann::json Metrics(const std::string& prefix, const Trial& t, const std::string& mounting, std::string* err = nullptr) {
  return RunJson(Join({"metrics", prefix, "--mounting=" + mounting}, BlockArgs(t)), err);
}

nlohmann::json Fit(const std::string& prefix, const Trial& t, const std::string& mounting) {
  return RunJson(Join({"fit", prefix, "--mounting=" + mounting}, BlockArgs(t)));
}

// The rotation the data show (block axes from the given mounting's), from the JSON angles [deg].
Eigen::Matrix3d EstimatedRotation(const nlohmann::json& mounting) {
  const Eigen::Vector3d angles_deg(mounting["angles_deg"][0].get<double>(), mounting["angles_deg"][1].get<double>(),
                                   mounting["angles_deg"][2].get<double>());
  const double angle = angles_deg.norm() / kDegPerRad;
  return angle == 0.0 ? Eigen::Matrix3d::Identity()
                      : Eigen::AngleAxisd(angle, angles_deg.normalized()).toRotationMatrix();
}

double AngleBetweenDeg(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b) {
  return Eigen::AngleAxisd(a * b.transpose()).angle() * kDegPerRad;
}

// A rotation by up to kMaxMisalignment_deg about a uniformly random axis, from raw engine output (portable).
Eigen::Matrix3d RandomMisalignment(std::mt19937_64& rng, Eigen::Vector3d* angles_deg) {
  const auto uniform = [&] { return static_cast<double>(rng() >> 11) * 0x1.0p-53; };
  const double z = 2.0 * uniform() - 1.0, phi = 2.0 * kPi * uniform();
  const Eigen::Vector3d axis(std::sqrt(1.0 - z * z) * std::cos(phi), std::sqrt(1.0 - z * z) * std::sin(phi), z);
  const double angle_deg = kMaxMisalignment_deg * uniform();
  *angles_deg = angle_deg * axis;
  return Eigen::AngleAxisd(angle_deg / kDegPerRad, axis).toRotationMatrix();
}

struct Reference {
  std::string prefix;
  nlohmann::json metrics, fit;
};

Reference Aligned(const ScratchDir& dir, const std::string& name, const Trial& t, const std::string& mounting,
                  bool fit = true) {
  Reference r;
  r.prefix = Synthesize(dir, name, t, mounting);
  r.metrics = Metrics(r.prefix, t, mounting);
  if (fit) r.fit = Fit(r.prefix, t, mounting);
  return r;
}

void ExpectOpmfClose(double opmf, double aligned, const std::string& what) {
  const double tolerance = aligned < kSmallOpmf ? kOpmfAbsolute : kOpmfRelative * aligned;
  EXPECT_NEAR(opmf, aligned, tolerance) << what;
}

// Every fitted parameter within the aligned fit's value ± 1.96·std_error; ε within 2 %. Returns the largest
// |Δ| / (1.96·std_error). A parameter the aligned fit itself flags as not identifiable has no interval to meet.
double ExpectFitLikeAligned(const nlohmann::json& fit, const nlohmann::json& aligned, const std::string& what) {
  double worst = 0.0;
  for (const char* name : {"t0", "alpha", "lambda", "lambda_lat", "lambda_lon"}) {
    const nlohmann::json& a = aligned["parameters"][name];
    if (a["fixed"].get<bool>() || a["std_error"].is_null()) continue;
    bool identifiable = true;
    for (const nlohmann::json& w : aligned["warnings"]) {
      if (w["kind"] == "not_identifiable" && w["parameter"] == name) identifiable = false;
    }
    if (!identifiable) continue;
    const double half_width = kIntervalZ * a["std_error"].get<double>();
    const double delta = fit["parameters"][name]["value"].get<double>() - a["value"].get<double>();
    EXPECT_LE(std::abs(delta), half_width) << what << ": " << name << " " << fit["parameters"][name]["value"]
                                           << " vs aligned " << a["value"] << " ± " << half_width;
    worst = std::max(worst, std::abs(delta) / half_width);
  }
  EXPECT_NEAR(fit["epsilon"].get<double>(), aligned["epsilon"].get<double>(),
              kEpsilonRelative * aligned["epsilon"].get<double>())
      << what;
  return worst;
}

// Blocks from slender to deep, both signs of λ_lat, tilts from 0.6 to 0.85 θ_c.
const Trial kTrials[] = {
    {0.035, 0.20, 1.5, 0.197, 2.185, -2.032, 0.197, 4101},  // the paper's Fig. 14 values
    {0.028, 0.21, 1.2, 0.150, 1.4, -3.2, 0.55, 4102},
    {0.065, 0.17, 1.6, 0.160, 0.7, 2.6, 1.15, 4103},
    {0.045, 0.20, 1.0, 0.170, 2.2, -1.9, 0.8, 4104},
};

TEST(CliMounting, AutoUndoesTwentyRandomMisalignmentsOfUpToFiveDegrees) {
  ROCKFIT_REQUIRE_OPTIMISED_BUILD();
  const ScratchDir dir("cli_mounting_sweep");
  std::mt19937_64 rng(20261125);
  constexpr int kPerTrial = 5;  // 4 blocks × 5 = 20 misalignments
  std::cout << "trial  truth x y z [deg]        estimate x y z [deg]        err [deg]  OPMF aligned/auto/identity"
               "        ε aligned/auto [rad/s]   max |Δp|/(1.96 se)\n";
  int index = 0;
  for (const Trial& t : kTrials) {
    const Reference aligned = Aligned(dir, fmt::format("aligned{}", t.seed), t, "x,y,z");
    const double aligned_opmf = aligned.metrics["opmf"].get<double>();
    for (int k = 0; k < kPerTrial; ++k, ++index) {
      Eigen::Vector3d truth_deg;
      const Eigen::Matrix3d R_small = RandomMisalignment(rng, &truth_deg);
      const std::string prefix = Synthesize(dir, fmt::format("turned{}", index), t, QuaternionText(R_small));
      const std::string what = fmt::format("trial {} (seed {}), sensor turned by ({:+.3f}, {:+.3f}, {:+.3f})°", index,
                                           t.seed, truth_deg.x(), truth_deg.y(), truth_deg.z());
      const nlohmann::json m = Metrics(prefix, t, "auto");
      ASSERT_EQ(m["mounting"]["status"], "ok") << what << "\n" << m["mounting"].dump(1);
      const double error_deg = AngleBetweenDeg(EstimatedRotation(m["mounting"]), R_small);
      EXPECT_LT(error_deg, kEstimateTolerance_deg) << what << "\n" << m["mounting"].dump(1);
      ExpectOpmfClose(m["opmf"].get<double>(), aligned_opmf, what);
      const double identity_opmf = Metrics(prefix, t, "identity")["opmf"].get<double>();
      // A whole fit for one of the five per block (the suite's time budget); all twenty are in io/README.md.
      if (k != 0) {
        std::cout << fmt::format("{:>5}  {:+.3f} {:+.3f} {:+.3f}   estimate error {:.3f}°, OPMF {:.4f}/{:.4f}/{:.4f}\n",
                                 index, truth_deg.x(), truth_deg.y(), truth_deg.z(), error_deg, aligned_opmf,
                                 m["opmf"].get<double>(), identity_opmf);
        continue;
      }
      const nlohmann::json fit = Fit(prefix, t, "auto");
      const double worst = ExpectFitLikeAligned(fit, aligned.fit, what);
      const Eigen::Vector3d est(m["mounting"]["angles_deg"][0].get<double>(), m["mounting"]["angles_deg"][1].get<double>(),
                                m["mounting"]["angles_deg"][2].get<double>());
      std::cout << fmt::format("{:>5}  {:+.3f} {:+.3f} {:+.3f}   {:+.3f} {:+.3f} {:+.3f}   {:.3f}      {:.4f}/{:.4f}/{:.4f}"
                               "     {:.5f}/{:.5f}          {:.2f}\n",
                               index, truth_deg.x(), truth_deg.y(), truth_deg.z(), est.x(), est.y(), est.z(), error_deg,
                               aligned_opmf, m["opmf"].get<double>(), identity_opmf,
                               aligned.fit["epsilon"].get<double>(), fit["epsilon"].get<double>(), worst);
    }
  }
}

TEST(CliMounting, AutoUndoesAnUpsideDownSensorTurnedByAFewDegrees) {
  ROCKFIT_REQUIRE_OPTIMISED_BUILD();
  const ScratchDir dir("cli_mounting_upside_down");
  const Trial& t = kTrials[0];
  const Eigen::Matrix3d upside_down = Eigen::Vector3d(1, -1, -1).asDiagonal();  // x,-y,-z
  const Eigen::Vector3d truth_deg(1.8, -2.4, 3.1);
  const Eigen::Matrix3d R_small = Eigen::AngleAxisd(truth_deg.norm() / kDegPerRad, truth_deg.normalized()).toRotationMatrix();
  const Reference aligned = Aligned(dir, "aligned", t, "x,-y,-z");
  const std::string prefix = Synthesize(dir, "turned", t, QuaternionText(R_small * upside_down));

  // Starting at the permutation the user knows: the small rotation is left.
  const nlohmann::json m = Metrics(prefix, t, "auto:x,-y,-z");
  ASSERT_EQ(m["mounting"]["status"], "ok") << m["mounting"].dump(1);
  EXPECT_EQ(m["mounting"]["given"], "x,-y,-z");
  EXPECT_LT(AngleBetweenDeg(EstimatedRotation(m["mounting"]), R_small), kEstimateTolerance_deg) << m["mounting"].dump(1);
  ExpectOpmfClose(m["opmf"].get<double>(), aligned.metrics["opmf"].get<double>(), "upside down");
  ExpectFitLikeAligned(Fit(prefix, t, "auto:x,-y,-z"), aligned.fit, "upside down");

  // Plain `auto` starts at identity, 180° away, and still finds the whole mounting.
  const nlohmann::json from_identity = Metrics(prefix, t, "auto");
  ASSERT_EQ(from_identity["mounting"]["status"], "ok");
  EXPECT_LT(AngleBetweenDeg(EstimatedRotation(from_identity["mounting"]), R_small * upside_down), kEstimateTolerance_deg)
      << from_identity["mounting"].dump(1);
  ExpectOpmfClose(from_identity["opmf"].get<double>(), aligned.metrics["opmf"].get<double>(), "upside down from identity");
}

TEST(CliMounting, PlanarTrialsFixTheMountingWhenTheyEndAtRestAndNameTheOpenAngleOtherwise) {
  ROCKFIT_REQUIRE_OPTIMISED_BUILD();
  const ScratchDir dir("cli_mounting_planar");
  Trial planar = kTrials[0];
  planar.lambda_lat = 0.0;  // no lateral motion after the facet impact
  planar.lambda_lon = 0.8;  // loses energy fast enough to come to rest 5.4 s after the release
  planar.rocking_s = 6.0;
  const Eigen::Vector3d truth_deg(-2.0, 1.5, 3.5);
  const Eigen::Matrix3d R_small = Eigen::AngleAxisd(truth_deg.norm() / kDegPerRad, truth_deg.normalized()).toRotationMatrix();
  const Reference aligned = Aligned(dir, "aligned", planar, "x,y,z", /*fit=*/false);
  const std::string prefix = Synthesize(dir, "turned", planar, QuaternionText(R_small));
  const nlohmann::json m = Metrics(prefix, planar, "auto");
  ASSERT_EQ(m["mounting"]["status"], "ok") << m["mounting"].dump(1);
  EXPECT_LT(AngleBetweenDeg(EstimatedRotation(m["mounting"]), R_small), kEstimateTolerance_deg) << m["mounting"].dump(1);
  ExpectOpmfClose(m["opmf"].get<double>(), aligned.metrics["opmf"].get<double>(), "planar");

  // Cut 1.2 s after the release, while the block still rocks: the turn about y cannot be told from α.
  Trial cut = planar;
  cut.rocking_s = 1.2;
  const std::string cut_prefix = Synthesize(dir, "cut", cut, QuaternionText(R_small));
  const nlohmann::json c = RunJson({"inspect", cut_prefix, "--mounting", "auto"});
  const nlohmann::json& check = c["mounting_check"];
  ASSERT_EQ(check["status"], "partial") << check.dump(1);
  EXPECT_EQ(check["determined"], nlohmann::json::array({true, false, true}));
  EXPECT_THAT(check["message"].get<std::string>(), HasSubstr("about block y"));
  EXPECT_THAT(c["warnings"].dump(), HasSubstr("does not end at rest"));
  EXPECT_NEAR(check["angles_deg"][0].get<double>(), truth_deg.x(), kEstimateTolerance_deg);
  EXPECT_NEAR(check["angles_deg"][2].get<double>(), truth_deg.z(), kEstimateTolerance_deg);
}

TEST(CliMounting, AWrongMountingGivenWithoutAutoIsWarnedAboutWithTheRightSize) {
  ROCKFIT_REQUIRE_OPTIMISED_BUILD();
  const ScratchDir dir("cli_mounting_warning");
  const Trial& t = kTrials[0];
  const Eigen::Vector3d truth_deg(0.4, -0.7, 3.0);  // mostly yaw, the turn that mixes φy into φx
  const Eigen::Matrix3d R_small = Eigen::AngleAxisd(truth_deg.norm() / kDegPerRad, truth_deg.normalized()).toRotationMatrix();
  const std::string prefix = Synthesize(dir, "turned", t, QuaternionText(R_small));
  const CommandResult r = RunRockfit(Join({"metrics", prefix, "--mounting", "x,y,z"}, BlockArgs(t)));
  EXPECT_EQ(r.exit_code, 0) << r.err;
  std::smatch match;
  ASSERT_TRUE(std::regex_search(r.err, match, std::regex("disagree with the mounting 'identity' by ([0-9.]+)°")))
      << r.err;
  EXPECT_NEAR(std::stod(match[1].str()), truth_deg.norm(), kEstimateTolerance_deg) << r.err;
  EXPECT_THAT(r.err, HasSubstr("--mounting auto"));

  // The aligned recording: no warning.
  const std::string aligned = Synthesize(dir, "aligned", t, "x,y,z");
  const CommandResult ok = RunRockfit(Join({"metrics", aligned}, BlockArgs(t)));
  EXPECT_EQ(ok.exit_code, 0);
  EXPECT_THAT(ok.err, ::testing::Not(HasSubstr("disagree")));
}

TEST(CliMounting, AReleaseOnACornerIsNotTakenForASensorTurnedAboutZ) {
  // `rockfit synth --release-roll 0.006` with the sensor on the block's axes: read as a fall about the edge, the roll
  // looked like the sensor turned by 2–3° about z (the warning, and `auto` turning the data by it). The estimate sees
  // the block fall rolling, keeps z at the given mounting and says why; x and y are still checked.
  ROCKFIT_REQUIRE_OPTIMISED_BUILD();
  const ScratchDir dir("cli_mounting_rolled");
  Trial rolled = kTrials[0];
  rolled.release_roll_rad = 0.006;
  const std::string prefix = Synthesize(dir, "rolled", rolled, "x,y,z");
  const CommandResult r = RunRockfit(Join({"metrics", prefix}, BlockArgs(rolled)));
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.err, ::testing::Not(HasSubstr("disagree"))) << r.err;
  const nlohmann::json c = RunJson({"inspect", prefix, "--mounting", "auto"});
  const nlohmann::json& check = c["mounting_check"];
  ASSERT_EQ(check["status"], "partial") << check.dump(1);
  EXPECT_EQ(check["determined"], nlohmann::json::array({true, true, false}));
  EXPECT_THAT(check["message"].get<std::string>(), HasSubstr("fell rolling"));
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(check["angles_deg"][i].get<double>(), 0.0, kEstimateTolerance_deg) << check.dump(1);
}

// The warnings of `kind` in a fit's JSON.
std::vector<std::string> WarningsOf(const nlohmann::json& fit, const std::string& kind) {
  std::vector<std::string> messages;
  for (const nlohmann::json& w : fit["warnings"]) {
    if (w["kind"] == kind) messages.push_back(w["message"].get<std::string>());
  }
  return messages;
}

TEST(CliMounting, ASensorTurnedAboutZOnACornerReleaseIsFoundByTheFit) {
  // The estimate cannot tell a turn about z from the roll of a release on a corner (the test above): the fit, which
  // models the roll, can. The same rolled release recorded with the sensor turned by 3° about block z: the fit warns
  // and gives the mounting that undoes the turn (within kEstimateTolerance_deg); fitted with that mounting, ε is
  // the aligned recording's and the warning is gone. The aligned recording is not warned about.
  ROCKFIT_REQUIRE_OPTIMISED_BUILD();
  const ScratchDir dir("cli_mounting_rolled_turned");
  Trial rolled = kTrials[0];
  rolled.release_roll_rad = 0.006;
  const Eigen::Matrix3d R_true = Eigen::AngleAxisd(3.0 / kDegPerRad, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const std::string aligned_prefix = Synthesize(dir, "aligned", rolled, "x,y,z");
  const std::string turned_prefix = Synthesize(dir, "turned", rolled, QuaternionText(R_true));

  const nlohmann::json aligned = Fit(aligned_prefix, rolled, "identity");
  EXPECT_TRUE(WarningsOf(aligned, "sensor_turned_about_z").empty()) << aligned["warnings"].dump(1);

  const nlohmann::json turned = Fit(turned_prefix, rolled, "identity");
  ASSERT_EQ(turned["mounting"]["determined"], nlohmann::json::array({true, true, false})) << turned["mounting"].dump(1);
  const std::vector<std::string> warned = WarningsOf(turned, "sensor_turned_about_z");
  ASSERT_EQ(warned.size(), 1u) << turned["warnings"].dump(1);
  std::smatch match;
  ASSERT_TRUE(std::regex_search(warned[0], match, std::regex("--mounting=([-0-9.e,]+)"))) << warned[0];
  const std::string advised = match[1].str();
  const Eigen::Quaterniond q_advised = [&] {
    double w, x, y, z;
    EXPECT_EQ(std::sscanf(advised.c_str(), "%lf,%lf,%lf,%lf", &w, &x, &y, &z), 4) << advised;
    return Eigen::Quaterniond(w, x, y, z).normalized();
  }();
  EXPECT_LT(q_advised.angularDistance(Eigen::Quaterniond(R_true)) * kDegPerRad, kEstimateTolerance_deg) << advised;

  const nlohmann::json refit = Fit(turned_prefix, rolled, advised);
  EXPECT_TRUE(WarningsOf(refit, "sensor_turned_about_z").empty()) << refit["warnings"].dump(1);
  EXPECT_NEAR(refit["epsilon"].get<double>(), aligned["epsilon"].get<double>(),
              kEpsilonRelative * aligned["epsilon"].get<double>());
  EXPECT_GT(turned["epsilon"].get<double>(), 2.0 * aligned["epsilon"].get<double>());
}

}  // namespace
}  // namespace rockfit::testing
