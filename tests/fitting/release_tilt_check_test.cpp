// The check of the fitted α against the tilt at rest (release_tilt_check.hpp): z from its definition, the verdict at
// kReleaseTiltMaxZ, the warning only on a disagreement, and no comparison without both tilts and both errors.
#include "rockfit/fitting/release_tilt_check.hpp"

#include <cmath>
#include <limits>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "rockfit/fitting/fit_summary.hpp"

namespace rockfit::fitting {
namespace {

io::MountingCheck RestTilt(double alpha_rad, double std_error_rad) {
  io::MountingCheck m;
  m.status = io::MountingStatus::kOk;
  m.determined = {true, true, true};
  m.release_tilt_rad = alpha_rad;
  m.release_tilt_std_error_rad = std_error_rad;
  return m;
}

FitSummary FittedAlpha(double alpha_rad, double std_error_rad) {
  FitSummary s;
  s.parameters[ParameterId::kAlpha].value = alpha_rad;
  s.parameters[ParameterId::kAlpha].fixed = false;
  s.std_error.fill(std::numeric_limits<double>::quiet_NaN());
  s.std_error[static_cast<std::size_t>(ParameterId::kAlpha)] = std_error_rad;
  return s;
}

// A fit of α = fitted_alpha_rad ± 0.3 mrad checked against a rest at 0.2 ± 0.4 mrad from which the block turned by
// turn_deg before its fall.
FitSummary CheckedWithTurn(double turn_deg, double fitted_alpha_rad) {
  io::MountingCheck lifted = RestTilt(0.2, 0.0004);
  lifted.turn_before_fall_deg = turn_deg;
  FitSummary s = FittedAlpha(fitted_alpha_rad, 0.0003);
  AttachReleaseTiltCheck(lifted, &s);
  return s;
}

TEST(ReleaseTiltCheck, AgreeingTiltsGiveZFromTheCombinedErrorAndNoWarning) {
  FitSummary s = FittedAlpha(0.2006, 0.0003);
  AttachReleaseTiltCheck(RestTilt(0.2, 0.0004), &s);
  ASSERT_TRUE(s.release_tilt.has_value());
  const ReleaseTiltCheck& c = *s.release_tilt;
  EXPECT_TRUE(c.available);
  EXPECT_NEAR(c.difference_rad, 0.0006, 1e-15);
  EXPECT_NEAR(c.z, 0.0006 / 0.0005, 1e-9);  // √(0.3² + 0.4²) = 0.5 mrad
  EXPECT_TRUE(c.consistent);
  EXPECT_FALSE(s.HasWarning(WarningKind::kReleaseTiltDisagrees));
  EXPECT_NE(c.reason.find("1.2 σ apart, consistent"), std::string::npos) << c.reason;
}

TEST(ReleaseTiltCheck, TiltsFourSigmaApartDisagreeAndWarnAboutTheDimensions) {
  // Just inside and just beyond 4 σ (σ = 0.5 mrad): 1.99 mrad agrees, 2.01 mrad does not.
  FitSummary inside = FittedAlpha(0.2 - 0.00199, 0.0003);
  AttachReleaseTiltCheck(RestTilt(0.2, 0.0004), &inside);
  EXPECT_TRUE(inside.release_tilt->consistent);
  FitSummary beyond = FittedAlpha(0.2 - 0.00201, 0.0003);
  AttachReleaseTiltCheck(RestTilt(0.2, 0.0004), &beyond);
  EXPECT_FALSE(beyond.release_tilt->consistent);
  EXPECT_LT(beyond.release_tilt->z, -kReleaseTiltMaxZ);
  ASSERT_TRUE(beyond.HasWarning(WarningKind::kReleaseTiltDisagrees, "alpha"));
  EXPECT_NE(beyond.warnings.back().message.find("dimensions"), std::string::npos) << beyond.warnings.back().message;
  const nlohmann::json j = nlohmann::json::parse(ReleaseTiltCheckJson(*beyond.release_tilt));
  EXPECT_EQ(j["consistent"], false);
  EXPECT_NEAR(j["z"].get<double>(), -4.02, 1e-9);
}

TEST(ReleaseTiltCheck, ATurnBeforeTheFallIsNamedInDegreesAndMradAndExplainsADisagreement) {
  // Lifted by 0.8° (13.96 mrad) as it was let go: the fit's α is the top of the lift, 14 mrad above the rest.
  const FitSummary apart = CheckedWithTurn(0.8, 0.214);
  EXPECT_FALSE(apart.release_tilt->consistent);
  EXPECT_DOUBLE_EQ(apart.release_tilt->turn_before_fall_deg, 0.8);
  const std::string& why = apart.release_tilt->reason;
  EXPECT_NE(why.find("+14.00 mrad"), std::string::npos) << why;
  EXPECT_NE(why.find("turned by 0.80° (14.0 mrad) between the rest and the fall"), std::string::npos) << why;
  EXPECT_NE(why.find("the fitted α is the tilt it fell from"), std::string::npos) << why;
  ASSERT_TRUE(apart.HasWarning(WarningKind::kReleaseTiltDisagrees, "alpha"));
  EXPECT_NE(apart.warnings.back().message.find("turned by 0.80°"), std::string::npos);
  EXPECT_EQ(nlohmann::json::parse(ReleaseTiltCheckJson(*apart.release_tilt))["turn_before_fall_deg"], 0.8);
  ASSERT_TRUE(apart.HasWarning(WarningKind::kTurnedBeforeFall));

  // A lift too small to move α beyond the errors: consistent, and the turn is still said.
  const FitSummary close = CheckedWithTurn(0.05, 0.2006);
  EXPECT_TRUE(close.release_tilt->consistent);
  EXPECT_NE(close.release_tilt->reason.find("consistent; the block turned by 0.05° (0.9 mrad)"), std::string::npos)
      << close.release_tilt->reason;
  EXPECT_FALSE(close.HasWarning(WarningKind::kTurnedBeforeFall)) << "0.05° is below kTurnBeforeFallWarningDeg";

  // No turn (the rest ends at the fall) or none known: nothing is said about it, and the JSON says which.
  const FitSummary held = CheckedWithTurn(0.0, 0.2006);
  EXPECT_EQ(held.release_tilt->reason.find("turned"), std::string::npos) << held.release_tilt->reason;
  EXPECT_EQ(nlohmann::json::parse(ReleaseTiltCheckJson(*held.release_tilt))["turn_before_fall_deg"], 0.0);
  FitSummary unknown = FittedAlpha(0.2006, 0.0003);
  AttachReleaseTiltCheck(RestTilt(0.2, 0.0004), &unknown);
  EXPECT_TRUE(nlohmann::json::parse(ReleaseTiltCheckJson(*unknown.release_tilt))["turn_before_fall_deg"].is_null());
  EXPECT_TRUE(std::isnan(ReleaseTiltCheck{}.turn_before_fall_deg)) << "a check made otherwise does not claim a turn of 0";
  EXPECT_FALSE(held.HasWarning(WarningKind::kTurnedBeforeFall));
  EXPECT_FALSE(unknown.HasWarning(WarningKind::kTurnedBeforeFall));
}

TEST(ReleaseTiltCheck, ATurnBeforeTheFallIsWarnedAboutEvenWhereTheTiltsAgreeOrCannotBeCompared) {
  // The turn is seen by the gyro, not inferred from the fit: it is a warning whether or not the two tilts agree,
  // and also where the recording gives no tilt at rest independent of the mounting (no rest after the rocking).
  const FitSummary agree = CheckedWithTurn(0.64, 0.2006);
  EXPECT_TRUE(agree.release_tilt->consistent);
  EXPECT_FALSE(agree.HasWarning(WarningKind::kReleaseTiltDisagrees));
  ASSERT_TRUE(agree.HasWarning(WarningKind::kTurnedBeforeFall));
  EXPECT_NE(agree.warnings.back().message.find("turned by 0.64° (11.2 mrad)"), std::string::npos)
      << agree.warnings.back().message;
  EXPECT_NE(agree.warnings.back().message.find("t0 and α are those of the fall from where it stopped"),
            std::string::npos);

  io::MountingCheck partial = RestTilt(0.2, 0.0004);
  partial.turn_before_fall_deg = 0.64;
  partial.status = io::MountingStatus::kPartial;
  partial.determined = {true, false, false};
  FitSummary uncompared = FittedAlpha(0.2006, 0.0003);
  AttachReleaseTiltCheck(partial, &uncompared);
  EXPECT_FALSE(uncompared.release_tilt->available);
  EXPECT_TRUE(uncompared.HasWarning(WarningKind::kTurnedBeforeFall));
}

TEST(ReleaseTiltCheck, NoComparisonWithoutARestTiltAFixedMountingTurnAFreeAlphaOrItsError) {
  io::MountingCheck none;
  none.status = io::MountingStatus::kNoRest;
  none.message = "no rest of 0.2 s before the release";
  FitSummary s = FittedAlpha(0.2, 0.0003);
  AttachReleaseTiltCheck(none, &s);
  EXPECT_FALSE(s.release_tilt->available);
  EXPECT_TRUE(s.release_tilt->consistent);
  EXPECT_NE(s.release_tilt->reason.find("no rest of 0.2 s"), std::string::npos) << s.release_tilt->reason;
  const nlohmann::json j = nlohmann::json::parse(ReleaseTiltCheckJson(*s.release_tilt));
  EXPECT_TRUE(j["z"].is_null());
  EXPECT_TRUE(j["rest_rad"].is_null());

  FitSummary fixed = FittedAlpha(0.2, 0.0003);
  fixed.parameters[ParameterId::kAlpha].fixed = true;
  AttachReleaseTiltCheck(RestTilt(0.19, 0.0004), &fixed);
  EXPECT_FALSE(fixed.release_tilt->available);
  EXPECT_FALSE(fixed.HasWarning(WarningKind::kReleaseTiltDisagrees));

  // The mounting's turn about y not fixed (no rest after the rocking): the tilt at rest is the given mounting's,
  // with the prior's σ, and is not compared even where it has numbers.
  io::MountingCheck partial = RestTilt(0.19, 0.1745);
  partial.status = io::MountingStatus::kPartial;
  partial.determined = {true, false, true};
  partial.message = "the data do not fix the rotation about block y (kept at the given mounting)";
  FitSummary unfixed = FittedAlpha(0.2, 0.0003);
  AttachReleaseTiltCheck(partial, &unfixed);
  EXPECT_FALSE(unfixed.release_tilt->available);
  EXPECT_NE(unfixed.release_tilt->reason.find("independent of the mounting: the data do not fix the rotation about "
                                              "block y"),
            std::string::npos)
      << unfixed.release_tilt->reason;
  const nlohmann::json u = nlohmann::json::parse(ReleaseTiltCheckJson(*unfixed.release_tilt));
  EXPECT_TRUE(u["z"].is_null());
  EXPECT_EQ(u["rest_rad"], 0.19);

  FitSummary no_error = FittedAlpha(0.25, std::numeric_limits<double>::quiet_NaN());
  AttachReleaseTiltCheck(RestTilt(0.2, 0.0004), &no_error);
  EXPECT_FALSE(no_error.release_tilt->available);
  EXPECT_FALSE(no_error.HasWarning(WarningKind::kReleaseTiltDisagrees));
}

}  // namespace
}  // namespace rockfit::fitting
