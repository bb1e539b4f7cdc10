// `rockfit plot fit` (Fig. 14) and `rockfit plot parameters` (Fig. 15).
#include "plot_fit.hpp"

#include <algorithm>
#include <cmath>
#include <iostream>
#include <limits>
#include <map>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "cli_common.hpp"
#include "command_registry.hpp"
#include "gnuplot.hpp"
#include "plot_command.hpp"
#include "rockfit/core/errors.hpp"
#include "rockfit/io/hdf5_file.hpp"

namespace rockfit::tools {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
const char* kColourMeasured = "#1f77b4";
const char* kColourSimulated = "#d62728";
const char* kColourFacet = "#000000";
const char* kColourEdge = "#999999";

std::string Caption(const std::string& trial, double epsilon, const std::vector<std::pair<std::string, double>>& values) {
  std::string text = fmt::format("Trial {}:", trial);
  for (const auto& [name, value] : values) {
    if (name == "tau_edge") continue;
    const std::string symbol = name == "alpha" ? "α" : name == "lambda" ? "λ" : name == "lambda_lat" ? "λ_{lat}"
                               : name == "lambda_lon" ? "λ_{lon}" : name == "t0" ? "t_0" : name;
    text += fmt::format("  {} = {:.4g}{}", symbol, value, name == "t0" ? " s" : name == "alpha" ? " rad" : "");
  }
  return text + fmt::format("    ε = {:.4g} rad/s", epsilon);
}

// ---------------------------------------------------------------- plot fit

struct PlotFitCommand {
  std::string path;
  std::string trial_id;
  PictureArgs picture;
};

int RunPlotFit(const PlotFitCommand& cmd) {
  ImageFormatFor(cmd.picture.output);
  const io::hdf5::File file = io::hdf5::File::Open(cmd.path);
  std::string trial = cmd.trial_id;
  const std::vector<std::string> stored = fitting::ListFitsHdf5(file.Root());
  if (trial.empty()) {
    if (stored.size() != 1) {
      std::string list;
      for (const std::string& s : stored) list += (list.empty() ? "" : ", ") + s;
      throw InvalidArgument(fmt::format("{} holds {} fits: say which with --trial ID (one of: {})", cmd.path,
                                        stored.size(), list.empty() ? "none" : list));
    }
    trial = stored.front();
  }
  const fitting::StoredFit fit = fitting::ReadFitHdf5(file.Root(), trial);
  if (fit.status != "ok") throw BadInput(fmt::format("{}: trial {} failed to fit: {}", cmd.path, trial, fit.message));
  RenderFitFigure(FitFigureFrom(fit), cmd.picture.output, cmd.picture.width_px, cmd.picture.height_px);
  if (cmd.picture.json) {
    PrintJson({{"kind", "fit"}, {"output", cmd.picture.output}, {"trial", trial},
               {"format", ImageFormatFor(cmd.picture.output) == ImageFormat::kPng ? "png" : "svg"},
               {"width_px", cmd.picture.width_px}, {"height_px", cmd.picture.height_px}});
  } else {
    std::cout << "written " << cmd.picture.output << "\n";
  }
  return kExitOk;
}

// ---------------------------------------------------------------- plot parameters

struct PlotParametersCommand {
  std::string path;
  PictureArgs picture;
};

int RunPlotParameters(const PlotParametersCommand& cmd) {
  ImageFormatFor(cmd.picture.output);
  const io::hdf5::File file = io::hdf5::File::Open(cmd.path);
  std::vector<fitting::StoredFit> fits;
  for (const std::string& id : fitting::ListFitsHdf5(file.Root())) {
    fitting::StoredFit f = fitting::ReadFitHdf5(file.Root(), id);
    if (f.status == "ok") fits.push_back(std::move(f));
  }
  if (fits.empty()) {
    throw BadInput(fmt::format("{}: no successful fit under /fits; run `rockfit batch MANIFEST -o {}` first", cmd.path,
                               cmd.path));
  }
  // Blocks along x in order of b2 (the paper's blocks differ in depth), positions side by side.
  std::vector<std::pair<double, std::string>> blocks;
  std::vector<std::string> positions;
  for (const auto& f : fits) {
    if (std::none_of(blocks.begin(), blocks.end(), [&](const auto& b) { return b.second == f.labels.block_id; })) {
      blocks.emplace_back(f.labels.b2_m, f.labels.block_id);
    }
    if (std::find(positions.begin(), positions.end(), f.labels.position) == positions.end()) {
      positions.push_back(f.labels.position);
    }
  }
  std::sort(blocks.begin(), blocks.end());
  std::sort(positions.begin(), positions.end());
  const char* names[] = {"alpha", "lambda", "lambda_lat", "lambda_lon"};
  const char* labels[] = {"α [rad]", "λ (edge)", "λ_{lat}", "λ_{lon}"};
  const char* palette[] = {"#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#8c564b", "#e377c2"};

  GnuplotFigure figure;
  std::string body = "set multiplot layout 2,2 title 'Fitted parameters per block and position' font ',13'\n";
  // Margins above and below the points, so that none sits on the frame; the key in an opaque box.
  body += "set grid lc rgb '#dddddd'\nset key top left font ',9' opaque box\nset offsets 0, 0, graph 0.12, graph 0.06\n";
  std::string xtics = "set xtics (";
  for (std::size_t b = 0; b < blocks.size(); ++b) xtics += fmt::format("{}'{}' {}", b ? ", " : "", blocks[b].second, b + 1);
  body += xtics + ")\n";
  body += fmt::format("set xrange [0.5:{}]\nset xlabel 'block (by b_2)'\n", blocks.size() + 0.5);
  std::size_t points = 0;
  for (int panel = 0; panel < 4; ++panel) {
    std::vector<std::string> plots;
    for (std::size_t p = 0; p < positions.size(); ++p) {
      const double shift = 0.15 * (static_cast<double>(p) - 0.5 * static_cast<double>(positions.size() - 1));
      std::vector<std::vector<double>> columns(2);
      for (const auto& f : fits) {
        if (f.labels.position != positions[p]) continue;
        const auto it = std::find_if(blocks.begin(), blocks.end(), [&](const auto& b) { return b.second == f.labels.block_id; });
        const std::size_t i = std::find(f.names.begin(), f.names.end(), names[panel]) - f.names.begin();
        if (i >= f.names.size() || f.fixed[i]) continue;
        columns[0].push_back(static_cast<double>(it - blocks.begin()) + 1.0 + shift);
        columns[1].push_back(f.value[i]);
        ++points;
      }
      if (columns[0].empty()) continue;
      const std::string data = figure.AddData(fmt::format("p{}_{}", panel, p), columns);
      plots.push_back(fmt::format("{} using 1:2 with points pt 7 ps 0.8 lc rgb '{}' title {}", data,
                                  palette[p % 6], GnuplotString("position " + positions[p])));
    }
    body += fmt::format("set ylabel {}\n", GnuplotString(labels[panel]));
    body += plots.empty() ? std::string("set label 1 'not fitted' at graph 0.5, 0.5 center\nplot NaN notitle\nunset label 1\n")
                          : "plot " + [&] {
                              std::string joined;
                              for (const std::string& s : plots) joined += (joined.empty() ? "" : ", ") + s;
                              return joined;
                            }() + "\n";
  }
  body += "unset multiplot\n";
  figure.Render(body, cmd.picture.output, cmd.picture.width_px, cmd.picture.height_px);
  if (cmd.picture.json) {
    PrintJson({{"kind", "parameters"}, {"output", cmd.picture.output}, {"trials", fits.size()},
               {"blocks", blocks.size()}, {"positions", positions}, {"points", points},
               {"format", ImageFormatFor(cmd.picture.output) == ImageFormat::kPng ? "png" : "svg"},
               {"width_px", cmd.picture.width_px}, {"height_px", cmd.picture.height_px}});
  } else {
    std::cout << "written " << cmd.picture.output << "\n";
  }
  return kExitOk;
}

const CommandRegistration kRegistration([](CLI::App& root) {
  CLI::App& plot = PlotApp(root);
  {
    auto cmd = std::make_shared<PlotFitCommand>();
    CLI::App* app = plot.add_subcommand(
        "fit", "Measured (dots) and simulated (lines) angular velocity of a fitted trial with its impacts (Fig. 14)");
    app->add_option("PATH", cmd->path, "HDF5 file written by `rockfit fit -o` or `rockfit batch`")->required();
    app->add_option("--trial", cmd->trial_id, "Trial id (needed when the file holds several fits)");
    AddPictureOptions(*app, cmd->picture, 1200, 900);
    app->callback([cmd] { SetExitCode(RunPlotFit(*cmd)); });
  }
  {
    auto cmd = std::make_shared<PlotParametersCommand>();
    CLI::App* app = plot.add_subcommand("parameters", "Fitted α, λ, λ_lat, λ_lon per block and position (Fig. 15)");
    app->add_option("PATH", cmd->path, "HDF5 file written by `rockfit batch`")->required();
    AddPictureOptions(*app, cmd->picture, 1200, 900);
    app->callback([cmd] { SetExitCode(RunPlotParameters(*cmd)); });
  }
});

}  // namespace

