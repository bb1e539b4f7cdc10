#include "rockfit/fitting/release_tilt_check.hpp"

#include <cmath>
#include <cstddef>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "rockfit/fitting/fit_summary.hpp"
#include "rockfit/io/units.hpp"

namespace rockfit::fitting {
namespace {

constexpr std::size_t kBlockY = 1;  // index of the block's y axis in MountingCheck::determined

// The sentence's note on a turn before the fall ("" when the rest ends at the fall), in both units so that it can
// be read against the difference in mrad.
std::string TurnNote(double turn_before_fall_deg) {
  if (!(turn_before_fall_deg > 0.0)) return "";
  return fmt::format("the block turned by {:.2f}° ({:.1f} mrad) between the rest and the fall (lifted or pushed as "
                     "it was let go)",
                     turn_before_fall_deg, 1e3 * io::kRadPerDeg * turn_before_fall_deg);
}

}  // namespace

ReleaseTiltCheck CheckReleaseTilt(const io::MountingCheck& mounting, const Parameter& alpha,
                                  double alpha_std_error_rad) {
  ReleaseTiltCheck c;
  c.fitted_rad = alpha.value;
  c.fitted_std_error_rad = alpha_std_error_rad;
  c.rest_rad = mounting.release_tilt_rad;
  c.rest_std_error_rad = mounting.release_tilt_std_error_rad;
  c.turn_before_fall_deg = mounting.turn_before_fall_deg;
  if (!mounting.has_estimate()) {
    c.reason = mounting.status == io::MountingStatus::kNotChecked
                   ? "no tilt at rest: the recording was not checked for its mounting"
                   : "no tilt at rest: " + mounting.message;
    return c;
  }
  // Without rest after the rocking, a turn of the mounting about block y and the tilt at rest are one unknown
  // (before the release a turn about y looks like a different α): the tilt at rest is then read through the given
  // mounting, its σ is the mounting prior's (10°), and a comparison would test nothing.
  if (!mounting.determined[kBlockY]) {
    c.reason = "no tilt at rest independent of the mounting: " + mounting.message;
    return c;
  }
  if (!(std::isfinite(c.rest_rad) && std::isfinite(c.rest_std_error_rad) && c.rest_std_error_rad > 0.0)) {
    c.reason = "no tilt at rest: the mounting estimate gave none";
    return c;
  }
  if (alpha.fixed) {
    c.reason = fmt::format("α held at {:.5f} rad, tilt at rest {:.5f} ± {:.5f} rad (accelerometer)", c.fitted_rad,
                           c.rest_rad, c.rest_std_error_rad);
    return c;
  }
  if (!(std::isfinite(alpha_std_error_rad) && alpha_std_error_rad >= 0.0)) {
    c.reason = fmt::format("tilt at rest {:.5f} ± {:.5f} rad (accelerometer); the fitted α {:.5f} rad has no standard "
                           "error to compare with",
                           c.rest_rad, c.rest_std_error_rad, c.fitted_rad);
    return c;
  }
  c.available = true;
  c.difference_rad = c.fitted_rad - c.rest_rad;
  c.z = c.difference_rad / std::hypot(c.fitted_std_error_rad, c.rest_std_error_rad);
  c.consistent = std::abs(c.z) <= kReleaseTiltMaxZ;
  const std::string turn = TurnNote(c.turn_before_fall_deg);
  std::string verdict;
  if (c.consistent) {
    verdict = turn.empty() ? ", consistent" : ", consistent; " + turn;
  } else if (turn.empty()) {
    verdict = ": they disagree; check the block's dimensions (b1, b2, h) and the release (a push, a hand that "
              "follows), on which the fitted α rests";
  } else {
    verdict = ": they disagree, and " + turn + ": the fitted α is the tilt it fell from, not the one it was held "
              "at; if the turn does not account for the difference, check the block's dimensions (b1, b2, h)";
  }
  c.reason = fmt::format("fitted α {:.5f} ± {:.5f} rad, at rest {:.5f} ± {:.5f} rad (accelerometer): {:+.2f} mrad, "
                         "{:.1f} σ apart{}",
                         c.fitted_rad, c.fitted_std_error_rad, c.rest_rad, c.rest_std_error_rad, 1e3 * c.difference_rad,
                         std::abs(c.z), verdict);
  return c;
}

void AttachReleaseTiltCheck(const io::MountingCheck& mounting, FitSummary* summary) {
  const std::size_t k = static_cast<std::size_t>(ParameterId::kAlpha);
  summary->release_tilt = CheckReleaseTilt(mounting, summary->parameters[ParameterId::kAlpha], summary->std_error[k]);
  if (summary->release_tilt->available && !summary->release_tilt->consistent) {
    summary->warnings.push_back(
        {WarningKind::kReleaseTiltDisagrees, "alpha",
         "the fitted release tilt and the tilt at rest disagree: " + summary->release_tilt->reason});
  }
  if (mounting.turn_before_fall_deg > kTurnBeforeFallWarningDeg) {
    summary->warnings.push_back(
        {WarningKind::kTurnedBeforeFall, "",
         TurnNote(mounting.turn_before_fall_deg) + ": t0 and α are those of the fall from where it stopped, not of a "
                                                   "release from the rest it was held in"});
  }
}

std::string ReleaseTiltCheckJson(const ReleaseTiltCheck& c) {
  const auto number = [&c](double v) { return c.available ? nlohmann::json(v) : nlohmann::json(nullptr); };
  const auto finite = [](double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); };
  nlohmann::json j;
  j["available"] = c.available;
  j["rest_rad"] = finite(c.rest_rad);
  j["rest_std_error_rad"] = finite(c.rest_std_error_rad);
  j["fitted_rad"] = c.fitted_rad;
  j["fitted_std_error_rad"] = finite(c.fitted_std_error_rad);
  j["difference_rad"] = number(c.difference_rad);
  j["z"] = number(c.z);
  j["consistent"] = c.consistent;
  j["turn_before_fall_deg"] = finite(c.turn_before_fall_deg);
  j["reason"] = c.reason;
  return j.dump();
}

std::string ReleaseTiltCheckText(const ReleaseTiltCheck& c) { return c.reason; }

}  // namespace rockfit::fitting
