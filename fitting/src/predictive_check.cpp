#include "rockfit/fitting/predictive_check.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <map>
#include <utility>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "parallel_for.hpp"
#include "rockfit/core/errors.hpp"
#include "rockfit/fitting/fitter.hpp"
#include "rockfit/fitting/local_optimizer.hpp"

namespace rockfit::fitting {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// The own 95 % interval as a range (an open end reaches to infinity); false when the fit has no interval.
bool OwnRange(const OwnFit& own, ParameterId id, double* lo, double* hi) {
  const Interval& i = own.interval_95[static_cast<std::size_t>(id)];
  if (std::isnan(i[0]) && std::isnan(i[1])) return false;
  *lo = std::isnan(i[0]) ? -std::numeric_limits<double>::infinity() : i[0];
  *hi = std::isnan(i[1]) ? std::numeric_limits<double>::infinity() : i[1];
  return true;
}

bool Overlaps(const OwnFit& own, ParameterId id, const PooledEstimate& pooled) {
  double lo = 0.0, hi = 0.0;
  if (!OwnRange(own, id, &lo, &hi) || !std::isfinite(pooled.interval_95[0]) || !std::isfinite(pooled.interval_95[1])) {
    return false;
  }
  return lo <= pooled.interval_95[1] && pooled.interval_95[0] <= hi;
}

// The others' mean of one parameter (used where no other trial determines it).
double MeanOfOthers(const std::vector<OwnFit>& fits, std::size_t left_out, ParameterId id) {
  double sum = 0.0;
  int n = 0;
  for (std::size_t i = 0; i < fits.size(); ++i) {
    if (i == left_out || !fits[i].feasible || fits[i].block != fits[left_out].block ||
        fits[i].position != fits[left_out].position) {
      continue;
    }
    sum += fits[i].values.value(id);
    ++n;
  }
  return n > 0 ? sum / n : kNaN;
}

// The best of Nelder–Mead runs of `objective` from the release (t0, α, β) of each start; held parameters stay.
LocalResult BestOfStarts(const Objective& objective, const std::vector<ParameterSet>& starts,
                         const PredictiveCheckOptions& options) {
  NelderMeadOptions nm;
  nm.max_evaluations = options.max_evaluations;
  const auto optimizer = MakeNelderMead(nm);
  LocalResult best;
  bool have = false;
  for (const ParameterSet& start : starts) {
    ParameterSet s = objective.parameters();
    for (ParameterId id : {ParameterId::kT0, ParameterId::kAlpha, ParameterId::kReleaseRoll}) {
      if (!s[id].fixed) s[id].value = std::clamp(start.value(id), s[id].lower, s[id].upper);
    }
    const LocalResult r = optimizer->Minimize(objective, objective.FreeValues(s));
    if (!have || (r.feasible && (!best.feasible || r.epsilon_rad_s < best.epsilon_rad_s))) {
      best = r;
      have = true;
    }
  }
  return best;
}

// The left-out trial's release — t0, α and the release roll β where its problem fits it (release_roll_choice.hpp:
// a roll belongs to one release, like t0 and α, and is never pooled) — with the impact parameters held; the better
// of two Nelder–Mead starts (the own fit's values, the data estimate) on the problem's window. Where the own fit
// extended its window (window_extension.hpp) its ε is taken again over the problem's window, at the own fit's
// values, so that ε_pred and ε_own are over the same nodes: over several return impacts the motion is so sensitive
// to the λ's that even λ's pooled to 0.1 % of the truth would not transfer there.
void FitReleaseOnly(const PreparedTrial& problem, const OwnFit& own, const PredictiveCheckOptions& options,
                    TrialPrediction* p) {
  ParameterSet held = problem.objective.parameters();
  for (std::size_t k = 0; k < kPooledImpactParameters.size(); ++k) {
    Parameter& q = held[kPooledImpactParameters[k]];
    q.value = std::clamp(p->held[k], q.lower, q.upper);
    q.fixed = true;
  }
  held[ParameterId::kT0].fixed = held[ParameterId::kAlpha].fixed = false;
  p->release_roll_fitted = !held[ParameterId::kReleaseRoll].fixed;
  const Objective objective = problem.objective.WithParameters(held);
  const std::int64_t runs_before = objective.counters().runs();
  const LocalResult best = BestOfStarts(objective, {own.values, problem.start}, options);
  p->t_end_s = objective.t_end_s();
  if (std::isfinite(own.t_end_s) && own.t_end_s != objective.t_end_s()) {
    const Evaluation own_here = objective.Evaluate(own.values);
    if (!own_here.feasible) {
      p->simulations = objective.counters().runs() - runs_before;
      p->message = "the own fit fails on the problem's window";
      return;
    }
    p->epsilon_own_rad_s = own_here.epsilon_rad_s;
  }
  p->simulations = objective.counters().runs() - runs_before;
  if (!best.feasible) {
    p->message = "the model fails everywhere with the pooled impact parameters";
    return;
  }
  const ParameterSet at = objective.WithFree(best.x);
  p->t0_s = at.value(ParameterId::kT0);
  p->alpha_rad = at.value(ParameterId::kAlpha);
  p->release_roll_rad = at.value(ParameterId::kReleaseRoll);
  p->epsilon_pred_rad_s = best.epsilon_rad_s;
  p->ratio = best.epsilon_rad_s / p->epsilon_own_rad_s;
  p->transfers = p->ratio <= options.ratio_warning;
  p->predicted = true;
}

TrialPrediction PredictTrial(const std::vector<OwnFit>& fits, std::size_t i,
                             const std::function<PreparedTrial(std::size_t)>& problem,
                             const PredictiveCheckOptions& options) {
  const OwnFit& own = fits[i];
  TrialPrediction p;
  p.trial = own.trial;
  p.block = own.block;
  p.position = own.position;
  p.epsilon_own_rad_s = own.epsilon_rad_s;
  p.pooled = PoolOthers(fits, i, &p.n_others);
  p.ratio = p.epsilon_pred_rad_s = p.t0_s = p.alpha_rad = p.release_roll_rad = p.t_end_s = kNaN;
  p.held.fill(kNaN);
  if (!own.feasible || !(own.epsilon_rad_s > 0.0)) {
    p.message = "no own fit: " + (own.message.empty() ? std::string("infeasible") : own.message);
    return p;
  }
  if (p.n_others == 0) {
    p.message = fmt::format("no other fitted trial of {} {} to take the impact parameters from", own.block, own.position);
    return p;
  }
  for (std::size_t k = 0; k < kPooledImpactParameters.size(); ++k) {
    const PooledEstimate& e = p.pooled[k];
    p.held[k] = e.n_pooled > 0 ? e.pooled : MeanOfOthers(fits, i, kPooledImpactParameters[k]);
    p.overlaps[k] = Overlaps(own, kPooledImpactParameters[k], e);
  }
  p.overlaps_all = std::all_of(p.overlaps.begin(), p.overlaps.end(), [](bool b) { return b; });
  try {
    FitReleaseOnly(problem(i), own, options, &p);
  } catch (const std::exception& e) {
    p.message = e.what();
  }
  return p;
}

double Median(std::vector<double> v) {
  if (v.empty()) return kNaN;
  std::sort(v.begin(), v.end());
  const std::size_t m = v.size() / 2;
  return v.size() % 2 == 1 ? v[m] : 0.5 * (v[m - 1] + v[m]);
}

std::vector<GroupValidation> SummariseGroups(const std::vector<TrialPrediction>& trials) {
  std::map<std::pair<std::string, std::string>, std::vector<const TrialPrediction*>> members;
  for (const TrialPrediction& t : trials) members[{t.block, t.position}].push_back(&t);
  std::vector<GroupValidation> groups;
  for (const auto& [key, list] : members) {
    GroupValidation g;
    g.block = key.first;
    g.position = key.second;
    g.n = static_cast<int>(list.size());
    std::vector<double> ratios;
    for (const TrialPrediction* t : list) {
      if (!t->predicted) continue;
      ++g.n_predicted;
      ratios.push_back(t->ratio);
      if (t->overlaps_all) ++g.n_overlap_all;
      if (t->transfers) ++g.n_transfer;
    }
    g.median_ratio = Median(ratios);
    g.max_ratio = ratios.empty() ? kNaN : *std::max_element(ratios.begin(), ratios.end());
    groups.push_back(g);
  }
  return groups;
}

nlohmann::json NumberOrNull(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(); }

}  // namespace

