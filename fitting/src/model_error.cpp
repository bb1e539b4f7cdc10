#include "rockfit/fitting/model_error.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "rockfit/core/errors.hpp"

namespace rockfit::fitting {

void ModelErrorOptions::Validate() const {
  rest.Validate();
  if (!(dominance_share >= 0.0 && dominance_share < 1.0)) {
    throw InvalidArgument(fmt::format("model error: dominance_share must lie in [0, 1), got {}", dominance_share));
  }
}

ModelErrorStatement AssessModelError(const Objective& objective, double epsilon_rad_s, const ModelErrorOptions& options) {
  options.Validate();
  ModelErrorStatement s;
  const std::vector<bool>& excluded = objective.signal().excluded;
  s.clipped_samples = static_cast<std::size_t>(std::count(excluded.begin(), excluded.end(), true));
  if (!options.enabled || !std::isfinite(epsilon_rad_s) || !(epsilon_rad_s > 0.0)) return s;
  // The rest ends before the data estimate of the release (the objective's start value of t0, as for the gyro
  // bias), not before the fitted t0: a fit that model error drove far from the release would otherwise leave no rest.
  const RestNoise rest =
      MeasureRestNoise(objective.signal(), objective.parameters().value(ParameterId::kT0), options.rest);
  s.rest_duration_s = std::max(0.0, rest.duration_s);
  s.rest_samples = rest.samples;
  if (!rest.available || !std::isfinite(rest.epsilon_floor_rad_s)) return s;
  s.available = true;
  s.epsilon_rad_s = epsilon_rad_s;
  s.noise_floor_rad_s = rest.epsilon_floor_rad_s;
  const double floor_sq = s.noise_floor_rad_s * s.noise_floor_rad_s, epsilon_sq = epsilon_rad_s * epsilon_rad_s;
  s.ratio = epsilon_rad_s / s.noise_floor_rad_s;  // +inf for a noiseless rest
  s.noise_share = std::min(1.0, floor_sq / epsilon_sq);
  s.model_error_rad_s = std::sqrt(std::max(0.0, epsilon_sq - floor_sq));
  s.dominates = 1.0 - s.noise_share > options.dominance_share;
  return s;
}

std::string ModelErrorJson(const ModelErrorStatement& s) {
  auto number = [&](double v) { return s.available && std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(); };
  return nlohmann::json{{"available", s.available},
                        {"epsilon_rad_s", number(s.epsilon_rad_s)},
                        {"noise_floor_rad_s", number(s.noise_floor_rad_s)},
                        {"ratio", number(s.ratio)},
                        {"noise_share", number(s.noise_share)},
                        {"model_error_rad_s", number(s.model_error_rad_s)},
                        {"model_error_share", number(1.0 - s.noise_share)},
                        {"dominates", s.available ? nlohmann::json(s.dominates) : nlohmann::json()},
                        {"rest_duration_s", s.rest_duration_s},
                        {"rest_samples", s.rest_samples},
                        {"clipped_samples", s.clipped_samples}}
      .dump();
}

std::string ModelErrorText(const ModelErrorStatement& s) {
  if (!s.available) {
    return fmt::format("not measured: no rest of at least the required length before the release ({:.2f} s found)",
                       s.rest_duration_s);
  }
  const std::string clipped =
      s.clipped_samples > 0 ? fmt::format(" ({} clipped gyro samples)", s.clipped_samples) : std::string();
  return fmt::format("ε = {:.2f} × the noise floor {:.3g} rad/s (rest {:.2f} s): the noise explains {:.0f} % of ε², "
                     "model error {:.3g} rad/s{}{}",
                     s.ratio, s.noise_floor_rad_s, s.rest_duration_s, 100.0 * s.noise_share, s.model_error_rad_s,
                     s.dominates ? " dominates" : "", clipped);
}

}  // namespace rockfit::fitting
