#include "rockfit/fitting/fit_store.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <tuple>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "rockfit/core/errors.hpp"

namespace rockfit::fitting {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
// Parameters summarised per group (t0 is a time in each recording, not a property of the block).
const ParameterId kGroupParameters[] = {ParameterId::kAlpha, ParameterId::kLambda, ParameterId::kLambdaLat,
                                        ParameterId::kLambdaLon};

void WriteLabels(const io::hdf5::Group& g, const std::string& trial_id, const FitLabels& labels,
                 const std::string& status, const std::string& settings_hash) {
  g.SetInt("fit_schema_version", kFitSchemaVersion);
  g.SetString("trial", trial_id);
  g.SetString("status", status);
  g.SetString("block_id", labels.block_id);
  g.SetString("position", labels.position);
  g.SetDouble("b1_m", labels.b1_m);
  g.SetDouble("b2_m", labels.b2_m);
  g.SetDouble("h_m", labels.h_m);
  g.SetString("settings_hash", settings_hash);
}

double Mean(const std::vector<double>& v) {
  double s = 0.0;
  for (double x : v) s += x;
  return v.empty() ? kNaN : s / static_cast<double>(v.size());
}

double SampleStd(const std::vector<double>& v) {
  if (v.size() < 2) return kNaN;
  const double m = Mean(v);
  double s = 0.0;
  for (double x : v) s += (x - m) * (x - m);
  return std::sqrt(s / static_cast<double>(v.size() - 1));
}

}  // namespace

std::optional<double> StoredFit::Value(const std::string& name) const {
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (names[i] == name) return value[i];
  }
  return std::nullopt;
}