OwnFit OwnFitFromSummary(const std::string& trial, const std::string& block, const std::string& position,
                         const FitSummary& summary) {
  OwnFit f{trial, block, position, summary.parameters, {}, {}, summary.epsilon_rad_s, summary.feasible, "",
           summary.t_end_s};
  for (std::size_t k = 0; k < kNumParameters; ++k) {
    f.interval_95[k] = summary.uncertainty.interval_95[k];
    f.determined[k] = summary.uncertainty.determined[k] && *summary.uncertainty.determined[k] == Determination::kYes;
  }
  return f;
}

std::vector<OwnFit> FitOwnTrials(const std::vector<CampaignTrial>& trials, int num_threads) {
  std::vector<OwnFit> fits(trials.size());
  ParallelFor(trials.size(), num_threads, [&](std::size_t i) {
    const CampaignTrial& t = trials[i];
    try {
      const PreparedTrial prepared = t.prepare();
      FitOptions options = prepared.options;
      options.num_threads = 1;  // parallel over trials
      const FitSummary summary = Fit(prepared.objective, prepared.start, options);
      fits[i] = OwnFitFromSummary(t.id, t.labels.block_id, t.labels.position, summary);
      if (!summary.feasible) fits[i].message = "no feasible parameters: " + summary.termination;
    } catch (const std::exception& e) {
      fits[i].trial = t.id;
      fits[i].block = t.labels.block_id;
      fits[i].position = t.labels.position;
      fits[i].feasible = false;
      fits[i].epsilon_rad_s = kNaN;
      fits[i].message = e.what();
    }
  });
  return fits;
}

