// `rockfit plot fit FITS.h5 --trial ID` (paper Fig. 14) and `rockfit plot parameters FITS.h5` (Fig. 15).
#include "plot_fit.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include <fmt/format.h>

#include "cli_common.hpp"
#include "command_registry.hpp"
#include "gnuplot.hpp"
#include "plot_command.hpp"
#include "rockfit/core/errors.hpp"
#include "rockfit/io/hdf5_file.hpp"

namespace rockfit::tools {
namespace {

const char* const kColours[3] = {"#d62728", "#1f77b4", "#2ca02c"};
const char* const kComponent[3] = {"ω_x", "ω_y", "ω_z"};

io::hdf5::Group OpenFits(const io::hdf5::File& file, const std::string& path) {
  const io::hdf5::Group root = file.Root();
  if (!root.IsGroup("fits") || root.OpenGroup("fits").Children().empty()) {
    throw BadInput(fmt::format("{}: no /fits group; write one with `rockfit fit ... -o {}` or `rockfit batch`", path, path));
  }
  return root.OpenGroup("fits");
}

FitPlotData ReadFitPlotData(const std::string& path, const std::string& trial) {
  const io::hdf5::File file = io::hdf5::File::Open(path);
  const io::hdf5::Group fits = OpenFits(file, path);
  std::string id = trial;
  if (id.empty()) {
    const std::vector<std::string> children = fits.Children();
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
  d.impact_kind = g.ReadStrings("impacts/kind");
  d.epsilon_rad_s = g.GetDouble("epsilon_rad_s").value_or(std::numeric_limits<double>::quiet_NaN());
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
  if (cmd.picture.json) {
    nlohmann::json j = PictureJson("fit", cmd.picture);
    j.update({{"trial", d.trial}, {"epsilon", d.epsilon_rad_s}});
    PrintJson(j);
  } else {
    std::cout << "written " << cmd.picture.output << "\n";
  }
  return kExitOk;
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
    std::map<std::string, double> value;
  };
  std::vector<Row> rows;
  for (const std::string& id : fits.Children()) {
    const io::hdf5::Group g = fits.OpenGroup(id);
    if (!g.IsGroup("parameters")) continue;
    Row r;
    r.trial = id;
    const std::string block = g.GetString("block").value_or("");
    const std::string position = g.GetString("position").value_or("");
    r.group = block.empty() ? "—" : block + " " + position;
    const std::vector<std::string> names = g.ReadStrings("parameters/name");
    const std::vector<double> values = g.ReadDoubles("parameters/value");
    for (std::size_t k = 0; k < names.size() && k < values.size(); ++k) r.value[names[k]] = values[k];
    r.value["epsilon"] = g.GetDouble("epsilon_rad_s").value_or(std::nan(""));
    rows.push_back(r);
  }
  std::stable_sort(rows.begin(), rows.end(), [](const Row& a, const Row& b) { return a.group < b.group; });
  const char* const panels[] = {"alpha", "lambda", "lambda_lat", "lambda_lon", "epsilon"};
  const char* const labels[] = {"α [rad]", "λ", "λ_{lat}", "λ_{lon}", "ε (28) [rad/s]"};
  GnuplotFigure figure;
  std::vector<std::vector<double>> columns(6);
  std::string xtics;
  std::vector<std::size_t> block_starts;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    if (i > 0 && rows[i].group != rows[i - 1].group) block_starts.push_back(i);
    columns[0].push_back(static_cast<double>(i + 1));
    for (int p = 0; p < 5; ++p) {
      const auto it = rows[i].value.find(panels[p]);
      columns[static_cast<std::size_t>(p) + 1].push_back(it == rows[i].value.end() ? std::nan("") : it->second);
    }
    xtics += fmt::format("{}{} {}", xtics.empty() ? "" : ", ", GnuplotString(rows[i].trial), i + 1);
  }
  const std::string data = figure.AddData("parameters", columns, block_starts);
  std::string body = fmt::format("set multiplot layout 5,1 title {} font ',13'\n",
                                 GnuplotString(fmt::format("Fitted parameters per trial ({} fits), lines join a block "
                                                           "and position", rows.size())));
  body += fmt::format("set xrange [0.5:{}]\nset grid lc rgb '#dddddd'\nset lmargin 12\nset rmargin 3\nset key off\nset offsets 0, 0, graph 0.08, graph 0.08\n",
                      rows.size() + 0.5);
  for (int p = 0; p < 5; ++p) {
    body += fmt::format("set ylabel {}\n", GnuplotString(labels[p]));
    body += p == 4 ? fmt::format("set xtics ({}) rotate by 45 right font ',8'\n", xtics) : "set xtics 1 format ''\n";
    body += fmt::format("plot {} using 1:{} with linespoints pt 7 ps 0.8 lc rgb '#1f77b4'\n", data, p + 2);
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
  CLI::App* b = plot.add_subcommand("parameters", "Fitted α, λ, λ_lat, λ_lon and ε per trial, by block and position (Fig. 15)");
  b->add_option("FITS", params->path, "HDF5 file written by `rockfit batch` or `rockfit fit -o`")->required();
  AddPictureOptions(*b, params->picture, 1200, 1200);
  b->callback([params] { SetExitCode(RunPlotParameters(*params)); });
});

}  // namespace

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
    const bool facet = i < d.impact_kind.size() && d.impact_kind[i] == "facet";
    marks += fmt::format("set arrow from {0},graph 0 to {0},graph 1 nohead lc rgb '{1}' dt {2}\n", d.impact_t_s[i],
                         facet ? "#555555" : "#bbbbbb", facet ? 1 : 3);
  }
  std::string body = fmt::format("set multiplot layout 3,1 title {} font ',13'\n",
                                 GnuplotString(fmt::format("Fit of trial {}     ε = {:.4g} rad/s     impacts: facet "
                                                           "(solid), edge (dotted)", d.trial, d.epsilon_rad_s)));
  body += "set grid lc rgb '#dddddd'\nset lmargin 10\nset rmargin 3\nset key top right font ',9'\n" + marks;
  for (int c = 0; c < 3; ++c) {
    body += fmt::format("set ylabel '{} [rad/s]'\n", kComponent[c]);
    body += c == 2 ? "set xlabel 't [s]'\n" : "";
    body += fmt::format("plot {0} using 1:{1} with points pt 7 ps 0.4 lc rgb '{3}' title 'measured', {0} using 1:{2} "
                        "with lines lw 1.5 lc rgb '#000000' title 'simulated'\n",
                        data, c + 2, c + 5, kColours[c]);
  }
  body += "unset multiplot\n";
  figure.Render(body, output, width_px, height_px);
}

}  // namespace rockfit::tools