void WriteFitHdf5(const io::hdf5::Group& root, const std::string& trial_id, const FitLabels& labels,
                  const TrialFit& fit, const std::string& settings_json, const std::string& settings_hash) {
  const FitSummary& s = fit.summary;
  root.Remove("fits/" + trial_id);
  const io::hdf5::Group g = root.RequireGroup("fits").CreateGroup(trial_id);
  WriteLabels(g, trial_id, labels, "ok", settings_hash);
  g.SetString("message", "");
  g.SetString("method", ToString(s.method));
  g.SetString("termination", s.termination);
  g.SetInt("converged", s.converged ? 1 : 0);
  g.SetDouble("epsilon_rad_s", s.epsilon_rad_s);
  g.SetDouble("epsilon_initial_rad_s", s.epsilon_initial_rad_s);
  g.SetDouble("t_end_s", s.t_end_s);
  g.SetInt("simulations", s.simulations);
  g.SetDouble("wall_time_s", s.wall_time_s);
  g.SetDouble("simulations_per_second", s.simulations_per_second);
  g.SetString("model", s.model_description);
  g.SetString("settings", settings_json);
  g.SetString("summary", s.ToJson(trial_id));
  g.SetDouble("rest_bias_rad_s_x", fit.estimate.rest_bias_rad_s.x());
  g.SetDouble("rest_bias_rad_s_y", fit.estimate.rest_bias_rad_s.y());
  g.SetDouble("rest_bias_rad_s_z", fit.estimate.rest_bias_rad_s.z());
  g.SetString("description", "fit of (28) for one trial; see fitting/README.md, 'HDF5 layout'");

  const io::hdf5::Group p = g.CreateGroup("parameters");
  std::vector<std::string> names, units;
  std::vector<double> value, lower, upper, std_error, start;
  std::vector<std::int64_t> fixed, identifiable, at_bound;
  for (ParameterId id : kAllParameters) {
    const std::size_t k = static_cast<std::size_t>(id);
    const Parameter& q = s.parameters[id];
    names.push_back(Name(id));
    units.push_back(Unit(id));
    value.push_back(q.value);
    lower.push_back(q.lower);
    upper.push_back(q.upper);
    std_error.push_back(s.std_error[k]);
    start.push_back(s.start.value(id));
    fixed.push_back(q.fixed ? 1 : 0);
    identifiable.push_back(s.identifiable[k] ? 1 : 0);
    at_bound.push_back(s.at_bound[k] ? 1 : 0);
  }
  p.WriteStrings("name", names);
  p.WriteStrings("unit", units);
  p.WriteDoubles("value", value, "see unit");
  p.WriteDoubles("lower", lower, "see unit");
  p.WriteDoubles("upper", upper, "see unit");
  p.WriteDoubles("std_error", std_error, "see unit");
  p.WriteDoubles("start", start, "see unit");
  p.WriteInts("fixed", fixed, "1");
  p.WriteInts("identifiable", identifiable, "1");
  p.WriteInts("at_bound", at_bound, "1");
  p.SetString("columns", "name, unit, value, lower, upper, std_error, start, fixed, identifiable, at_bound");

  // The window, measured and simulated at the same times.
  std::vector<double> time;
  std::vector<Eigen::Vector3d> measured;
  for (double t : fit.trace.t_s) {
    time.push_back(t);
    measured.push_back(fit.signal.Interpolate(t));
  }
  g.WriteDoubles("time_s", time, "s");
  g.WriteVectors("w_measured_B_rad_s", measured, "rad/s");
  g.WriteVectors("w_simulated_B_rad_s", fit.trace.ok ? fit.trace.w_B : std::vector<Eigen::Vector3d>(time.size(), Eigen::Vector3d::Constant(kNaN)), "rad/s");

  const io::hdf5::Group impacts = g.CreateGroup("impacts");
  std::vector<double> impact_t;
  std::vector<std::string> impact_kind;
  for (const ModelEvent& e : fit.trace.events) {
    impact_t.push_back(e.t_s);
    impact_kind.push_back(e.kind);
  }
  impacts.WriteDoubles("time_s", impact_t, "s");
  impacts.WriteStrings("kind", impact_kind);
  g.WriteDoubles("measured_impacts_time_s", fit.estimate.impact_times_s, "s");

  const io::hdf5::Group stages = g.CreateGroup("stages");
  std::vector<std::string> stage_name, stage_termination;
  std::vector<double> stage_epsilon, stage_wall;
  std::vector<std::int64_t> stage_evaluations;
  for (const StageReport& r : s.stages) {
    stage_name.push_back(r.name);
    stage_termination.push_back(r.termination);
    stage_epsilon.push_back(r.epsilon_rad_s);
    stage_wall.push_back(r.wall_time_s);
    stage_evaluations.push_back(r.evaluations);
  }
  stages.WriteStrings("name", stage_name);
  stages.WriteDoubles("epsilon_rad_s", stage_epsilon, "rad/s");
  stages.WriteInts("evaluations", stage_evaluations, "1");
  stages.WriteDoubles("wall_time_s", stage_wall, "s");
  stages.WriteStrings("termination", stage_termination);

  const io::hdf5::Group warnings = g.CreateGroup("warnings");
  std::vector<std::string> w_kind, w_parameter, w_message;
  for (const FitWarning& w : s.warnings) {
    w_kind.push_back(w.kind);
    w_parameter.push_back(w.parameter);
    w_message.push_back(w.message);
  }
  warnings.WriteStrings("kind", w_kind);
  warnings.WriteStrings("parameter", w_parameter);
  warnings.WriteStrings("message", w_message);

  const io::hdf5::Group failures = g.CreateGroup("failures");
  std::vector<std::string> reasons;
  std::vector<std::int64_t> counts;
  for (const auto& [reason, count] : s.failures_by_reason) {
    reasons.push_back(reason);
    counts.push_back(count);
  }
  failures.WriteStrings("reason", reasons);
  failures.WriteInts("count", counts, "1");
}

void WriteFailedFitHdf5(const io::hdf5::Group& root, const std::string& trial_id, const FitLabels& labels,
                        const std::string& message, const std::string& settings_hash) {
  root.Remove("fits/" + trial_id);
  const io::hdf5::Group g = root.RequireGroup("fits").CreateGroup(trial_id);
  WriteLabels(g, trial_id, labels, "failed", settings_hash);
  g.SetString("message", message);
}

std::vector<std::string> ListFitsHdf5(const io::hdf5::Group& root) {
  if (!root.IsGroup("fits")) return {};
  return root.OpenGroup("fits").Children();
}

std::optional<std::string> StoredSettingsHash(const io::hdf5::Group& root, const std::string& trial_id) {
  const std::string path = "fits/" + trial_id;
  if (!root.IsGroup(path)) return std::nullopt;
  const io::hdf5::Group g = root.OpenGroup(path);
  if (g.GetString("status").value_or("") != "ok") return std::nullopt;
  return g.GetString("settings_hash");
}