void PredictiveCheckOptions::Validate() const {
  if (max_evaluations < 10) throw InvalidArgument(fmt::format("predictive check: max_evaluations must be ≥ 10, got {}", max_evaluations));
  if (!(std::isfinite(ratio_warning) && ratio_warning >= 1.0)) {
    throw InvalidArgument(fmt::format("predictive check: ratio_warning must be ≥ 1, got {}", ratio_warning));
  }
  if (num_threads < 0) throw InvalidArgument("predictive check: num_threads must be ≥ 0");
}

std::array<PooledEstimate, 3> PoolOthers(const std::vector<OwnFit>& fits, std::size_t left_out, int* n_others) {
  std::array<std::vector<TrialEstimate>, 3> estimates;
  int n = 0;
  for (std::size_t i = 0; i < fits.size(); ++i) {
    const OwnFit& f = fits[i];
    if (i == left_out || !f.feasible || f.block != fits[left_out].block || f.position != fits[left_out].position) continue;
    ++n;
    for (std::size_t k = 0; k < kPooledImpactParameters.size(); ++k) {
      const auto id = static_cast<std::size_t>(kPooledImpactParameters[k]);
      estimates[k].push_back({f.values.value(kPooledImpactParameters[k]), f.interval_95[id], f.determined[id]});
    }
  }
  if (n_others) *n_others = n;
  std::array<PooledEstimate, 3> pooled;
  for (std::size_t k = 0; k < pooled.size(); ++k) pooled[k] = PoolTrials(estimates[k]);
  return pooled;
}

ValidationSummary RunPredictiveCheck(const std::vector<OwnFit>& fits,
                                     const std::function<PreparedTrial(std::size_t)>& problem,
                                     const PredictiveCheckOptions& options) {
  options.Validate();
  const auto start = std::chrono::steady_clock::now();
  ValidationSummary s;
  s.options = options;
  s.trials.resize(fits.size());
  ParallelFor(fits.size(), options.num_threads, [&](std::size_t i) { s.trials[i] = PredictTrial(fits, i, problem, options); });
  for (const TrialPrediction& t : s.trials) s.simulations += t.simulations;
  s.groups = SummariseGroups(s.trials);
  s.wall_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return s;
}

std::string ValidationJson(const ValidationSummary& s) {
  nlohmann::json trials = nlohmann::json::array();
  for (const TrialPrediction& t : s.trials) {
    nlohmann::json pooled = nlohmann::json::object();
    for (std::size_t k = 0; k < kPooledImpactParameters.size(); ++k) {
      const PooledEstimate& e = t.pooled[k];
      pooled[Name(kPooledImpactParameters[k])] = {
          {"held", NumberOrNull(t.held[k])},
          {"pooled", e.n_pooled > 0 ? NumberOrNull(e.pooled) : nlohmann::json()},
          {"pooled_interval_95", {NumberOrNull(e.interval_95[0]), NumberOrNull(e.interval_95[1])}},
          {"n_pooled", e.n_pooled},
          {"overlaps", t.overlaps[k]}};
    }
    trials.push_back({{"trial", t.trial},
                      {"block", t.block},
                      {"position", t.position},
                      {"predicted", t.predicted},
                      {"message", t.message},
                      {"n_others", t.n_others},
                      {"epsilon_own", NumberOrNull(t.epsilon_own_rad_s)},
                      {"epsilon_pred", NumberOrNull(t.epsilon_pred_rad_s)},
                      {"ratio", NumberOrNull(t.ratio)},
                      {"transfers", t.predicted ? nlohmann::json(t.transfers) : nlohmann::json()},
                      {"overlaps_all", t.overlaps_all},
                      {"t0", NumberOrNull(t.t0_s)},
                      {"alpha", NumberOrNull(t.alpha_rad)},
                      {"release_roll", NumberOrNull(t.release_roll_rad)},
                      {"release_roll_fitted", t.predicted ? nlohmann::json(t.release_roll_fitted) : nlohmann::json()},
                      {"t_end", NumberOrNull(t.t_end_s)},
                      {"parameters", pooled}});
  }
  nlohmann::json groups = nlohmann::json::array();
  for (const GroupValidation& g : s.groups) {
    groups.push_back({{"block", g.block},
                      {"position", g.position},
                      {"n", g.n},
                      {"n_predicted", g.n_predicted},
                      {"median_ratio", NumberOrNull(g.median_ratio)},
                      {"max_ratio", NumberOrNull(g.max_ratio)},
                      {"n_transfer", g.n_transfer},
                      {"n_overlap_all", g.n_overlap_all}});
  }
  return nlohmann::json{{"trials", trials},
                        {"groups", groups},
                        {"ratio_warning", s.options.ratio_warning},
                        {"simulations", s.simulations},
                        {"wall_s", s.wall_time_s}}
      .dump();
}

}  // namespace rockfit::fitting
