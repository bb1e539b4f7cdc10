#include "rockfit/io/avrf.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include <fmt/format.h>

#include "rockfit/core/errors.hpp"
#include "rockfit/core/impact_maps.hpp"
#include "rockfit/io/peak_finding.hpp"

namespace rockfit::io {

const char* ToString(UpliftFormula formula) {
  switch (formula) {
    case UpliftFormula::kComUplift: return "com";
    case UpliftFormula::kPaperPrinted: return "paper";
  }
  return "unknown";
}

bool FromString(std::string_view text, UpliftFormula* formula) {
  for (UpliftFormula f : {UpliftFormula::kComUplift, UpliftFormula::kPaperPrinted}) {
    if (text == ToString(f)) {
      *formula = f;
      return true;
    }
  }
  return false;
}

const char* ToString(AvrfStatus status) {
  switch (status) {
    case AvrfStatus::kOk: return "ok";
    case AvrfStatus::kNoImpact: return "no_impact";
    case AvrfStatus::kTooFewPeaks: return "too_few_peaks";
    case AvrfStatus::kInvalidUplift: return "invalid_uplift";
    case AvrfStatus::kNoBlock: return "no_block";
  }
  return "unknown";
}

void AvrfOptions::Validate() const {
  if (max_peaks < 2) throw InvalidArgument("AVRF max_peaks must be at least 2 (one ratio)");
  if (min_peaks < 2) throw InvalidArgument("AVRF min_peaks must be at least 2 (one ratio)");
  if (min_peaks > max_peaks) throw InvalidArgument("AVRF min_peaks must not exceed max_peaks");
  if (!std::isfinite(min_peak_prominence_rad) || min_peak_prominence_rad < 0.0) {
    throw InvalidArgument("AVRF min_peak_prominence_rad must be a finite number ≥ 0 [rad]");
  }
}

double Uplift(const core::Block& block, double phi_rad, UpliftFormula formula) {
  const double b1 = block.b1(), h = block.h();
  switch (formula) {
    case UpliftFormula::kComUplift: return b1 * std::sin(phi_rad) - h * (1.0 - std::cos(phi_rad));
    case UpliftFormula::kPaperPrinted: return h * std::sin(phi_rad) - b1 * (1.0 - std::cos(phi_rad));  // Sect. 3.2
  }
  return 0.0;
}

namespace {

double Median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  return n % 2 == 1 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

}  // namespace

AvrfResult ComputeAvrf(const std::vector<double>& t_s, const DriftCorrection& correction, const core::Block& block,
                       const AvrfOptions& options) {
  options.Validate();
  if (t_s.size() != correction.euler_corrected_zyx.size()) {
    throw InvalidArgument("ComputeAvrf: time and corrected angles differ in length");
  }
  AvrfResult result;
  if (correction.impacts_y.empty()) {
    result.status = AvrfStatus::kNoImpact;
    result.message = "no impact was detected, so there are no peak inclinations after the first impact";
    return result;
  }
  const double first_impact_s = correction.impacts_y.front().t_s;
  const std::size_t start = static_cast<std::size_t>(
      std::upper_bound(t_s.begin(), t_s.end(), first_impact_s) - t_s.begin());
  std::vector<double> abs_phi_y;
  abs_phi_y.reserve(t_s.size() - start);
  for (std::size_t i = start; i < t_s.size(); ++i) abs_phi_y.push_back(std::abs(correction.euler_corrected_zyx[i][1]));

  PeakOptions peak_options;
  peak_options.min_prominence = options.min_peak_prominence_rad;
  const std::vector<Peak> peaks = FindPeaks(abs_phi_y, peak_options);

  // One peak per stretch between consecutive impacts: the highest (a second one is noise or ringing).
  struct Candidate {
    std::size_t stretch;
    std::size_t index;  // in abs_phi_y
  };
  std::vector<Candidate> chosen;
  for (const Peak& peak : peaks) {
    const double t = t_s[start + peak.index];
    const auto stretch = static_cast<std::size_t>(
        std::upper_bound(correction.impacts_y.begin(), correction.impacts_y.end(), t,
                         [](double time, const Anchor& a) { return time < a.t_s; }) -
        correction.impacts_y.begin());
    // The correction is interpolated only between impacts: a peak after the last one is not used.
    if (stretch >= correction.impacts_y.size()) break;
    if (!chosen.empty() && chosen.back().stretch == stretch) {
      if (abs_phi_y[peak.index] > abs_phi_y[chosen.back().index]) chosen.back().index = peak.index;
      continue;
    }
    if (chosen.size() == options.max_peaks) break;
    chosen.push_back({stretch, peak.index});
  }

  const double dt = t_s.size() > 1 ? (t_s.back() - t_s.front()) / static_cast<double>(t_s.size() - 1) : 0.0;
  for (const Candidate& c : chosen) {
    const RefinedPeak refined = options.refine_peaks ? RefinePeakParabolic(abs_phi_y, c.index)
                                                     : RefinedPeak{0.0, abs_phi_y[c.index]};
    result.peak_times_s.push_back(t_s[start + c.index] + refined.offset_samples * dt);
    result.peak_angles_rad.push_back(refined.value);
    result.uplifts_m.push_back(Uplift(block, refined.value, options.uplift));
  }
  result.peaks_used = chosen.size();

  for (std::size_t i = 0; i < result.uplifts_m.size(); ++i) {
    if (!(result.uplifts_m[i] > 0.0)) {
      result.status = AvrfStatus::kInvalidUplift;
      result.message = fmt::format(
          "the uplift u = {:.4g} m at peak {} (|φ_y| = {:.4g} rad, t = {:.3f} s) is not positive with the '{}' "
          "formula: the inclination is beyond what the block geometry (b1 = {} m, h = {} m) allows; check the "
          "block and the angle units",
          result.uplifts_m[i], i + 1, result.peak_angles_rad[i], result.peak_times_s[i], ToString(options.uplift),
          block.b1(), block.h());
      return result;
    }
  }
  for (std::size_t i = 0; i + 1 < result.uplifts_m.size(); ++i) {
    result.ratios.push_back(std::sqrt(result.uplifts_m[i + 1] / result.uplifts_m[i]));  // r_i = √(u_(i+1)/u_i)
  }
  if (result.peaks_used < options.min_peaks) {
    result.status = AvrfStatus::kTooFewPeaks;
    result.message = fmt::format(
        "only {} peak inclination(s) of |φ_y| after the first impact (at least {} needed for the AVRF); the "
        "rocking may be too short or the peaks below {} rad",
        result.peaks_used, options.min_peaks, options.min_peak_prominence_rad);
    return result;
  }
  result.status = AvrfStatus::kOk;
  result.avrf = Median(result.ratios);
  // λ of (6) with b = b1, θ = Θ_yy (the inverse of (6)); defined for every finite r ≠ −1, and r > 0 here.
  result.lambda_equivalent = core::LambdaFromAvrf(core::PlanarBlockAboutY(block), result.avrf);
  return result;
}

}  // namespace rockfit::io