StoredFit ReadFitHdf5(const io::hdf5::Group& root, const std::string& trial_id) {
  const std::vector<std::string> known = ListFitsHdf5(root);
  if (std::find(known.begin(), known.end(), trial_id) == known.end()) {
    std::string list;
    for (const std::string& k : known) list += (list.empty() ? "" : ", ") + k;
    throw BadInput(fmt::format("{}: no fit of trial '{}' under /fits (stored: {}); run `rockfit fit ... -o {}` first",
                               root.file_name(), trial_id, list.empty() ? "none" : list, root.file_name()));
  }
  const io::hdf5::Group g = root.OpenGroup("fits/" + trial_id);
  StoredFit f;
  f.trial_id = trial_id;
  f.status = g.GetString("status").value_or("");
  f.message = g.GetString("message").value_or("");
  f.settings_hash = g.GetString("settings_hash").value_or("");
  f.labels.block_id = g.GetString("block_id").value_or("");
  f.labels.position = g.GetString("position").value_or("");
  f.labels.b1_m = g.GetDouble("b1_m").value_or(kNaN);
  f.labels.b2_m = g.GetDouble("b2_m").value_or(kNaN);
  f.labels.h_m = g.GetDouble("h_m").value_or(kNaN);
  if (f.status != "ok") return f;
  f.summary_json = g.GetString("summary").value_or("");
  f.epsilon_rad_s = g.GetDouble("epsilon_rad_s").value_or(kNaN);
  f.epsilon_initial_rad_s = g.GetDouble("epsilon_initial_rad_s").value_or(kNaN);
  f.t_end_s = g.GetDouble("t_end_s").value_or(kNaN);
  const io::hdf5::Group p = g.OpenGroup("parameters");
  f.names = p.ReadStrings("name");
  f.value = p.ReadDoubles("value");
  f.lower = p.ReadDoubles("lower");
  f.upper = p.ReadDoubles("upper");
  f.std_error = p.ReadDoubles("std_error");
  for (std::int64_t v : p.ReadInts("fixed")) f.fixed.push_back(v != 0);
  f.time_s = g.ReadDoubles("time_s");
  f.w_measured_B = g.ReadVectors("w_measured_B_rad_s");
  f.w_simulated_B = g.ReadVectors("w_simulated_B_rad_s");
  f.impact_time_s = g.OpenGroup("impacts").ReadDoubles("time_s");
  f.impact_kind = g.OpenGroup("impacts").ReadStrings("kind");
  f.measured_impact_time_s = g.ReadDoubles("measured_impacts_time_s");
  f.warnings = g.OpenGroup("warnings").ReadStrings("message");
  const std::size_t n = f.names.size();
  if (f.value.size() != n || f.lower.size() != n || f.upper.size() != n || f.std_error.size() != n ||
      f.fixed.size() != n || f.w_measured_B.size() != f.time_s.size() || f.w_simulated_B.size() != f.time_s.size() ||
      f.impact_kind.size() != f.impact_time_s.size()) {
    throw BadInput(fmt::format("{}: /fits/{} is damaged (columns of different lengths); fit the trial again",
                               root.file_name(), trial_id));
  }
  return f;
}

