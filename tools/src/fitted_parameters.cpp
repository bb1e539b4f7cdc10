#include "fitted_parameters.hpp"

#include <cmath>
#include <map>
#include <set>

#include "rockfit/core/errors.hpp"
#include "rockfit/io/hdf5_file.hpp"

namespace rockfit::tools {
namespace {

// The fitted values by name ("alpha", "lambda", …) of /fits/<trial>/parameters.
std::map<std::string, double> ParameterTable(const io::hdf5::Group& fit) {
  const std::vector<std::string> names = fit.ReadStrings("parameters/name");
  const std::vector<double> values = fit.ReadDoubles("parameters/value");
  if (names.size() != values.size()) {
    throw BadInput(fit.file_name() + ": " + fit.path() + "/parameters has " + std::to_string(names.size()) +
                   " names but " + std::to_string(values.size()) + " values; write the fit again with rockfit fit -o");
  }
  std::map<std::string, double> table;
  for (std::size_t k = 0; k < names.size(); ++k) table[names[k]] = values[k];
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

}  // namespace

FittedParameters ReadFittedTrial(const std::filesystem::path& fits, const std::string& trial) {
  const io::hdf5::File file = io::hdf5::File::Open(fits);
  const io::hdf5::Group root = file.Root();
  if (!root.IsGroup("fits/" + trial)) {
    std::string present;
    if (root.IsGroup("fits")) {
      for (const std::string& name : root.OpenGroup("fits").Children()) present += (present.empty() ? "" : ", ") + name;
    }
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
  if (root.IsGroup("fits")) {
    const io::hdf5::Group all = root.OpenGroup("fits");
    for (const std::string& trial : all.Children()) {
      const io::hdf5::Group fit = all.OpenGroup(trial);
      const std::string b = fit.GetString("block").value_or("");
      const std::string pos = fit.GetString("position").value_or("");
      groups_present.insert(b + "," + pos);
      if (b != block || pos != position || fit.GetInt("feasible").value_or(1) == 0) continue;
      for (const auto& [name, value] : ParameterTable(fit)) sums[name] += value;
      out.trials.push_back(trial);
    }
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
  constexpr double kZ95 = 1.959963984540054;  // the pooled 95 % interval is ±1.96 standard errors
  const io::hdf5::File file = io::hdf5::File::Open(fits);
  const io::hdf5::Group root = file.Root();
  const std::string table = "summary/fits/per_group";
  if (!root.IsGroup(table)) {
    throw BadInput(fits.string() + ": no /" + table + " (pooled estimates and spreads per block and position); it is "
                   "written by `rockfit batch MANIFEST -o " + fits.string() + "`");
  }
  const io::hdf5::Group g = root.OpenGroup(table);
  const std::vector<std::string> blocks = g.ReadStrings("block"), positions = g.ReadStrings("position");
  std::size_t row = blocks.size();
  std::string present;
  for (std::size_t i = 0; i < blocks.size() && i < positions.size(); ++i) {
    if (blocks[i] == block && positions[i] == position) row = i;
    present += (present.empty() ? "" : "; ") + blocks[i] + "," + positions[i];
  }
  if (row == blocks.size()) {
    throw BadInput(fits.string() + ": /" + table + " has no group " + block + "," + position + " (groups present: " +
                   (present.empty() ? std::string("none") : present) + "); give --group BLOCK,POSITION as in the manifest");
  }
  const auto column = [&](const std::string& name) {
    const std::vector<double> values = g.ReadDoubles(name);
    if (row >= values.size()) {
      throw BadInput(fits.string() + ": /" + table + "/" + name + " is shorter than the group table; run rockfit batch again");
    }
    return values[row];
  };
  const auto range = [&](const std::string& name) {
    FittedParameterRange r;
    const double pooled = column(name + "_pooled");
    r.pooled = std::isfinite(pooled);
    r.value = r.pooled ? pooled : column(name + "_mean");
    if (r.pooled) {
      const double width = column(name + "_pooled_95_upper") - column(name + "_pooled_95_lower");
      r.estimate_sd = std::isfinite(width) ? 0.5 * width / kZ95 : 0.0;
    }
    const double spread = column(name + "_std");
    r.between_trial_sd = std::isfinite(spread) ? spread : 0.0;
    if (!std::isfinite(r.value)) {
      throw BadInput(fits.string() + ": group " + block + "," + position + " has no value of " + name);
    }
    return r;
  };
  FittedGroupRanges out;
  out.lambda = range("lambda");
  out.lambda_lat = range("lambda_lat");
  out.lambda_lon = range("lambda_lon");
  out.tau_edge = range("tau_edge");
  out.trials = g.ReadInts("n").at(row);
  out.description = (out.lambda.pooled && out.lambda_lat.pooled && out.lambda_lon.pooled ? "pooled estimates of "
                                                                                          : "estimates of ") +
                    std::to_string(out.trials) + " fits of " + block + " " + position;
  return out;
}

}  // namespace rockfit::tools
