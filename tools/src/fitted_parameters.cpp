#include "fitted_parameters.hpp"

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

}  // namespace rockfit::tools
