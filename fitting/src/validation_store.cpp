#include "rockfit/fitting/validation_store.hpp"

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "rockfit/core/errors.hpp"
#include "rockfit/fitting/fit_store.hpp"

namespace rockfit::fitting {
namespace {

constexpr const char* kValidation = "validation";

// One column of a table from a value of each row.
template <class Row, class Get>
void DoubleColumn(const io::hdf5::Group& g, const std::string& name, const std::vector<Row>& rows, Get get,
                  const std::string& units) {
  std::vector<double> column;
  for (const Row& r : rows) column.push_back(get(r));
  g.WriteDoubles(name, column, units);
}
template <class Row, class Get>
void IntColumn(const io::hdf5::Group& g, const std::string& name, const std::vector<Row>& rows, Get get,
               const std::string& units) {
  std::vector<std::int64_t> column;
  for (const Row& r : rows) column.push_back(get(r));
  g.WriteInts(name, column, units);
}
template <class Row, class Get>
void StringColumn(const io::hdf5::Group& g, const std::string& name, const std::vector<Row>& rows, Get get) {
  std::vector<std::string> column;
  for (const Row& r : rows) column.push_back(get(r));
  g.WriteStrings(name, column);
}

void WritePerTrial(const io::hdf5::Group& v, const ValidationSummary& s) {
  const io::hdf5::Group t = v.CreateGroup("per_trial");
  using P = TrialPrediction;
  const std::vector<P>& rows = s.trials;
  StringColumn(t, "trial", rows, [](const P& p) { return p.trial; });
  StringColumn(t, "block", rows, [](const P& p) { return p.block; });
  StringColumn(t, "position", rows, [](const P& p) { return p.position; });
  IntColumn(t, "predicted", rows, [](const P& p) { return p.predicted ? 1 : 0; }, "1");
  StringColumn(t, "message", rows, [](const P& p) { return p.message; });
  IntColumn(t, "n_others", rows, [](const P& p) { return p.n_others; }, "1");
  DoubleColumn(t, "epsilon_own_rad_s", rows, [](const P& p) { return p.epsilon_own_rad_s; }, "rad/s");
  DoubleColumn(t, "epsilon_pred_rad_s", rows, [](const P& p) { return p.epsilon_pred_rad_s; }, "rad/s; NaN: not predicted");
  DoubleColumn(t, "ratio", rows, [](const P& p) { return p.ratio; }, "1; ε_pred/ε_own, NaN: not predicted");
  IntColumn(t, "transfers", rows, [](const P& p) { return p.predicted ? (p.transfers ? 1 : 0) : -1; },
            "1; ratio ≤ ratio_warning, -1: not predicted");
  IntColumn(t, "overlaps_all", rows, [](const P& p) { return p.overlaps_all ? 1 : 0; },
            "1; the own 95 % intervals of λ, λ_lat, λ_lon overlap the pooled ones");
  DoubleColumn(t, "t0_s", rows, [](const P& p) { return p.t0_s; }, "s; fitted with the pooled impact parameters held");
  DoubleColumn(t, "alpha_rad", rows, [](const P& p) { return p.alpha_rad; },
               "rad; fitted with the pooled impact parameters held");
  DoubleColumn(t, "release_roll_rad", rows, [](const P& p) { return p.release_roll_rad; },
               "rad; fitted with t0 and α where release_roll_fitted, else held; NaN: not predicted");
  IntColumn(t, "release_roll_fitted", rows, [](const P& p) { return p.predicted ? (p.release_roll_fitted ? 1 : 0) : -1; },
            "1; the trial's problem fits its release roll (--release-roll-mode), -1: not predicted");
  DoubleColumn(t, "t_end_s", rows, [](const P& p) { return p.t_end_s; },
               "s; end of the window of epsilon_own and epsilon_pred (recording time), NaN: not predicted");
  for (std::size_t k = 0; k < kPooledImpactParameters.size(); ++k) {
    const std::string name = Name(kPooledImpactParameters[k]);
    DoubleColumn(t, name + "_held", rows, [k](const P& p) { return p.held[k]; },
                 "1; the others' pooled estimate (their mean where none determines it)");
    DoubleColumn(t, name + "_pooled_95_lower", rows, [k](const P& p) { return p.pooled[k].interval_95[0]; },
                 "1; NaN: no other trial determines it");
    DoubleColumn(t, name + "_pooled_95_upper", rows, [k](const P& p) { return p.pooled[k].interval_95[1]; },
                 "1; NaN: no other trial determines it");
    IntColumn(t, name + "_n_pooled", rows, [k](const P& p) { return p.pooled[k].n_pooled; }, "1");
    IntColumn(t, name + "_overlaps", rows, [k](const P& p) { return p.overlaps[k] ? 1 : 0; }, "1");
  }
}

void WritePerGroup(const io::hdf5::Group& v, const ValidationSummary& s) {
  const io::hdf5::Group g = v.CreateGroup("per_group");
  using G = GroupValidation;
  const std::vector<G>& rows = s.groups;
  StringColumn(g, "block", rows, [](const G& r) { return r.block; });
  StringColumn(g, "position", rows, [](const G& r) { return r.position; });
  IntColumn(g, "n", rows, [](const G& r) { return r.n; }, "1");
  IntColumn(g, "n_predicted", rows, [](const G& r) { return r.n_predicted; }, "1");
  DoubleColumn(g, "median_ratio", rows, [](const G& r) { return r.median_ratio; }, "1; NaN: none predicted");
  DoubleColumn(g, "max_ratio", rows, [](const G& r) { return r.max_ratio; }, "1; NaN: none predicted");
  IntColumn(g, "n_transfer", rows, [](const G& r) { return r.n_transfer; }, "1");
  IntColumn(g, "n_overlap_all", rows, [](const G& r) { return r.n_overlap_all; }, "1");
}

}  // namespace

OwnFit ReadOwnFit(const io::hdf5::Group& root, const std::string& trial) {
  if (!root.IsGroup("fits/" + trial)) {
    throw BadInput(root.file_name() + ": no /fits/" + trial + "; fit the campaign first with rockfit batch MANIFEST -o " +
                   root.file_name());
  }
  const io::hdf5::Group g = root.OpenGroup("fits/" + trial);
  const StoredParameters stored = ReadFitParameters(g);
  const StoredFitLabels labels = ReadFitLabels(g);
  OwnFit f;
  f.trial = trial;
  f.block = labels.block;
  f.position = labels.position;
  f.epsilon_rad_s = labels.epsilon_rad_s;
  f.feasible = labels.feasible;
  f.t_end_s = g.GetDouble("t_end_s").value_or(std::nan(""));  // the window of ε, extended or not
  // A fit that did not estimate the release roll stores no row for it: the roll was held at 0.
  f.values[ParameterId::kReleaseRoll].fixed = true;
  for (ParameterId id : kAllParameters) {
    const std::size_t row = stored.Row(Name(id)), k = static_cast<std::size_t>(id);
    if (row >= stored.size()) {
      f.interval_95[k] = {std::nan(""), std::nan("")};
      continue;
    }
    f.values[id].value = stored.value[row];
    f.values[id].fixed = stored.fixed[row];
    f.interval_95[k] = {stored.interval_95_lower[row], stored.interval_95_upper[row]};
    f.determined[k] = stored.determined[row] == "yes";
  }
  return f;
}

void WriteValidationGroup(const io::hdf5::Group& root, const ValidationSummary& s) {
  const io::hdf5::Group v = root.CreateGroup(kValidation);
  v.SetDouble("ratio_warning", s.options.ratio_warning);
  v.SetInt("max_evaluations", s.options.max_evaluations);
  v.SetInt("simulations", s.simulations);
  v.SetDouble("wall_s", s.wall_time_s);
  WritePerTrial(v, s);
  WritePerGroup(v, s);
}

ValidationSummary ReadValidationGroup(const io::hdf5::Group& root) {
  if (!root.IsGroup(kValidation)) {
    throw BadInput(root.file_name() + ": no /validation group; write one with rockfit validate MANIFEST -o FILE");
  }
  const io::hdf5::Group t = root.OpenGroup(std::string(kValidation) + "/per_trial");
  const std::vector<std::string> trial = t.ReadStrings("trial"), block = t.ReadStrings("block"),
                                 position = t.ReadStrings("position");
  const std::vector<double> own = t.ReadDoubles("epsilon_own_rad_s"), pred = t.ReadDoubles("epsilon_pred_rad_s"),
                            ratio = t.ReadDoubles("ratio");
  const std::vector<std::int64_t> predicted = t.ReadInts("predicted"), overlaps = t.ReadInts("overlaps_all");
  const std::size_t n = trial.size();
  for (std::size_t size : {block.size(), position.size(), own.size(), pred.size(), ratio.size(), predicted.size(),
                           overlaps.size()}) {
    if (size != n) throw BadInput(root.file_name() + ": /validation/per_trial has columns of different lengths");
  }
  ValidationSummary s;
  s.options.ratio_warning = root.OpenGroup(kValidation).GetDouble("ratio_warning").value_or(1.5);
  for (std::size_t i = 0; i < n; ++i) {
    TrialPrediction p;
    p.trial = trial[i];
    p.block = block[i];
    p.position = position[i];
    p.predicted = predicted[i] != 0;
    p.epsilon_own_rad_s = own[i];
    p.epsilon_pred_rad_s = pred[i];
    p.ratio = ratio[i];
    p.overlaps_all = overlaps[i] != 0;
    p.transfers = p.predicted && p.ratio <= s.options.ratio_warning;
    s.trials.push_back(p);
  }
  return s;
}

}  // namespace rockfit::fitting
