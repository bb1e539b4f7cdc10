// Intervals that hold under model error (fitting/README.md, "Intervals under model error").
//
// The profile and sandwich intervals (uncertainty.hpp) describe the scatter that the residuals' noise makes,
// with its correlation in time (the long-run variance over IntervalOptions::noise_correlation_window_s). A
// recording that the model cannot reproduce biases the fitted parameters beyond that scatter, and by more the
// larger the part of ε the noise does not explain. The 95 % half-widths h (each side) are therefore widened to
//
//   h' = √( (f·h)² + floor² ),   f = √( 1 + c²·max(0, r² − 1) ),   r = ε / ε_noise,
//
// ε_noise the noise floor at rest (model_error.hpp), c = IntervalOptions::model_error_widening: the variance of
// the parameter gains a model-error term proportional to the model error's share of ε² over the noise's,
// ε_model² / ε_noise² = r² − 1 (f = 1 where the noise explains ε, f ≈ c·r where model error dominates). The
// floor is for t0 only, IntervalOptions::t0_floor_samples sample periods: t0 is fixed by the time of the first
// impact, which soft contact, a clock off by some ppm, timing jitter or a dropped sample move by a fraction of
// a sample without raising ε. The widened interval is clipped to the parameter's bounds; the fitted values do
// not change.
#pragma once

#include <array>

namespace rockfit::fitting {

using Interval = std::array<double, 2>;  // as in uncertainty.hpp: [lower, upper], NaN for an open end

// f above; 1 for a ratio that is not finite or not above 1, or a coefficient of 0.
double ModelErrorWideningFactor(double epsilon_over_noise_floor, double coefficient);

// √((factor·half_width)² + floor²): one side of an interval widened.
double WidenedHalfWidth(double half_width, double factor, double floor);

// `interval` about `value` widened side by side (an open end stays open), clipped to [lower, upper].
Interval WidenInterval(const Interval& interval, double value, double factor, double floor, double lower, double upper);

}  // namespace rockfit::fitting
