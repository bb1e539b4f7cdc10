#include "rockfit/app/fit_setup.hpp"

#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "rockfit/app/block_args.hpp"
#include "rockfit/app/json_values.hpp"
#include "rockfit/app/option_grammar.hpp"
#include "rockfit/app/recording_input.hpp"
#include "rockfit/core/errors.hpp"
#include "rockfit/fitting/simulator_model.hpp"

namespace rockfit::app {
namespace {

std::vector<std::string> SplitList(const std::vector<std::string>& items) {
  std::vector<std::string> out;
  for (const std::string& item : items) {
    std::size_t start = 0;
    while (start <= item.size()) {
      const std::size_t comma = item.find(',', start);
      const std::string name = item.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
      if (!name.empty()) out.push_back(name);
      if (comma == std::string::npos) break;
      start = comma + 1;
    }
  }
  return out;
}

// The number after '=' in `entry` (an option value NAME=VALUE); InvalidArgument naming the option otherwise.
double ParseEntryValue(const std::string& entry, std::size_t eq, const std::string& option) {
  double value = 0.0;
  try {
    std::size_t used = 0;
    value = std::stod(entry.substr(eq + 1), &used);
    if (used != entry.size() - eq - 1) throw std::invalid_argument("trailing characters");
  } catch (const std::exception&) {
    throw InvalidArgument(fmt::format("{} '{}': '{}' is not a number", option, entry, entry.substr(eq + 1)));
  }
  if (!std::isfinite(value)) throw InvalidArgument(fmt::format("{} '{}': the value must be finite", option, entry));
  return value;
}

void ApplyBound(const std::string& entry, const std::string& option, bool lower, fitting::ParameterSet* set) {
  const std::size_t eq = entry.find('=');
  if (eq == std::string::npos) {
    throw InvalidArgument(fmt::format("{} '{}': expected NAME=VALUE, e.g. {} lambda_lat=-2", option, entry, option));
  }
  const fitting::ParameterId id = fitting::ParseParameterName(entry.substr(0, eq));
  const double value = ParseEntryValue(entry, eq, option);
  (lower ? (*set)[id].lower : (*set)[id].upper) = value;
}


}  // namespace


std::vector<FixEntry> ParseFixEntries(const FitArgs& args) {
  std::vector<FixEntry> entries;
  for (const std::string& entry : SplitList(args.fix)) {
    const std::size_t eq = entry.find('=');
    FixEntry fix;
    fix.id = fitting::ParseParameterName(entry.substr(0, eq));
    if (eq != std::string::npos) fix.value = ParseEntryValue(entry, eq, "--fix");
    entries.push_back(fix);
  }
  return entries;
}

fitting::ReleaseRollMode ReleaseRollModeOf(const FitArgs& args) {
  fitting::ReleaseRollMode mode = fitting::ReleaseRollMode::kAuto;
  if (!fitting::FromString(args.release_roll_mode, &mode)) {
    throw InvalidArgument(fmt::format("--release-roll-mode '{}': expected off, auto or on", args.release_roll_mode));
  }
  if (args.fit_release_roll) mode = fitting::ReleaseRollMode::kOn;
  for (const std::string& name : SplitList(args.free)) {
    if (fitting::ParseParameterName(name) == fitting::ParameterId::kReleaseRoll) mode = fitting::ReleaseRollMode::kOn;
  }
  for (const FixEntry& fix : ParseFixEntries(args)) {
    if (fix.id == fitting::ParameterId::kReleaseRoll && fix.value) mode = fitting::ReleaseRollMode::kOff;
  }
  return mode;
}

fitting::ParameterSet MakeParameterSet(const FitArgs& args) {
  fitting::ParameterSet set = fitting::ParameterSet::Defaults(fitting::ParseBoundsSet(args.bounds));
  for (const std::string& name : SplitList(args.free)) set[fitting::ParseParameterName(name)].fixed = false;
  if (ReleaseRollModeOf(args) == fitting::ReleaseRollMode::kOn) set[fitting::ParameterId::kReleaseRoll].fixed = false;
  for (const FixEntry& fix : ParseFixEntries(args)) {
    fitting::Parameter& p = set[fix.id];
    if (fix.value) {
      p.value = *fix.value;
      p.fixed = true;
    } else {
      p.fixed = false;  // estimated from the data first, fixed afterwards (PrepareFit)
    }
  }
  for (const std::string& e : args.lower) ApplyBound(e, "--lower", true, &set);
  for (const std::string& e : args.upper) ApplyBound(e, "--upper", false, &set);
  for (const FixEntry& fix : ParseFixEntries(args)) {
    const fitting::Parameter& p = set[fix.id];
    if (fix.value && !(p.lower <= *fix.value && *fix.value <= p.upper)) {
      throw InvalidArgument(fmt::format("--fix {}={:g}: the value lies outside the bounds [{:g}, {:g}]; change them "
                                        "with --lower/--upper", fitting::Name(fix.id), *fix.value, p.lower, p.upper));
    }
  }
  return set;
}

PreparedFit PrepareFit(const io::Recording& recording, const core::Block& block, const FitArgs& args) {
  fitting::FitOptions options;
  options.method = fitting::ParseFitMethod(args.method);
  options.global.enabled = !args.no_global;
  if (args.max_evaluations < 0) throw InvalidArgument("--max-evaluations must be ≥ 0");
  if (args.max_evaluations > 0) options.nelder_mead.max_evaluations = args.max_evaluations;
  if (args.threads < 0) throw InvalidArgument("--threads must be ≥ 0");
  options.num_threads = args.threads;
  options.intervals.method = fitting::ParseIntervalMethod(args.intervals);
  options.intervals.model_error_widening = args.model_error_widening;
  options.intervals.t0_floor_samples = args.t0_floor_samples;
  options.gyro_scale = fitting::ParseGyroScaleMode(args.estimate_gyro_scale);
  options.Validate();

  fitting::ParameterSet set = MakeParameterSet(args);
  const fitting::MeasuredSignal signal{recording.t_s, recording.w_B, {}, {}};
  fitting::TrialProblemOptions problem_options;
  problem_options.t_end_s = args.t_end_s;
  problem_options.subtract_rest_bias = !args.keep_bias;
  problem_options.release_roll.mode = ReleaseRollModeOf(args);
  fitting::TrialProblem problem = fitting::PrepareTrialProblem(signal, block, set, problem_options);
  // --fix NAME without a value: held at the data estimate.
  bool fixed_at_estimate = false;
  for (const FixEntry& fix : ParseFixEntries(args)) {
    if (fix.value) continue;
    problem.start[fix.id].fixed = true;
    fixed_at_estimate = true;
  }
  if (fixed_at_estimate) {
    if (problem.start.FreeIds().empty()) throw InvalidArgument("--fix leaves no parameter free to fit");
    problem.objective = problem.objective.WithParameters(problem.start);
  }
  // The objective projects the gyro scale out as the fit does, so that what is evaluated after the fit (the
  // stored trajectory, plots) is the model as fitted.
  problem.objective = problem.objective.WithGyroScale(options.gyro_scale);
  std::string settings = FitSettingsText(block, args);
  return PreparedFit{std::move(problem.objective), std::move(problem.start), options, std::move(problem.guess),
                     settings, std::move(problem.notes), problem.release_roll};
}

std::string FitSettingsText(const core::Block& block, const FitArgs& args) {
  const fitting::ParameterSet set = MakeParameterSet(args);
  // v2: the gyro bias at rest is subtracted unless --keep-bias, and a detected window ends just before its impact.
  // v3: the window-end detector follows the integrated attitude and recognises landings with a small jump; the
  // values of fixed parameters are part of the settings.
  // v4: 68 % / 95 % intervals (--intervals); their profiles can move the fit to a lower (28).
  // v5: the 68 % intervals at the bulk noise level of the standard errors.
  // v6: the lateral rescan.
  // v7: the model-error statement is stored with each fit (the fitted values are those of v6).
  // v8: the 95 % intervals widened for model error by default (the fitted values are those of v7).
  // v9: clipped gyro samples censored in (28).
  // v10: on clipped recordings, the censored components the model satisfies count in no degree of freedom (the
  // intervals change; recordings without a rail do not); the projected gyro scale minimises (28) itself.
  // v11: the release roll fitted when the fall shows one (release_roll=auto, the default) and started from the data;
  // the model-error widening's default 1.1.
  // v12: the global stage's ridge scan at 21 values of t0 instead of 41 (fits move within 0.05 % of ε).
  std::string settings = fmt::format("rockfit-fit v12; method={}; intervals={}; bounds={}; t_end={}; max_evaluations={}; "
                                     "global={}; keep_bias={}; block=({:.17g},{:.17g},{:.17g},{:.17g})",
                                     fitting::ToString(fitting::ParseFitMethod(args.method)),
                                     fitting::ToString(fitting::ParseIntervalMethod(args.intervals)), args.bounds,
                                     args.t_end_s ? fmt::format("{:.17g}", *args.t_end_s) : "auto",
                                     args.max_evaluations, !args.no_global, args.keep_bias, block.b1(), block.b2(),
                                     block.h(), block.mass());
  // The reported parameters only: a fit that does not estimate the release roll keeps the settings of v9.
  for (fitting::ParameterId id : set.ReportedIds()) {
    const fitting::Parameter& p = set[id];
    settings += fmt::format("; {}:{}[{:.17g},{:.17g}]", fitting::Name(id), p.fixed ? "fixed" : "free", p.lower, p.upper);
    if (p.fixed) settings += fmt::format("={:.17g}", p.value);
  }
  for (const FixEntry& fix : ParseFixEntries(args)) {
    if (!fix.value) settings += fmt::format("; {}:fixed at the data estimate", fitting::Name(fix.id));
  }
  settings += fmt::format("; model_error_widening={:.17g}; t0_floor_samples={:.17g}", args.model_error_widening,
                          args.t0_floor_samples);
  // The automatic choice of the release roll depends on the recording: a fit made before it (β held at 0) is not
  // one made with it. (on: the parameter list above says release_roll:free; off: as before the choice.)
  if (ReleaseRollModeOf(args) == fitting::ReleaseRollMode::kAuto) settings += "; release_roll=auto";
  // Only when estimated, so that the settings (and hashes) of fits without it stay those of v8.
  const fitting::GyroScaleMode gyro_scale = fitting::ParseGyroScaleMode(args.estimate_gyro_scale);
  if (gyro_scale != fitting::GyroScaleMode::kOff) settings += fmt::format("; gyro_scale={}", fitting::ToString(gyro_scale));
  return settings;
}

fitting::CampaignTrial MakeCampaignTrial(const io::Manifest& manifest, const io::TrialSpec& spec, const FitArgs& fit_args,
                                         std::function<void(const io::Recording&)> on_loaded) {
  fitting::CampaignTrial trial;
  trial.id = TrialNameFrom(spec.id);
  trial.labels = {spec.block_id, spec.position, spec.notes};
  trial.settings = [&manifest, &spec, fit_args] {
    const core::Block block = manifest.FindBlock(spec.block_id).ToBlock();
    return FitSettingsText(block, fit_args) + "; mounting=" + (spec.mounting.empty() ? "identity" : spec.mounting);
  };
  trial.prepare = [&manifest, &spec, fit_args, on_loaded] {
    const core::Block block = manifest.FindBlock(spec.block_id).ToBlock();
    auto recording = std::make_shared<const io::Recording>(LoadManifestTrial(spec));
    if (on_loaded) on_loaded(*recording);
    PreparedFit prepared = PrepareFit(*recording, block, fit_args);
    return fitting::PreparedTrial{std::move(prepared.objective), std::move(prepared.start), prepared.options,
                                  std::move(recording), prepared.release_roll_choice};
  };
  return trial;
}

nlohmann::json FitResultJson(const std::string& trial, const fitting::FitSummary& s) {
  // The fit's own JSON (FitSummary::ToJson), narrowed to the keys `fit --json` documents (fitting/README.md,
  // "rockfit fit"): one JSON writer for the library, the command line and Python.
  static const char* const kKeys[] = {"trial", "parameters", "correlation", "uncertainty_method", "uncertainty",
                                      "lateral_motion", "model_error", "motion_before_release", "gyro_scale", "release_roll_choice", "release_tilt", "epsilon", "epsilon_initial", "t_end", "window", "simulations",
                                      "wall_s", "termination", "warnings"};
  static const char* const kParameterKeys[] = {"value",       "lower",       "upper",      "fixed",
                                               "std_error",   "interval_68", "interval_95", "determined"};
  const nlohmann::json full = nlohmann::json::parse(s.ToJson(trial));
  nlohmann::json out = nlohmann::json::object();
  for (const char* key : kKeys) {
    if (full.contains(key)) out[key] = full[key];
  }
  for (auto& [name, parameter] : out["parameters"].items()) {
    nlohmann::json narrowed = nlohmann::json::object();
    for (const char* key : kParameterKeys) narrowed[key] = parameter[key];
    parameter = std::move(narrowed);
  }
  return out;
}

std::string FitResultTable(const std::string& trial, const fitting::FitSummary& s) {
  std::string out = fmt::format("trial        {}\n", trial);
  out += fmt::format("{:<12} {:>12} {:>10} {:>23} {:>23} {:>10} {:>10} {:>10}  {:<6} {}\n", "parameter", "value",
                     "std_error", "68 % interval", "95 % interval", "determined", "lower", "upper", "unit", "");
  auto end = [](double v) { return std::isnan(v) ? std::string("open") : fmt::format("{:.6g}", v); };
  for (fitting::ParameterId id : s.parameters.ReportedIds()) {
    const fitting::Parameter& p = s.parameters[id];
    const std::size_t k = static_cast<std::size_t>(id);
    const double se = s.std_error[k];
    auto interval = [&](const fitting::Interval& i) {
      return p.fixed ? std::string("—") : fmt::format("[{}, {}]", end(i[0]), end(i[1]));
    };
    const auto& d = s.uncertainty.determined[k];
    out += fmt::format("{:<12} {:>12.6g} {:>10} {:>23} {:>23} {:>10} {:>10.6g} {:>10.6g}  {:<6} {}\n",
                       fitting::Name(id), p.value, std::isfinite(se) ? fmt::format("{:.3g}", se) : "—",
                       interval(s.uncertainty.interval_68[k]), interval(s.uncertainty.interval_95[k]),
                       d ? fitting::ToString(*d) : "—", p.lower, p.upper, fitting::Unit(id), p.fixed ? "fixed" : "");
  }
  out += fmt::format("ε (28)       {:.6g} rad/s (start {:.6g} rad/s), window ends at {:.4f} s\n", s.epsilon_rad_s,
                     s.epsilon_initial_rad_s, s.t_end_s);
  out += "window       " + fitting::WindowReportText(s.window) + "\n";
  out += "model error  " + fitting::ModelErrorText(s.model_error) + "\n";
  if (s.gyro_scale.mode != fitting::GyroScaleMode::kOff) out += "gyro scale  " + fitting::GyroScaleText(s.gyro_scale) + "\n";
  if (s.release_roll_choice) out += "release roll " + fitting::ReleaseRollChoiceText(*s.release_roll_choice) + "\n";
  if (s.release_tilt) out += "release tilt " + fitting::ReleaseTiltCheckText(*s.release_tilt) + "\n";
  out += fmt::format("effort       {} simulations in {:.2f} s; {}\n", s.simulations, s.wall_time_s, s.termination);
  out += fmt::format("intervals    {} ({} of the simulations, {:.2f} s)\n", s.uncertainty.description,
                     s.uncertainty.evaluations, s.uncertainty.wall_time_s);
  for (const std::string& statement : s.uncertainty.statements) out += "data fix     " + statement + "\n";
  for (const fitting::FitWarning& w : s.warnings) out += "warning      " + w.message + "\n";
  return out;
}

}  // namespace rockfit::app
