#include "rockfit/fitting/fit_store.hpp"

#include <algorithm>
#include <cmath>

#include "rockfit/core/errors.hpp"
#include "rockfit/io/content_hash.hpp"

namespace rockfit::fitting {
namespace {

constexpr const char* kPerRow = "per row: see the unit dataset";
constexpr const char* kPerRowOpen = "per row: see the unit dataset; NaN: open";

// The columns of the parameter table as written (one row per reported parameter, ParameterSet::ReportedIds).
struct ParameterColumns {
  std::vector<std::string> names, units, determined;
  std::vector<double> value, lower, upper, std_error, start, lo68, hi68, lo95, hi95;
  std::vector<std::int64_t> fixed;
};

ParameterColumns CollectParameterColumns(const FitSummary& s) {
  ParameterColumns c;
  for (ParameterId id : s.parameters.ReportedIds()) {
    const Parameter& p = s.parameters[id];
    const std::size_t k = static_cast<std::size_t>(id);
    c.names.push_back(Name(id));
    c.units.push_back(Unit(id));
    c.value.push_back(p.value);
    c.lower.push_back(p.lower);
    c.upper.push_back(p.upper);
    c.fixed.push_back(p.fixed ? 1 : 0);
    c.std_error.push_back(s.std_error[k]);
    c.start.push_back(s.start.value(id));
    c.lo68.push_back(s.uncertainty.interval_68[k][0]);
    c.hi68.push_back(s.uncertainty.interval_68[k][1]);
    c.lo95.push_back(s.uncertainty.interval_95[k][0]);
    c.hi95.push_back(s.uncertainty.interval_95[k][1]);
    c.determined.push_back(s.uncertainty.determined[k] ? ToString(*s.uncertainty.determined[k]) : "fixed");
  }
  return c;
}

// The correlation matrix of the reported parameters, row-major (their number)², NaN where undefined.
std::vector<double> CorrelationRowMajor(const FitSummary& s) {
  const std::vector<ParameterId> ids = s.parameters.ReportedIds();
  const std::size_t n = ids.size();
  std::vector<double> correlation(n * n, std::nan(""));
  if (s.uncertainty.correlation.rows() != static_cast<Eigen::Index>(kNumParameters)) return correlation;
  for (std::size_t a = 0; a < n; ++a) {
    for (std::size_t b = 0; b < n; ++b) {
      correlation[a * n + b] =
          s.uncertainty.correlation(static_cast<Eigen::Index>(ids[a]), static_cast<Eigen::Index>(ids[b]));
    }
  }
  return correlation;
}

void WriteParameterTable(const io::hdf5::Group& fit, const FitSummary& s) {
  const ParameterColumns c = CollectParameterColumns(s);
  const io::hdf5::Group table = fit.CreateGroup("parameters");
  table.WriteStrings("name", c.names);
  table.WriteStrings("unit", c.units);
  table.WriteDoubles("value", c.value, kPerRow);
  table.WriteDoubles("lower", c.lower, kPerRow);
  table.WriteDoubles("upper", c.upper, kPerRow);
  table.WriteInts("fixed", c.fixed, "1");
  table.WriteDoubles("std_error", c.std_error, kPerRow);
  table.WriteDoubles("start", c.start, kPerRow);
  table.WriteDoubles("interval_68_lower", c.lo68, kPerRowOpen);
  table.WriteDoubles("interval_68_upper", c.hi68, kPerRowOpen);
  table.WriteDoubles("interval_95_lower", c.lo95, kPerRowOpen);
  table.WriteDoubles("interval_95_upper", c.hi95, kPerRowOpen);
  table.WriteStrings("determined", c.determined);
  const std::size_t reported = s.parameters.ReportedIds().size();
  table.WriteMatrix("correlation", CorrelationRowMajor(s), reported, reported, "1");
}

// The model-error statement (model_error.hpp): NaN numbers and dominates = -1 when it was not measured.
void WriteModelErrorAttributes(const io::hdf5::Group& g, const ModelErrorStatement& m) {
  const double nan = std::nan("");
  g.SetDouble("noise_floor_rad_s", m.available ? m.noise_floor_rad_s : nan);
  g.SetDouble("model_error_rad_s", m.available ? m.model_error_rad_s : nan);
  g.SetDouble("noise_share", m.available ? m.noise_share : nan);
  g.SetInt("model_error_dominates", m.available ? (m.dominates ? 1 : 0) : -1);
  g.SetDouble("rest_duration_s", m.rest_duration_s);
  g.SetInt("clipped_samples", static_cast<std::int64_t>(m.clipped_samples));
}

// The recorded motion before the fitted t0 (motion_before_release.hpp): NaN numbers and moving = -1 when it was not
// measured.
void WriteMotionBeforeReleaseAttributes(const io::hdf5::Group& g, const MotionBeforeRelease& m) {
  const double nan = std::nan("");
  g.SetDouble("motion_before_release_lookback_s", m.available ? m.lookback_s : nan);
  g.SetDouble("motion_before_release_turn_deg", m.available ? m.turn_deg : nan);
  g.SetDouble("motion_before_release_rate_rad_s", m.available ? m.rate_at_release_rad_s : nan);
  g.SetInt("moving_at_release", m.available ? (m.moving ? 1 : 0) : -1);
}

// The gyro scale estimated in the fit (gyro_scale_estimate.hpp), only when one was: the dataset gyro_scale
// (s_x, s_y, s_z) with the attribute mode and, per axis, the 95 % interval (NaN where the axis was not estimated)
// and whether the data determine it (0/1).
void WriteGyroScale(const io::hdf5::Group& g, const GyroScaleEstimate& e) {
  if (e.mode == GyroScaleMode::kOff) return;
  const double nan = std::nan("");
  g.WriteDoubles("gyro_scale", {e.value[0], e.value[1], e.value[2]}, "1");
  g.SetString("mode", ToString(e.mode), "gyro_scale");
  std::vector<double> lower, upper;
  for (const Interval& i : e.interval_95) {
    lower.push_back(e.available ? i[0] : nan);
    upper.push_back(e.available ? i[1] : nan);
  }
  g.WriteDoubles("gyro_scale_interval_95_lower", lower, "1");
  g.WriteDoubles("gyro_scale_interval_95_upper", upper, "1");
  g.WriteInts("gyro_scale_determined",
              {e.determined[0] ? 1 : 0, e.determined[1] ? 1 : 0, e.determined[2] ? 1 : 0}, "1");
}

// Whether the release roll was fitted and why (release_roll_choice.hpp), only when the problem was prepared from the
// recording: release_roll_mode (off/auto/on), release_roll_fitted (0/1), the roll seen in the fall, its noise and the
// start (NaN where not measured or not fitted), release_roll_choice (the sentence).
void WriteReleaseRollChoice(const io::hdf5::Group& g, const std::optional<ReleaseRollChoice>& choice) {
  if (!choice) return;
  const double nan = std::nan("");
  const ReleaseRollChoice& c = *choice;
  g.SetString("release_roll_mode", ToString(c.mode));
  g.SetInt("release_roll_fitted", c.fitted ? 1 : 0);
  g.SetDouble("release_roll_seen_rad", c.judged ? c.roll_seen_rad : nan);
  g.SetDouble("release_roll_noise_rad", c.judged ? c.roll_noise_rad : nan);
  g.SetDouble("release_roll_start_rad", c.fitted ? c.start_rad : nan);
  g.SetString("release_roll_choice", c.reason);
}

// The fitted α against the tilt at rest (release_tilt_check.hpp), only when the fit was made from a recording:
// release_tilt_rest_rad, release_tilt_rest_std_error_rad (NaN where the recording gave none), release_tilt_z (NaN
// where not compared), release_tilt_consistent (1, 0; −1 where not compared), release_tilt_check (the sentence).
void WriteReleaseTiltCheck(const io::hdf5::Group& g, const std::optional<ReleaseTiltCheck>& check) {
  if (!check) return;
  const double nan = std::nan("");
  const ReleaseTiltCheck& c = *check;
  g.SetDouble("release_tilt_rest_rad", std::isfinite(c.rest_rad) ? c.rest_rad : nan);
  g.SetDouble("release_tilt_rest_std_error_rad", std::isfinite(c.rest_std_error_rad) ? c.rest_std_error_rad : nan);
  g.SetDouble("release_tilt_z", c.available ? c.z : nan);
  g.SetInt("release_tilt_consistent", c.available ? (c.consistent ? 1 : 0) : -1);
  g.SetString("release_tilt_check", c.reason);
}

void WriteFitAttributes(const io::hdf5::Group& g, const std::string& settings, const FitSummary& s) {
  g.SetDouble("epsilon_rad_s", s.epsilon_rad_s);
  g.SetDouble("epsilon_initial_rad_s", s.epsilon_initial_rad_s);
  g.SetDouble("t_end_s", s.t_end_s);
  g.SetDouble("window_first_t_end_s", s.window.first_t_end_s);
  g.SetInt("window_extensions", s.window.extensions);
  g.SetString("window_end_reason", s.window.reason);
  g.SetInt("simulations", s.simulations);
  g.SetDouble("wall_s", s.wall_time_s);
  g.SetString("termination", s.termination);
  g.SetString("termination_type", ToString(s.termination_type));
  g.SetString("method", ToString(s.method));
  g.SetString("uncertainty_method", ToString(s.uncertainty.method));
  g.SetString("uncertainty", s.uncertainty.description);
  g.SetDouble("noise_correlation_factor", s.uncertainty.correlation_factor);
  g.SetDouble("noise_inflation_68", s.uncertainty.bulk_inflation);
  g.SetInt("feasible", s.feasible ? 1 : 0);
  WriteModelErrorAttributes(g, s.model_error);
  WriteMotionBeforeReleaseAttributes(g, s.motion_before_release);
  WriteGyroScale(g, s.gyro_scale);
  WriteReleaseRollChoice(g, s.release_roll_choice);
  WriteReleaseTiltCheck(g, s.release_tilt);
  g.SetString("settings", settings);
  g.SetString("settings_hash", SettingsHash(settings));
  g.SetString("model", s.model_description);
  std::vector<std::string> warnings;
  for (const FitWarning& w : s.warnings) warnings.push_back(std::string(ToString(w.kind)) + ": " + w.message);
  g.WriteStrings("warnings", warnings);
  g.WriteStrings("summary", {s.FullReport()});
}

// The simulated ω at the measured times of the window (the nodes of (28)) and the model's impact log, in
// recording time.
void WriteFittedTrajectory(const io::hdf5::Group& g, const Objective& given, const FitSummary& s) {
  ErrorNodes nodes;
  ModelOutput output;
  // The model as fitted: scaled by the gyro scale when the fit estimated one, on the fit's window (extended or not).
  const Objective on_window = given.t_end_s() == s.t_end_s ? given : given.WithWindowEnd(s.t_end_s);
  const Objective objective =
      on_window.options().gyro_scale == s.gyro_scale.mode ? on_window : on_window.WithGyroScale(s.gyro_scale.mode);
  objective.EvaluateDetailed(s.parameters, &nodes, &output);
  g.WriteDoubles("time_s", nodes.t_s, "s");
  g.WriteVectors("w_B_measured", nodes.w_m_B, "rad/s");
  if (output.ok() && output.w_B.size() == nodes.size()) g.WriteVectors("w_B_simulated", output.w_B, "rad/s");
  std::vector<double> impact_t_s;
  std::vector<std::string> impact_kind;
  const double t0_s = s.parameters.value(ParameterId::kT0);
  for (const ModelEvent& e : output.events) {
    impact_t_s.push_back(t0_s + e.t_s);
    impact_kind.push_back(core::ToString(e.kind));
  }
  const io::hdf5::Group impacts = g.CreateGroup("impacts");
  impacts.WriteDoubles("t_s", impact_t_s, "s");
  impacts.WriteStrings("kind", impact_kind);
}

// A column of /fits/<trial>/parameters, or `rows` copies of `missing` when the file predates it.
template <class T>
std::vector<T> OptionalColumn(const io::hdf5::Group& fit, const std::string& name, std::size_t rows, const T& missing);
template <>
std::vector<double> OptionalColumn(const io::hdf5::Group& fit, const std::string& name, std::size_t rows,
                                   const double& missing) {
  return fit.IsDataset("parameters/" + name) ? fit.ReadDoubles("parameters/" + name)
                                             : std::vector<double>(rows, missing);
}
template <>
std::vector<std::string> OptionalColumn(const io::hdf5::Group& fit, const std::string& name, std::size_t rows,
                                        const std::string& missing) {
  return fit.IsDataset("parameters/" + name) ? fit.ReadStrings("parameters/" + name)
                                             : std::vector<std::string>(rows, missing);
}

template <class T>
void RequireColumnLength(const io::hdf5::Group& fit, const std::string& column, const std::vector<T>& values,
                         std::size_t rows) {
  if (values.size() == rows) return;
  throw BadInput(fit.file_name() + ": " + fit.path() + "/parameters has " + std::to_string(rows) + " names but " +
                 std::to_string(values.size()) + " " + (column == "value" ? "values" : column + " entries") +
                 "; write the fit again with rockfit fit -o");
}

// ---------------------------------------------------------------------------------------- /summary/fits

// The per-trial table before writing: one entry per /fits/<trial>, the parameters by name.
struct PerTrialColumns {
  std::vector<std::string> trials, blocks, positions, mounting;
  std::map<std::string, std::vector<double>> value, lo68, hi68, lo95, hi95;
  std::map<std::string, std::vector<std::string>> determined;
  std::vector<double> epsilon_rad_s, wall_s, mounting_x_deg, mounting_y_deg, mounting_z_deg;
  std::vector<double> noise_floor_rad_s, model_error_rad_s, noise_share, release_tilt_z;
  std::vector<std::int64_t> simulations, model_error_dominates, release_roll_fitted, release_tilt_consistent;
};

void AppendParameters(const StoredParameters& stored, PerTrialColumns* c) {
  for (const char* name : kSummaryParameters) {
    const std::size_t row = stored.Row(name);
    const bool found = row < stored.size();
    c->value[name].push_back(found ? stored.value[row] : std::nan(""));
    c->lo68[name].push_back(found ? stored.interval_68_lower[row] : std::nan(""));
    c->hi68[name].push_back(found ? stored.interval_68_upper[row] : std::nan(""));
    c->lo95[name].push_back(found ? stored.interval_95_lower[row] : std::nan(""));
    c->hi95[name].push_back(found ? stored.interval_95_upper[row] : std::nan(""));
    c->determined[name].push_back(found ? stored.determined[row] : "");
  }
}

void AppendTrial(const std::string& id, const io::hdf5::Group& g, PerTrialColumns* c) {
  const StoredFitLabels labels = ReadFitLabels(g);
  c->trials.push_back(id);
  c->blocks.push_back(labels.block);
  c->positions.push_back(labels.position);
  AppendParameters(ReadFitParameters(g), c);
  c->epsilon_rad_s.push_back(g.GetDouble("epsilon_rad_s").value_or(std::nan("")));
  c->wall_s.push_back(g.GetDouble("wall_s").value_or(std::nan("")));
  c->simulations.push_back(labels.simulations);
  c->noise_floor_rad_s.push_back(labels.noise_floor_rad_s);
  c->model_error_rad_s.push_back(labels.model_error_rad_s);
  c->noise_share.push_back(labels.noise_share);
  c->model_error_dominates.push_back(labels.model_error_dominates);
  c->release_roll_fitted.push_back(g.GetInt("release_roll_fitted").value_or(-1));
  c->release_tilt_z.push_back(labels.release_tilt_z);
  c->release_tilt_consistent.push_back(labels.release_tilt_consistent);
  c->mounting.push_back(labels.mounting);
  const std::vector<double> angles =
      g.Exists("mounting_angles_deg") ? g.ReadDoubles("mounting_angles_deg") : std::vector<double>{};
  c->mounting_x_deg.push_back(angles.size() == 3 ? angles[0] : std::nan(""));
  c->mounting_y_deg.push_back(angles.size() == 3 ? angles[1] : std::nan(""));
  c->mounting_z_deg.push_back(angles.size() == 3 ? angles[2] : std::nan(""));
}

PerTrialColumns ReadPerTrialColumns(const io::hdf5::Group& root) {
  PerTrialColumns c;
  const io::hdf5::Group fits = root.OpenGroup("fits");
  for (const std::string& id : fits.Children()) AppendTrial(id, fits.OpenGroup(id), &c);
  return c;
}

void WritePerTrialTable(const io::hdf5::Group& root, PerTrialColumns& c) {
  const io::hdf5::Group t = root.CreateGroup("summary/fits/per_trial");
  t.WriteStrings("trial", c.trials);
  t.WriteStrings("block", c.blocks);
  t.WriteStrings("position", c.positions);
  for (const char* name : kSummaryParameters) {
    const std::string unit = Unit(ParseParameterName(name));
    const std::string n = name;
    t.WriteDoubles(n, c.value[name], unit);
    t.WriteDoubles(n + "_interval_68_lower", c.lo68[name], unit + "; NaN: open");
    t.WriteDoubles(n + "_interval_68_upper", c.hi68[name], unit + "; NaN: open");
    t.WriteDoubles(n + "_interval_95_lower", c.lo95[name], unit + "; NaN: open");
    t.WriteDoubles(n + "_interval_95_upper", c.hi95[name], unit + "; NaN: open");
    t.WriteStrings(n + "_determined", c.determined[name]);
  }
  t.WriteDoubles("epsilon_rad_s", c.epsilon_rad_s, "rad/s");
  t.WriteDoubles("wall_s", c.wall_s, "s");
  t.WriteInts("simulations", c.simulations, "1");
  t.WriteDoubles("noise_floor_rad_s", c.noise_floor_rad_s, "rad/s; NaN: not measured");
  t.WriteDoubles("model_error_rad_s", c.model_error_rad_s, "rad/s; NaN: not measured");
  t.WriteDoubles("noise_share", c.noise_share, "1; NaN: not measured");
  t.WriteInts("model_error_dominates", c.model_error_dominates, "1; -1: not measured");
  t.WriteInts("release_roll_fitted", c.release_roll_fitted, "1; -1: not recorded");
  t.WriteDoubles("release_tilt_z", c.release_tilt_z, "1; NaN: not compared");
  t.WriteInts("release_tilt_consistent", c.release_tilt_consistent, "1; -1: not compared");
  t.WriteStrings("mounting", c.mounting);
  t.WriteDoubles("mounting_angle_x_deg", c.mounting_x_deg, "deg");
  t.WriteDoubles("mounting_angle_y_deg", c.mounting_y_deg, "deg");
  t.WriteDoubles("mounting_angle_z_deg", c.mounting_z_deg, "deg");
}

// Mean, spread and pooled estimate of every parameter over the trials `members` of one group.
GroupSummary SummariseGroup(const std::string& block, const std::string& position,
                            const std::vector<std::size_t>& members, PerTrialColumns& c) {
  GroupSummary g{block, position, static_cast<std::int64_t>(members.size()), {}, {}, {}};
  for (const char* name : kSummaryParameters) {
    const std::vector<double>& x = c.value[name];
    double sum = 0.0;
    for (std::size_t i : members) sum += x[i];
    const double mean = sum / static_cast<double>(members.size());
    double ss = 0.0;
    for (std::size_t i : members) ss += (x[i] - mean) * (x[i] - mean);
    g.mean[name] = mean;
    g.std_dev[name] = members.size() > 1 ? std::sqrt(ss / static_cast<double>(members.size() - 1)) : std::nan("");
    std::vector<TrialEstimate> estimates;
    for (std::size_t i : members) {
      estimates.push_back({x[i], {c.lo95[name][i], c.hi95[name][i]}, c.determined[name][i] == "yes"});
    }
    g.pooled[name] = PoolTrials(estimates);
  }
  return g;
}

std::vector<GroupSummary> SummariseGroups(PerTrialColumns& c) {
  std::map<std::pair<std::string, std::string>, std::vector<std::size_t>> members;
  for (std::size_t i = 0; i < c.trials.size(); ++i) members[{c.blocks[i], c.positions[i]}].push_back(i);
  std::vector<GroupSummary> groups;
  for (const auto& [key, rows] : members) groups.push_back(SummariseGroup(key.first, key.second, rows, c));
  return groups;
}

void WriteGroupParameterColumns(const io::hdf5::Group& g, const std::vector<GroupSummary>& groups, const char* name) {
  const std::string unit = Unit(ParseParameterName(name));
  const std::string n = name;
  std::vector<double> mean, std_dev, pooled, lo, hi, chi2, p;
  std::vector<std::int64_t> n_pooled;
  for (const GroupSummary& r : groups) {
    mean.push_back(r.mean.at(name));
    std_dev.push_back(r.std_dev.at(name));
    const PooledEstimate& e = r.pooled.at(name);
    pooled.push_back(e.n_pooled > 0 ? e.pooled : std::nan(""));
    lo.push_back(e.interval_95[0]);
    hi.push_back(e.interval_95[1]);
    chi2.push_back(e.chi2_per_dof);
    p.push_back(e.consistency_p);
    n_pooled.push_back(e.n_pooled);
  }
  g.WriteDoubles(n + "_mean", mean, unit);
  g.WriteDoubles(n + "_std", std_dev, unit + "; the spread between trials");
  g.WriteDoubles(n + "_pooled", pooled, unit + "; inverse-variance weighted over the determined trials");
  g.WriteDoubles(n + "_pooled_95_lower", lo, unit);
  g.WriteDoubles(n + "_pooled_95_upper", hi, unit);
  g.WriteInts(n + "_n_pooled", n_pooled, "1");
  g.WriteDoubles(n + "_chi2_per_dof", chi2, "1");
  g.WriteDoubles(n + "_consistency_p", p, "1; below 0.05 the trials disagree beyond their intervals");
}

void WritePerGroupTable(const io::hdf5::Group& root, const std::vector<GroupSummary>& groups) {
  const io::hdf5::Group g = root.CreateGroup("summary/fits/per_group");
  std::vector<std::string> block, position;
  std::vector<std::int64_t> count;
  for (const GroupSummary& r : groups) {
    block.push_back(r.block);
    position.push_back(r.position);
    count.push_back(r.n);
  }
  g.WriteStrings("block", block);
  g.WriteStrings("position", position);
  g.WriteInts("n", count, "1");
  for (const char* name : kSummaryParameters) WriteGroupParameterColumns(g, groups, name);
}

constexpr const char* kPerGroup = "summary/fits/per_group";

// The columns of the per-group table, each at least as long as the table; a column the file lacks (tables written
// by hand, or by an older rockfit) reads as NaN (doubles) or 0 (counts).
class GroupColumns {
 public:
  GroupColumns(const io::hdf5::Group& table, std::size_t rows) : table_(table), rows_(rows) {}
  std::vector<double> Doubles(const std::string& name) const {
    return table_.IsDataset(name) ? Checked(name, table_.ReadDoubles(name)) : std::vector<double>(rows_, std::nan(""));
  }
  std::vector<std::int64_t> Ints(const std::string& name) const {
    return table_.IsDataset(name) ? Checked(name, table_.ReadInts(name)) : std::vector<std::int64_t>(rows_, 0);
  }
  // BadInput (from the io layer) when the file lacks it.
  std::vector<std::int64_t> RequiredInts(const std::string& name) const { return Checked(name, table_.ReadInts(name)); }