FitFigureData FitFigureFrom(const fitting::StoredFit& fit) {
  FitFigureData d;
  d.trial_id = fit.trial_id;
  d.t_s = fit.time_s;
  d.w_measured_B = fit.w_measured_B;
  d.w_simulated_B = fit.w_simulated_B;
  d.impact_t_s = fit.impact_time_s;
  d.impact_kind = fit.impact_kind;
  std::vector<std::pair<std::string, double>> values;
  for (std::size_t i = 0; i < fit.names.size(); ++i) values.emplace_back(fit.names[i], fit.value[i]);
  d.caption = Caption(fit.trial_id, fit.epsilon_rad_s, values);
  return d;
}

FitFigureData FitFigureFrom(const fitting::TrialFit& fit, const std::string& trial_id) {
  FitFigureData d;
  d.trial_id = trial_id;
  d.t_s = fit.trace.t_s;
  for (double t : fit.trace.t_s) d.w_measured_B.push_back(fit.signal.Interpolate(t));
  d.w_simulated_B = fit.trace.w_B;
  for (const fitting::ModelEvent& e : fit.trace.events) {
    d.impact_t_s.push_back(e.t_s);
    d.impact_kind.push_back(e.kind);
  }
  std::vector<std::pair<std::string, double>> values;
  for (fitting::ParameterId id : fitting::kAllParameters) values.emplace_back(fitting::Name(id), fit.summary.parameters.value(id));
  d.caption = Caption(trial_id, fit.summary.epsilon_rad_s, values);
  return d;
}