void WriteFitTablesHdf5(const io::hdf5::Group& root) {
  root.Remove("fit_summary");
  const io::hdf5::Group s = root.CreateGroup("fit_summary");
  s.SetString("description",
              "fitted parameters per trial (trials) and per block and position (groups: n, mean and sample standard "
              "deviation (n - 1) of the free, identifiable values); NaN where a value is missing");
  std::vector<StoredFit> fits;
  for (const std::string& id : ListFitsHdf5(root)) fits.push_back(ReadFitHdf5(root, id));

  // Per trial.
  const io::hdf5::Group t = s.CreateGroup("trials");
  std::vector<std::string> trial_id, block_id, position, status, message;
  std::vector<double> b1, b2, h, epsilon;
  std::map<std::string, std::vector<double>> values, errors;
  std::map<std::string, std::vector<bool>> used;  // free and identifiable
  for (const StoredFit& f : fits) {
    trial_id.push_back(f.trial_id), block_id.push_back(f.labels.block_id), position.push_back(f.labels.position);
    status.push_back(f.status), message.push_back(f.message);
    b1.push_back(f.labels.b1_m), b2.push_back(f.labels.b2_m), h.push_back(f.labels.h_m);
    epsilon.push_back(f.status == "ok" ? f.epsilon_rad_s : kNaN);
    std::vector<std::string> not_identifiable;
    if (f.status == "ok") {
      const io::hdf5::Group p = root.OpenGroup("fits/" + f.trial_id + "/parameters");
      const std::vector<std::int64_t> ident = p.ReadInts("identifiable");
      for (std::size_t i = 0; i < f.names.size() && i < ident.size(); ++i) {
        values[f.names[i]].push_back(f.value[i]);
        errors[f.names[i]].push_back(f.std_error[i]);
        used[f.names[i]].push_back(!f.fixed[i] && ident[i] != 0);
      }
    } else {
      for (ParameterId id : kAllParameters) {
        values[Name(id)].push_back(kNaN);
        errors[Name(id)].push_back(kNaN);
        used[Name(id)].push_back(false);
      }
    }
  }
  t.WriteStrings("trial_id", trial_id);
  t.WriteStrings("block_id", block_id);
  t.WriteStrings("position", position);
  t.WriteDoubles("b1_m", b1, "m");
  t.WriteDoubles("b2_m", b2, "m");
  t.WriteDoubles("h_m", h, "m");
  t.WriteStrings("status", status);
  t.WriteStrings("message", message);
  t.WriteDoubles("epsilon_rad_s", epsilon, "rad/s");
  std::string columns = "trial_id, block_id, position, b1_m, b2_m, h_m, status, message, epsilon_rad_s";
  for (ParameterId id : kAllParameters) {
    const std::string name = Name(id);
    values[name].resize(fits.size(), kNaN);
    errors[name].resize(fits.size(), kNaN);
    t.WriteDoubles(name, values[name], Unit(id));
    t.WriteDoubles(name + "_std_error", errors[name], Unit(id));
    std::vector<std::int64_t> flags;
    for (bool u : used[name]) flags.push_back(u ? 1 : 0);
    flags.resize(fits.size(), 0);
    t.WriteInts(name + "_fitted", flags, "1");
    columns += fmt::format(", {0}, {0}_std_error, {0}_fitted", name);
  }
  t.SetString("columns", columns);

  // Per block and position.
  struct Key {
    std::string block, position;
    bool operator<(const Key& o) const { return std::tie(block, position) < std::tie(o.block, o.position); }
  };
  std::map<Key, std::vector<std::size_t>> groups;
  for (std::size_t i = 0; i < fits.size(); ++i) groups[{block_id[i], position[i]}].push_back(i);
  const io::hdf5::Group gr = s.CreateGroup("groups");
  std::vector<std::string> g_block, g_position;
  std::vector<double> g_b1, g_b2, g_h;
  std::vector<std::int64_t> n_trials, n_ok;
  std::map<std::string, std::vector<double>> mean, stdev;
  std::map<std::string, std::vector<std::int64_t>> count;
  for (const auto& [key, rows] : groups) {
    g_block.push_back(key.block), g_position.push_back(key.position);
    g_b1.push_back(b1[rows.front()]), g_b2.push_back(b2[rows.front()]), g_h.push_back(h[rows.front()]);
    n_trials.push_back(static_cast<std::int64_t>(rows.size()));
    std::vector<double> eps;
    for (std::size_t r : rows) {
      if (status[r] == "ok") eps.push_back(epsilon[r]);
    }
    n_ok.push_back(static_cast<std::int64_t>(eps.size()));
    mean["epsilon_rad_s"].push_back(Mean(eps));
    stdev["epsilon_rad_s"].push_back(SampleStd(eps));
    for (ParameterId id : kGroupParameters) {
      const std::string name = Name(id);
      std::vector<double> v;
      for (std::size_t r : rows) {
        if (used[name].size() > r && used[name][r]) v.push_back(values[name][r]);
      }
      count[name].push_back(static_cast<std::int64_t>(v.size()));
      mean[name].push_back(Mean(v));
      stdev[name].push_back(SampleStd(v));
    }
  }
  gr.WriteStrings("block_id", g_block);
  gr.WriteStrings("position", g_position);
  gr.WriteDoubles("b1_m", g_b1, "m");
  gr.WriteDoubles("b2_m", g_b2, "m");
  gr.WriteDoubles("h_m", g_h, "m");
  gr.WriteInts("n_trials", n_trials, "1");
  gr.WriteInts("n_ok", n_ok, "1");
  gr.WriteDoubles("epsilon_rad_s_mean", mean["epsilon_rad_s"], "rad/s");
  gr.WriteDoubles("epsilon_rad_s_std", stdev["epsilon_rad_s"], "rad/s");
  std::string group_columns = "block_id, position, b1_m, b2_m, h_m, n_trials, n_ok, epsilon_rad_s_mean, epsilon_rad_s_std";
  for (ParameterId id : kGroupParameters) {
    const std::string name = Name(id);
    gr.WriteInts("n_" + name, count[name], "1");
    gr.WriteDoubles(name + "_mean", mean[name], Unit(id));
    gr.WriteDoubles(name + "_std", stdev[name], Unit(id));
    group_columns += fmt::format(", n_{0}, {0}_mean, {0}_std", name);
  }
  gr.SetString("columns", group_columns);
}

}  // namespace rockfit::fitting
