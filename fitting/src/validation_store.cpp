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

void WritePerTrial(const io::hdf5::Group& v, const ValidationSummary& s) {
  const io::hdf5::Group t = v.CreateGroup("per_trial");
  std::vector<std::string> trial, block, position, message;
  std::vector<double> eps_own, eps_pred, ratio, t0, alpha;
  std::vector<std::int64_t> predicted, n_others, transfers, overlaps_all;
  for (const TrialPrediction& p : s.trials) {
    trial.push_back(p.trial);
    block.push_back(p.block);
    position.push_back(p.position);
    message.push_back(p.message);
    eps_own.push_back(p.epsilon_own_rad_s);
    eps_pred.push_back(p.epsilon_pred_rad_s);
    ratio.push_back(p.ratio);
    t0.push_back(p.t0_s);
    alpha.push_back(p.alpha_rad);
    predicted.push_back(p.predicted ? 1 : 0);
    n_others.push_back(p.n_others);
    transfers.push_back(p.predicted ? (p.transfers ? 1 : 0) : -1);
    overlaps_all.push_back(p.overlaps_all ? 1 : 0);
  }
  t.WriteStrings("trial", trial);
  t.WriteStrings("block", block);
  t.WriteStrings("position", position);
  t.WriteInts("predicted", predicted, "1");
  t.WriteStrings("message", message);
  t.WriteInts("n_others", n_others, "1");
  t.WriteDoubles("epsilon_own_rad_s", eps_own, "rad/s");
  t.WriteDoubles("epsilon_pred_rad_s", eps_pred, "rad/s; NaN: not predicted");
  t.WriteDoubles("ratio", ratio, "1; ε_pred/ε_own, NaN: not predicted");
  t.WriteInts("transfers", transfers, "1; ratio ≤ ratio_warning, -1: not predicted");
  t.WriteInts("overlaps_all", overlaps_all, "1; the own 95 % intervals of λ, λ_lat, λ_lon overlap the pooled ones");
  t.WriteDoubles("t0_s", t0, "s; fitted with the pooled impact parameters held");
  t.WriteDoubles("alpha_rad", alpha, "rad; fitted with the pooled impact parameters held");
  for (std::size_t k = 0; k < kPooledImpactParameters.size(); ++k) {
    const std::string name = Name(kPooledImpactParameters[k]);
    std::vector<double> held, lo, hi;
    std::vector<std::int64_t> overlaps, n_pooled;
    for (const TrialPrediction& p : s.trials) {
      held.push_back(p.held[k]);
      lo.push_back(p.pooled[k].interval_95[0]);
      hi.push_back(p.pooled[k].interval_95[1]);
      overlaps.push_back(p.overlaps[k] ? 1 : 0);
      n_pooled.push_back(p.pooled[k].n_pooled);
    }
    t.WriteDoubles(name + "_held", held, "1; the others' pooled estimate (their mean where none determines it)");
    t.WriteDoubles(name + "_pooled_95_lower", lo, "1; NaN: no other trial determines it");
    t.WriteDoubles(name + "_pooled_95_upper", hi, "1; NaN: no other trial determines it");
    t.WriteInts(name + "_n_pooled", n_pooled, "1");
    t.WriteInts(name + "_overlaps", overlaps, "1");
  }
}

void WritePerGroup(const io::hdf5::Group& v, const ValidationSummary& s) {
  const io::hdf5::Group g = v.CreateGroup("per_group");
  std::vector<std::string> block, position;
  std::vector<std::int64_t> n, n_predicted, n_transfer, n_overlap_all;
  std::vector<double> median_ratio, max_ratio;
  for (const GroupValidation& r : s.groups) {
    block.push_back(r.block);
    position.push_back(r.position);
    n.push_back(r.n);
    n_predicted.push_back(r.n_predicted);
    n_transfer.push_back(r.n_transfer);
    n_overlap_all.push_back(r.n_overlap_all);
    median_ratio.push_back(r.median_ratio);
    max_ratio.push_back(r.max_ratio);
  }
  g.WriteStrings("block", block);
  g.WriteStrings("position", position);
  g.WriteInts("n", n, "1");
  g.WriteInts("n_predicted", n_predicted, "1");
  g.WriteDoubles("median_ratio", median_ratio, "1; NaN: none predicted");
  g.WriteDoubles("max_ratio", max_ratio, "1; NaN: none predicted");
  g.WriteInts("n_transfer", n_transfer, "1");
  g.WriteInts("n_overlap_all", n_overlap_all, "1");
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