 private:
  template <class T>
  std::vector<T> Checked(const std::string& name, std::vector<T> values) const {
    if (values.size() < rows_) {
      throw BadInput(table_.file_name() + ": /" + kPerGroup + "/" + name +
                     " is shorter than the group table; run rockfit batch again");
    }
    return values;
  }
  const io::hdf5::Group& table_;
  std::size_t rows_;
};

void ReadGroupParameter(const GroupColumns& columns, const char* name, std::vector<GroupSummary>* groups) {
  const std::string n = name;
  const std::vector<double> mean = columns.Doubles(n + "_mean"), spread = columns.Doubles(n + "_std");
  const std::vector<double> pooled = columns.Doubles(n + "_pooled");
  const std::vector<double> lo = columns.Doubles(n + "_pooled_95_lower"), hi = columns.Doubles(n + "_pooled_95_upper");
  const std::vector<double> chi2 = columns.Doubles(n + "_chi2_per_dof"), p = columns.Doubles(n + "_consistency_p");
  const std::vector<std::int64_t> n_pooled = columns.Ints(n + "_n_pooled");
  for (std::size_t k = 0; k < groups->size(); ++k) {
    GroupSummary& g = (*groups)[k];
    g.mean[name] = mean[k];
    g.std_dev[name] = spread[k];
    PooledEstimate& e = g.pooled[name];
    e.n_trials = static_cast<int>(g.n);
    e.n_pooled = static_cast<int>(n_pooled[k]);
    e.pooled = pooled[k];
    e.interval_95 = {lo[k], hi[k]};
    e.spread = spread[k];
    e.chi2_per_dof = chi2[k];
    e.consistency_p = p[k];
  }
}

}  // namespace

std::string SettingsHash(const std::string& settings) { return io::HashHex(io::Fnv1a64(settings)); }

void WriteFitGroup(const io::hdf5::Group& root, const std::string& trial, const io::TrialLabels& labels,
                   const Objective& objective, const std::string& settings, const FitSummary& summary) {
  const io::hdf5::Group g = root.CreateGroup("fits/" + trial);
  g.SetString("block", labels.block_id);
  g.SetString("position", labels.position);
  WriteParameterTable(g, summary);
  WriteFitAttributes(g, settings, summary);
  WriteFittedTrajectory(g, objective, summary);
}

std::size_t StoredParameters::Row(const std::string& parameter) const {
  return static_cast<std::size_t>(std::find(name.begin(), name.end(), parameter) - name.begin());
}

StoredParameters ReadFitParameters(const io::hdf5::Group& fit) {
  StoredParameters s;
  s.name = fit.ReadStrings("parameters/name");
  s.value = fit.ReadDoubles("parameters/value");
  const std::size_t rows = s.name.size();
  RequireColumnLength(fit, "value", s.value, rows);
  const double nan = std::nan("");
  s.unit = OptionalColumn<std::string>(fit, "unit", rows, "");
  s.lower = OptionalColumn(fit, "lower", rows, nan);
  s.upper = OptionalColumn(fit, "upper", rows, nan);
  s.interval_68_lower = OptionalColumn(fit, "interval_68_lower", rows, nan);
  s.interval_68_upper = OptionalColumn(fit, "interval_68_upper", rows, nan);
  s.interval_95_lower = OptionalColumn(fit, "interval_95_lower", rows, nan);
  s.interval_95_upper = OptionalColumn(fit, "interval_95_upper", rows, nan);
  s.determined = OptionalColumn<std::string>(fit, "determined", rows, "");
  s.has_intervals = fit.IsDataset("parameters/interval_95_lower");
  if (fit.IsDataset("parameters/fixed")) {
    const std::vector<std::int64_t> fixed = fit.ReadInts("parameters/fixed");
    RequireColumnLength(fit, "fixed", fixed, rows);
    s.fixed.assign(fixed.begin(), fixed.end());
  } else {
    s.fixed.assign(rows, false);
  }
  for (const auto* column : {&s.lower, &s.upper, &s.interval_68_lower, &s.interval_68_upper, &s.interval_95_lower,
                             &s.interval_95_upper}) {
    RequireColumnLength(fit, "interval or bound", *column, rows);
  }
  RequireColumnLength(fit, "unit", s.unit, rows);
  RequireColumnLength(fit, "determined", s.determined, rows);
  return s;
}

StoredFitLabels ReadFitLabels(const io::hdf5::Group& fit) {
  StoredFitLabels l;
  l.block = fit.GetString("block").value_or("");
  l.position = fit.GetString("position").value_or("");
  l.settings_hash = fit.GetString("settings_hash").value_or("");
  l.mounting = fit.GetString("mounting").value_or("");
  l.feasible = fit.GetInt("feasible").value_or(1) != 0;
  l.epsilon_rad_s = fit.GetDouble("epsilon_rad_s").value_or(std::nan(""));
  l.wall_s = fit.GetDouble("wall_s").value_or(std::nan(""));
  l.simulations = fit.GetInt("simulations").value_or(0);
  l.noise_floor_rad_s = fit.GetDouble("noise_floor_rad_s").value_or(std::nan(""));
  l.model_error_rad_s = fit.GetDouble("model_error_rad_s").value_or(std::nan(""));
  l.noise_share = fit.GetDouble("noise_share").value_or(std::nan(""));
  l.model_error_dominates = fit.GetInt("model_error_dominates").value_or(-1);
  l.release_tilt_z = fit.GetDouble("release_tilt_z").value_or(std::nan(""));
  l.release_tilt_consistent = fit.GetInt("release_tilt_consistent").value_or(-1);
  l.release_tilt_check = fit.GetString("release_tilt_check").value_or("");
  return l;
}

std::vector<std::string> StoredFitTrials(const io::hdf5::Group& root) {
  return root.IsGroup("fits") ? root.OpenGroup("fits").Children() : std::vector<std::string>{};
}

std::map<std::string, std::string> StoredSettingsHashes(const std::filesystem::path& path) {
  std::map<std::string, std::string> hashes;
  if (!std::filesystem::exists(path) || !io::hdf5::File::IsHdf5(path)) return hashes;
  const io::hdf5::File file = io::hdf5::File::Open(path);
  const io::hdf5::Group root = file.Root();
  for (const std::string& id : StoredFitTrials(root)) {
    hashes[id] = root.OpenGroup("fits/" + id).GetString("settings_hash").value_or("");
  }
  return hashes;
}

std::vector<GroupSummary> WriteFitSummaryTables(const io::hdf5::Group& root) {
  PerTrialColumns columns = ReadPerTrialColumns(root);
  WritePerTrialTable(root, columns);
  std::vector<GroupSummary> groups = SummariseGroups(columns);
  WritePerGroupTable(root, groups);
  return groups;
}

bool HasFitGroupSummaries(const io::hdf5::Group& root) { return root.IsGroup(kPerGroup); }

std::vector<GroupSummary> ReadFitGroupSummaries(const io::hdf5::Group& root) {
  const io::hdf5::Group table = root.OpenGroup(kPerGroup);
  const std::vector<std::string> blocks = table.ReadStrings("block"), positions = table.ReadStrings("position");
  const std::size_t rows = std::min(blocks.size(), positions.size());
  const GroupColumns columns(table, rows);
  const std::vector<std::int64_t> n = columns.RequiredInts("n");
  std::vector<GroupSummary> groups(rows);
  for (std::size_t k = 0; k < rows; ++k) {
    groups[k].block = blocks[k];
    groups[k].position = positions[k];
    groups[k].n = n[k];
  }
  for (const char* name : kSummaryParameters) ReadGroupParameter(columns, name, &groups);
  return groups;
}

}  // namespace rockfit::fitting
