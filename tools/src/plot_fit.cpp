// `rockfit plot fit FITS.h5 --trial ID` (paper Fig. 14) and `rockfit plot parameters FITS.h5` (Fig. 15).
#include "plot_fit.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <array>
#include <map>

#include <fmt/format.h>

#include "cli_common.hpp"
#include "command_registry.hpp"
#include "rockfit/app/gnuplot.hpp"
#include "plot_command.hpp"
#include "rockfit/core/errors.hpp"
#include "rockfit/fitting/fit_store.hpp"
#include "rockfit/io/hdf5_file.hpp"

namespace rockfit::tools {
namespace {

const char* const kColours[3] = {"#d62728", "#1f77b4", "#2ca02c"};
const char* const kComponent[3] = {"ω_x", "ω_y", "ω_z"};

io::hdf5::Group OpenFits(const io::hdf5::File& file, const std::string& path) {
  const io::hdf5::Group root = file.Root();
  if (fitting::StoredFitTrials(root).empty()) {
    throw BadInput(fmt::format("{}: no /fits group; write one with `rockfit fit ... -o {}` or `rockfit batch`", path, path));
  }
  return root.OpenGroup("fits");
}

// The pooled estimates of /summary/fits/per_group (written by `batch`); none when the file has no such table or
// one from before the pooled columns (its bands are simply not drawn).
std::vector<fitting::GroupSummary> PooledGroups(const io::hdf5::Group& root) {
  if (!fitting::HasFitGroupSummaries(root) || !root.IsDataset("summary/fits/per_group/n")) return {};
  return fitting::ReadFitGroupSummaries(root);
}

FitPlotData ReadFitPlotData(const std::string& path, const std::string& trial) {
  const io::hdf5::File file = io::hdf5::File::Open(path);
  const io::hdf5::Group fits = OpenFits(file, path);
  std::string id = trial;
  if (id.empty()) {
    const std::vector<std::string> children = fitting::StoredFitTrials(file.Root());
    if (children.size() != 1) {
      std::string list;
      for (const std::string& c : children) list += (list.empty() ? "" : ", ") + c;
      throw InvalidArgument(fmt::format("{} holds several fits; choose one with --trial ID ({})", path, list));
    }
    id = children.front();
  }
  if (!fits.IsGroup(id)) throw BadInput(fmt::format("{}: no fit /fits/{}", path, id));
  const io::hdf5::Group g = fits.OpenGroup(id);
  FitPlotData d;
  d.trial = id;
  d.t_s = g.ReadDoubles("time_s");
  d.w_measured_B = g.ReadVectors("w_B_measured");
  if (g.IsDataset("w_B_simulated")) d.w_simulated_B = g.ReadVectors("w_B_simulated");
  d.impact_t_s = g.ReadDoubles("impacts/t_s");
  for (const std::string& text : g.ReadStrings("impacts/kind")) {
    core::ImpactKind kind = core::ImpactKind::kFacet;
    if (!core::FromString(text, &kind)) {
      throw BadInput(fmt::format("{}: /fits/{}/impacts/kind holds '{}', not an impact kind", path, id, text));
    }
    d.impact_kind.push_back(kind);
  }
  d.epsilon_rad_s = fitting::ReadFitLabels(g).epsilon_rad_s;
  const fitting::StoredParameters p = fitting::ReadFitParameters(g);
  if (p.has_intervals) {
    d.parameter_lines = ParameterLines(p.name, p.unit, p.value, p.fixed, p.interval_95_lower, p.interval_95_upper);
  }
  return d;
}

struct PlotFitCommand {
  std::string path;
  std::string trial;
  PictureArgs picture;
};

int RunPlotFit(const PlotFitCommand& cmd) {
  const FitPlotData d = ReadFitPlotData(cmd.path, cmd.trial);
  RenderFitPlot(d, cmd.picture.output, cmd.picture.width_px, cmd.picture.height_px);
  return ReportPicture("fit", cmd.picture, {{"trial", d.trial}, {"epsilon", d.epsilon_rad_s}});
}

struct PlotParametersCommand {
  std::string path;
  PictureArgs picture;
};

int RunPlotParameters(const PlotParametersCommand& cmd) {
  const io::hdf5::File file = io::hdf5::File::Open(cmd.path);
  const io::hdf5::Group fits = OpenFits(file, cmd.path);
  struct Row {
    std::string trial, group;
    std::map<std::string, double> value, lower, upper;  // value and 95 % interval (open ends at the bound)
  };
  std::vector<Row> rows;
  for (const std::string& id : fitting::StoredFitTrials(file.Root())) {
    const io::hdf5::Group g = fits.OpenGroup(id);
    if (!g.IsGroup("parameters")) continue;
    const fitting::StoredFitLabels labels = fitting::ReadFitLabels(g);
    const fitting::StoredParameters p = fitting::ReadFitParameters(g);
    Row r;
    r.trial = id;
    r.group = labels.block.empty() ? "—" : labels.block + " " + labels.position;
    for (std::size_t k = 0; k < p.size(); ++k) {
      r.value[p.name[k]] = p.value[k];
      if (!p.has_intervals || p.determined[k] == "fixed") continue;
      // An open end reaches the bound: the bar shows how far the data leave the parameter free.
      r.lower[p.name[k]] = std::isnan(p.interval_95_lower[k]) ? p.lower[k] : p.interval_95_lower[k];
      r.upper[p.name[k]] = std::isnan(p.interval_95_upper[k]) ? p.upper[k] : p.interval_95_upper[k];
    }
    r.value["epsilon"] = labels.epsilon_rad_s;
    rows.push_back(r);
  }
  std::stable_sort(rows.begin(), rows.end(), [](const Row& a, const Row& b) { return a.group < b.group; });
  const char* const panels[] = {"alpha", "lambda", "lambda_lat", "lambda_lon", "epsilon"};
  const char* const labels[] = {"α [rad]", "λ", "λ_{lat}", "λ_{lon}", "ε (28) [rad/s]"};
  GnuplotFigure figure;
  // Columns: x, then per panel value, lower and upper end of the 95 % interval (NaN: no interval).
  std::vector<std::vector<double>> columns(16);
  std::string xtics;
  std::vector<std::size_t> block_starts;
  std::map<std::string, std::pair<std::size_t, std::size_t>> group_rows;  // first and last x of each group
  auto lookup = [](const std::map<std::string, double>& m, const char* key) {
    const auto it = m.find(key);
    return it == m.end() ? std::nan("") : it->second;
  };
  for (std::size_t i = 0; i < rows.size(); ++i) {
    if (i > 0 && rows[i].group != rows[i - 1].group) block_starts.push_back(i);
    if (!group_rows.count(rows[i].group)) group_rows[rows[i].group] = {i + 1, i + 1};
    group_rows[rows[i].group].second = i + 1;
    columns[0].push_back(static_cast<double>(i + 1));
    for (std::size_t p = 0; p < 5; ++p) {
      columns[3 * p + 1].push_back(lookup(rows[i].value, panels[p]));
      columns[3 * p + 2].push_back(lookup(rows[i].lower, panels[p]));
      columns[3 * p + 3].push_back(lookup(rows[i].upper, panels[p]));
    }
    xtics += fmt::format("{}{} {}", xtics.empty() ? "" : ", ", GnuplotString(rows[i].trial), i + 1);
  }
  const std::string data = figure.AddData("parameters", columns, block_starts);
  // The pooled range of each block and position (/summary/fits/per_group, written by `batch`): a band over the
  // group's trials from the lower to the upper end of the pooled 95 % interval, a line at the pooled value.
  std::array<std::string, 5> bands;
  for (const fitting::GroupSummary& group : PooledGroups(file.Root())) {
    const auto it = group_rows.find(group.block.empty() ? "—" : group.block + " " + group.position);
    if (it == group_rows.end()) continue;
    const double x1 = static_cast<double>(it->second.first) - 0.4, x2 = static_cast<double>(it->second.second) + 0.4;
    for (std::size_t p = 0; p < 4; ++p) {
      const auto pooled = group.pooled.find(panels[p]);
      if (pooled == group.pooled.end() || !std::isfinite(pooled->second.pooled)) continue;
      const fitting::PooledEstimate& e = pooled->second;
      bands[p] += fmt::format("set object rect from {},{} to {},{} fc rgb '#ff7f0e' fs transparent solid 0.2 noborder "
                              "behind\nset arrow from {},{} to {},{} nohead lc rgb '#ff7f0e' lw 2\n",
                              x1, e.interval_95[0], x2, e.interval_95[1], x1, e.pooled, x2, e.pooled);
    }
  }
  std::string body = fmt::format("set multiplot layout 5,1 title {} font ',13'\n",
                                 GnuplotString(fmt::format("Fitted parameters per trial ({} fits) with 95 % intervals; "
                                                           "lines join a block and position, bands: its pooled range",
                                                           rows.size())));
  body += fmt::format("set xrange [0.5:{}]\nset grid lc rgb '#dddddd'\nset lmargin 12\nset rmargin 3\nset key off\nset offsets 0, 0, graph 0.08, graph 0.08\n",
                      rows.size() + 0.5);
  for (int p = 0; p < 5; ++p) {
    body += fmt::format("set ylabel {}\n", GnuplotString(labels[p]));
    body += p == 4 ? fmt::format("set xtics ({}) rotate by 45 right font ',8'\n", xtics) : "set xtics 1 format ''\n";
    body += "unset object\nunset arrow\n" + bands[static_cast<std::size_t>(p)];
    const int c = 3 * p + 2;
    body += fmt::format("plot {0} using 1:{1} with lines lc rgb '#1f77b4', {0} using 1:{1}:{2}:{3} with yerrorbars "
                        "pt 7 ps 0.8 lc rgb '#1f77b4'\n",
                        data, c, c + 1, c + 2);
  }
  body += "unset multiplot\n";
  figure.Render(body, cmd.picture.output, cmd.picture.width_px, cmd.picture.height_px);
  if (cmd.picture.json) {
    nlohmann::json j = PictureJson("parameters", cmd.picture);
    j["fits"] = rows.size();
    PrintJson(j);
  } else {
    std::cout << "written " << cmd.picture.output << " (" << rows.size() << " fits)\n";
  }
  return kExitOk;
}

const CommandRegistration kRegistration([](CLI::App& root) {
  CLI::App& plot = PlotApp(root);
  auto fit = std::make_shared<PlotFitCommand>();
  CLI::App* a = plot.add_subcommand("fit", "Measured ω (dots) and simulated ω (lines) of one fit, impacts marked (Fig. 14)");
  a->add_option("FITS", fit->path, "HDF5 file written by `rockfit fit -o` or `rockfit batch`")->required();
  a->add_option("--trial", fit->trial, "Trial id under /fits (needed when the file holds several)");
  AddPictureOptions(*a, fit->picture, 1200, 900);
  a->callback([fit] { SetExitCode(RunPlotFit(*fit)); });

  auto params = std::make_shared<PlotParametersCommand>();
  CLI::App* b = plot.add_subcommand(
      "parameters", "Fitted α, λ, λ_lat, λ_lon (with 95 % intervals) and ε per trial, by block and position, with each "
                    "group's pooled range (Fig. 15)");
  b->add_option("FITS", params->path, "HDF5 file written by `rockfit batch` or `rockfit fit -o`")->required();
  AddPictureOptions(*b, params->picture, 1200, 1200);
  b->callback([params] { SetExitCode(RunPlotParameters(*params)); });
});

}  // namespace

std::vector<std::string> ParameterLines(const std::vector<std::string>& names, const std::vector<std::string>& units,
                                        const std::vector<double>& values, const std::vector<bool>& fixed,
                                        const std::vector<double>& lower_95, const std::vector<double>& upper_95) {
  std::vector<std::string> lines;
  auto end = [](double v) { return std::isnan(v) ? std::string("open") : fmt::format("{:.4g}", v); };
  for (std::size_t k = 0; k < names.size() && k < values.size(); ++k) {
    if (k < fixed.size() && fixed[k]) continue;
    const std::string unit = k < units.size() && units[k] != "1" ? " " + units[k] : "";
    lines.push_back(fmt::format("{} = {:.5g}{} [{}, {}]", names[k], values[k], unit,
                                k < lower_95.size() ? end(lower_95[k]) : "?", k < upper_95.size() ? end(upper_95[k]) : "?"));
  }
  return lines;
}

void RenderFitPlot(const FitPlotData& d, const std::filesystem::path& output, int width_px, int height_px) {
  GnuplotFigure figure;
  std::vector<std::vector<double>> columns(7);
  for (std::size_t i = 0; i < d.t_s.size(); ++i) {
    columns[0].push_back(d.t_s[i]);
    for (int c = 0; c < 3; ++c) {
      columns[static_cast<std::size_t>(c) + 1].push_back(d.w_measured_B[i][c]);
      columns[static_cast<std::size_t>(c) + 4].push_back(i < d.w_simulated_B.size() ? d.w_simulated_B[i][c]
                                                                                     : std::nan(""));
    }
  }
  const std::string data = figure.AddData("omega", columns);
  std::string marks;
  for (std::size_t i = 0; i < d.impact_t_s.size(); ++i) {
    const bool facet = i < d.impact_kind.size() && d.impact_kind[i] == core::ImpactKind::kFacet;
    marks += fmt::format("set arrow from {0},graph 0 to {0},graph 1 nohead lc rgb '{1}' dt {2}\n", d.impact_t_s[i],
                         facet ? "#555555" : "#bbbbbb", facet ? 1 : 3);
  }
  std::string body = fmt::format("set multiplot layout 3,1 title {} font ',13'\n",
                                 GnuplotString(fmt::format("Fit of trial {}     ε = {:.4g} rad/s     impacts: facet "
                                                           "(solid), edge (dotted)", d.trial, d.epsilon_rad_s)));
  body += "set grid lc rgb '#dddddd'\nset lmargin 10\nset rmargin 3\nset key top right font ',9'\n" + marks;
  if (!d.parameter_lines.empty()) {
    // One line per parameter, top left of the first panel (the block is at rest there before the release).
    std::string text = "95 % intervals";
    for (const std::string& l : d.parameter_lines) text += "\\n" + l;  // a newline inside a double-quoted string
    body += fmt::format("set label 1 \"{}\" at graph 0.01, graph 0.95 left front font ',8' noenhanced\n", text);
  }
  for (int c = 0; c < 3; ++c) {
    body += fmt::format("set ylabel '{} [rad/s]'\n", kComponent[c]);
    body += c == 2 ? "set xlabel 't [s]'\n" : "";
    body += fmt::format("plot {0} using 1:{1} with points pt 7 ps 0.4 lc rgb '{3}' title 'measured', {0} using 1:{2} "
                        "with lines lw 1.5 lc rgb '#000000' title 'simulated'\n",
                        data, c + 2, c + 5, kColours[c]);
    if (c == 0) body += "unset label 1\n";  // drawn once, under the title
  }
  body += "unset multiplot\n";
  figure.Render(body, output, width_px, height_px);
}

}  // namespace rockfit::tools
