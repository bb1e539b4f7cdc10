#include "rockfit/app/validation_run.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "rockfit/core/errors.hpp"
#include "rockfit/fitting/validation_store.hpp"
#include "rockfit/io/hdf5_file.hpp"
#include "rockfit/io/manifest.hpp"

namespace rockfit::app {

fitting::ValidationSummary RunValidation(const ValidateArgs& args) {
  if (args.jobs < 0) throw InvalidArgument("-j must be ≥ 0 (0: all cores)");
  fitting::PredictiveCheckOptions options;
  options.num_threads = args.jobs;
  options.ratio_warning = args.ratio_warning;
  options.Validate();
  MakeParameterSet(args.fit);  // option errors before any work
  const io::Manifest manifest = io::ReadManifest(args.manifest);
  if (manifest.trials.empty()) throw BadInput(fmt::format("{}: the manifest lists no trials", args.manifest));

  FitArgs fit_args = args.fit;
  fit_args.threads = 1;  // parallel over trials
  std::vector<fitting::CampaignTrial> trials;
  for (const io::TrialSpec& spec : manifest.trials) trials.push_back(MakeCampaignTrial(manifest, spec, fit_args));

  std::vector<fitting::OwnFit> fits;
  if (args.fits.empty()) {
    fits = fitting::FitOwnTrials(trials, args.jobs);
  } else {
    const io::hdf5::File file = io::hdf5::File::Open(args.fits);
    for (const fitting::CampaignTrial& t : trials) {
      fitting::OwnFit f = fitting::ReadOwnFit(file.Root(), t.id);
      // The manifest decides the group, as it decided the problem.
      f.block = t.labels.block_id;
      f.position = t.labels.position;
      fits.push_back(std::move(f));
    }
  }
  return fitting::RunPredictiveCheck(fits, [&trials](std::size_t i) { return trials[i].prepare(); }, options);
}

std::string ValidationTable(const fitting::ValidationSummary& s) {
  auto number = [](double v, const char* format) { return std::isfinite(v) ? fmt::format(fmt::runtime(format), v) : "—"; };
  auto yes_no = [](bool b) { return b ? "yes" : "no"; };
  // The left-out trial's release roll gets a column where some trial's problem fits it (refitted with t0 and α).
  const bool any_roll = std::any_of(s.trials.begin(), s.trials.end(),
                                    [](const fitting::TrialPrediction& t) { return t.predicted && t.release_roll_fitted; });
  auto roll = [&](const fitting::TrialPrediction& t) {
    if (!any_roll) return std::string();
    return fmt::format("{:>12} ", t.release_roll_fitted ? fmt::format("{:.3f}", 1e3 * t.release_roll_rad)
                                                         : fmt::format("held {:.3g}", 1e3 * t.release_roll_rad));
  };
  std::string out = fmt::format("{:<14} {:<8} {:<4} {:>11} {:>11} {:>7}  {:<8} {:<6} {:<10} {:<10} {}{}\n", "trial",
                                "block", "pos", "ε_own", "ε_pred", "ratio", "overlap", "λ", "λ_lat", "λ_lon",
                                any_roll ? fmt::format("{:>12} ", "β [mrad]") : "", "held λ, λ_lat, λ_lon");
  for (const fitting::TrialPrediction& t : s.trials) {
    if (!t.predicted) {
      out += fmt::format("{:<14} {:<8} {:<4} {:>11} {:>11} {:>7}  not predicted: {}\n", t.trial, t.block, t.position,
                         number(t.epsilon_own_rad_s, "{:.5g}"), "—", "—", t.message);
      continue;
    }
    out += fmt::format("{:<14} {:<8} {:<4} {:>11.5g} {:>11.5g} {:>7.3f}{} {:<8} {:<6} {:<10} {:<10} {}{}, {}, {}\n",
                       t.trial, t.block, t.position, t.epsilon_own_rad_s, t.epsilon_pred_rad_s, t.ratio,
                       t.transfers ? " " : "!", yes_no(t.overlaps_all), yes_no(t.overlaps[0]), yes_no(t.overlaps[1]),
                       yes_no(t.overlaps[2]), roll(t), number(t.held[0], "{:.4g}"), number(t.held[1], "{:.4g}"),
                       number(t.held[2], "{:.4g}"));
  }
  out += fmt::format("{:<8} {:<4} {:>2} {:>9} {:>13} {:>10} {:>12} {:>14}\n", "block", "pos", "n", "predicted",
                     "median ratio", "max ratio", "ratio ≤ " + fmt::format("{:g}", s.options.ratio_warning),
                     "overlap (all)");
  for (const fitting::GroupValidation& g : s.groups) {
    out += fmt::format("{:<8} {:<4} {:>2} {:>9} {:>13} {:>10} {:>12} {:>14}\n", g.block, g.position, g.n, g.n_predicted,
                       number(g.median_ratio, "{:.3f}"), number(g.max_ratio, "{:.3f}"), g.n_transfer, g.n_overlap_all);
  }
  return out;
}

}  // namespace rockfit::app