void RenderFitFigure(const FitFigureData& d, const std::filesystem::path& output, int width_px, int height_px) {
  ImageFormatFor(output);
  if (d.t_s.empty()) throw BadInput("the fit has no samples to draw (the model failed at the fitted parameters)");
  std::vector<std::vector<double>> columns(7);
  for (std::size_t i = 0; i < d.t_s.size(); ++i) {
    columns[0].push_back(d.t_s[i]);
    for (int c = 0; c < 3; ++c) {
      columns[1 + c].push_back(d.w_measured_B[i][c]);
      columns[4 + c].push_back(i < d.w_simulated_B.size() ? d.w_simulated_B[i][c] : kNaN);
    }
  }
  std::vector<std::vector<double>> facets(1), edges(1);
  for (std::size_t i = 0; i < d.impact_t_s.size(); ++i) (d.impact_kind[i] == "facet" ? facets : edges)[0].push_back(d.impact_t_s[i]);
  GnuplotFigure figure;
  const std::string data = figure.AddData("fit", columns);
  const std::string facet_data = facets[0].empty() ? "" : figure.AddData("facet", facets);
  const std::string edge_data = edges[0].empty() ? "" : figure.AddData("edge", edges);
  std::string body = fmt::format("set multiplot layout 3,1 title {} font ',12'\n", GnuplotString(d.caption));
  body += fmt::format("set xrange [{}:{}]\nset grid lc rgb '#dddddd'\nset key outside right top font ',9'\n"
                      "set lmargin 10\nset rmargin 22\nset format x ''\n", d.t_s.front(), d.t_s.back());
  const char* axis[] = {"x", "y", "z"};
  for (int c = 0; c < 3; ++c) {
    if (c == 2) body += "set xlabel 't [s]'\nset format x '%g'\n";
    body += fmt::format("set ylabel 'ω_{} [rad/s]'\n", axis[c]);
    std::string marks;
    // Impacts as thin vertical lines across the panel: facet impacts black, edge impacts grey.
    if (!facet_data.empty()) {
      marks += fmt::format(", {} using 1:(0):(0):(1) axes x1y2 with vectors nohead lc rgb '{}' lw 1 title 'facet impacts'",
                           facet_data, kColourFacet);
    }
    if (!edge_data.empty()) {
      marks += fmt::format(", {} using 1:(0):(0):(1) axes x1y2 with vectors nohead dt 3 lc rgb '{}' title 'edge impacts'",
                           edge_data, kColourEdge);
    }
    body += "set y2range [0:1]\nunset y2tics\n";
    body += fmt::format("plot {0} using 1:{1} with points pt 6 ps 0.6 lc rgb '{2}' title 'measured', "
                        "{0} using 1:{3} with lines lw 2 lc rgb '{4}' title 'simulated'{5}\n",
                        data, 2 + c, kColourMeasured, 5 + c, kColourSimulated, marks);
  }
  body += "unset multiplot\n";
  figure.Render(body, output, width_px, height_px);
}

}  // namespace rockfit::tools
