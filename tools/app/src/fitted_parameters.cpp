#include "rockfit/app/fitted_parameters.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include "rockfit/core/errors.hpp"
#include "rockfit/fitting/fit_store.hpp"
#include "rockfit/io/hdf5_file.hpp"

namespace rockfit::app {
namespace {

// The fitted values by name ("alpha", "lambda", …) of /fits/<trial>/parameters.
std::map<std::string, double> ParameterTable(const io::hdf5::Group& fit) {
  const fitting::StoredParameters stored = fitting::ReadFitParameters(fit);
  std::map<std::string, double> table;
  for (std::size_t k = 0; k < stored.size(); ++k) table[stored.name[k]] = stored.value[k];
  return table;
}

core::ModelParameters FromTable(const std::map<std::string, double>& table, const std::string& where) {
  const auto get = [&](const char* name) {
    const auto it = table.find(name);
    if (it == table.end()) {
      throw BadInput(where + ": no parameter '" + name + "' in the fit; write the fit again with a current rockfit");
    }
    return it->second;
  };
  core::ModelParameters p;
  p.alpha_rad = get("alpha");
  p.lambda = get("lambda");
  p.lambda_lat = get("lambda_lat");
  p.lambda_lon = get("lambda_lon");
  p.tau_edge = table.count("tau_edge") != 0 ? table.at("tau_edge") : 0.0;
  return p;
}

// One parameter of a per-group row: the pooled estimate with the standard error behind its 95 % interval (else
// the mean) and the spread between the trials.
FittedParameterRange RangeOf(const fitting::GroupSummary& g, const char* name, const std::string& file) {
  constexpr double kZ95 = 1.959963984540054;  // the pooled 95 % interval is ±1.96 standard errors
  const fitting::PooledEstimate& e = g.pooled.at(name);
  FittedParameterRange r;
  r.pooled = std::isfinite(e.pooled);
  r.value = r.pooled ? e.pooled : g.mean.at(name);
  if (r.pooled) {
    const double width = e.interval_95[1] - e.interval_95[0];
    r.estimate_sd = std::isfinite(width) ? 0.5 * width / kZ95 : 0.0;
  }
  const double spread = g.std_dev.at(name);
  r.between_trial_sd = std::isfinite(spread) ? spread : 0.0;
  if (!std::isfinite(r.value)) {
    throw BadInput(file + ": group " + g.block + "," + g.position + " has no value of " + name);
  }
  return r;
}

}  // namespace

FittedParameters ReadFittedTrial(const std::filesystem::path& fits, const std::string& trial) {
  const io::hdf5::File file = io::hdf5::File::Open(fits);
  const io::hdf5::Group root = file.Root();
  if (!root.IsGroup("fits/" + trial)) {
    std::string present;
    for (const std::string& name : fitting::StoredFitTrials(root)) present += (present.empty() ? "" : ", ") + name;
    throw BadInput(fits.string() + ": no fit of trial '" + trial + "' (/fits holds: " +
                   (present.empty() ? std::string("nothing") : present) + "); run rockfit fit … -o " + fits.string() +
                   " or rockfit batch first");
  }
  const io::hdf5::Group fit = root.OpenGroup("fits/" + trial);
  FittedParameters out;
  out.params = FromTable(ParameterTable(fit), fits.string() + ": /fits/" + trial);
  out.trials = {trial};
  out.description = "fit of " + trial;
  return out;
}

FittedParameters ReadFittedGroupMean(const std::filesystem::path& fits, const std::string& block,
                                     const std::string& position) {
  const io::hdf5::File file = io::hdf5::File::Open(fits);
  const io::hdf5::Group root = file.Root();
  std::map<std::string, double> sums;
  std::set<std::string> groups_present;
  FittedParameters out;
  for (const std::string& trial : fitting::StoredFitTrials(root)) {
    const io::hdf5::Group fit = root.OpenGroup("fits/" + trial);
    const fitting::StoredFitLabels labels = fitting::ReadFitLabels(fit);
    groups_present.insert(labels.block + "," + labels.position);
    if (labels.block != block || labels.position != position || !labels.feasible) continue;
    for (const auto& [name, value] : ParameterTable(fit)) sums[name] += value;
    out.trials.push_back(trial);
  }
  if (out.trials.empty()) {
    std::string present;
    for (const std::string& g : groups_present) present += (present.empty() ? "" : "; ") + g;
    throw BadInput(fits.string() + ": no feasible fit of block '" + block + "' in position '" + position +
                   "' (groups present: " + (present.empty() ? std::string("none") : present) +
                   "); give --group BLOCK,POSITION as in the manifest");
  }
  for (auto& [name, sum] : sums) sum /= static_cast<double>(out.trials.size());
  out.params = FromTable(sums, fits.string() + ": group " + block + "," + position);
  out.description = "mean of " + std::to_string(out.trials.size()) + " fits of " + block + " " + position;
  return out;
}

double FittedParameterRange::TotalSd() const {
  return std::sqrt(estimate_sd * estimate_sd + between_trial_sd * between_trial_sd);
}

FittedGroupRanges ReadFittedGroupRanges(const std::filesystem::path& fits, const std::string& block,
                                       const std::string& position) {
  const io::hdf5::File file = io::hdf5::File::Open(fits);
  const io::hdf5::Group root = file.Root();
  if (!fitting::HasFitGroupSummaries(root)) {
    throw BadInput(fits.string() + ": no /summary/fits/per_group (pooled estimates and spreads per block and "
                   "position); it is written by `rockfit batch MANIFEST -o " + fits.string() + "`");
  }
  const std::vector<fitting::GroupSummary> groups = fitting::ReadFitGroupSummaries(root);
  const auto row = std::find_if(groups.begin(), groups.end(), [&](const fitting::GroupSummary& g) {
    return g.block == block && g.position == position;
  });
  if (row == groups.end()) {
    std::string present;
    for (const fitting::GroupSummary& g : groups) present += (present.empty() ? "" : "; ") + g.block + "," + g.position;
    throw BadInput(fits.string() + ": /summary/fits/per_group has no group " + block + "," + position +
                   " (groups present: " + (present.empty() ? std::string("none") : present) +
                   "); give --group BLOCK,POSITION as in the manifest");
  }
  FittedGroupRanges out;
  out.lambda = RangeOf(*row, "lambda", fits.string());
  out.lambda_lat = RangeOf(*row, "lambda_lat", fits.string());
  out.lambda_lon = RangeOf(*row, "lambda_lon", fits.string());
  out.tau_edge = RangeOf(*row, "tau_edge", fits.string());
  out.trials = row->n;
  out.description = (out.lambda.pooled && out.lambda_lat.pooled && out.lambda_lon.pooled ? "pooled estimates of "
                                                                                          : "estimates of ") +
                    std::to_string(out.trials) + " fits of " + block + " " + position;
  return out;
}

}  // namespace rockfit::app
