// `rockfit plot regions`: the facet-impact regions of the paper's Fig. 11 — post-impact contact or status over
// (λ_lat, λ_lon), the region (27), the energy bound (26) and the singular curves of (18).
#include <array>
#include <cmath>
#include <iostream>
#include <map>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <Eigen/Geometry>
#include <fmt/format.h>

#include "cli_common.hpp"
#include "command_registry.hpp"
#include "rockfit/app/gnuplot.hpp"
#include "plot_command.hpp"
#include "rockfit/core/errors.hpp"
#include "rockfit/core/facet_impact_regions.hpp"

namespace rockfit::tools {
namespace {

struct RegionsCommand {
  BlockArgs block;
  std::string pivot_edge = "1,2";
  std::string omega_minus;  // empty: 1 rad/s in the falling direction of the pivot edge
  std::optional<double> tau;
  std::string lat_range = "-2,2";
  std::string lon_range = "-2,2";
  int points = 201;
  PictureArgs picture;
};

// "MIN,MAX" → the two numbers; InvalidArgument naming the option.
std::array<double, 2> ParseRange(const std::string& text, const std::string& option) {
  std::stringstream stream(text);
  std::string cell;
  std::vector<double> values;
  while (std::getline(stream, cell, ',')) {
    char* end = nullptr;
    const double v = std::strtod(cell.c_str(), &end);
    if (cell.empty() || end == cell.c_str() || *end != '\0' || !std::isfinite(v)) {
      values.clear();
      break;
    }
    values.push_back(v);
  }
  if (values.size() != 2 || !(values[0] < values[1])) {
    throw InvalidArgument(option + " expects MIN,MAX with MIN < MAX (e.g. " + option + "=-2,2), got '" + text + "'");
  }
  return {values[0], values[1]};
}

// The background colour of each label, in the order of the key.
struct RegionStyle {
  const char* label;
  const char* colour;
};
constexpr RegionStyle kStyles[] = {
    {"V1", "#66c2a5"},   {"V2", "#e78ac3"},   {"V3", "#3f7fcf"},         {"V4", "#f39c34"},
    {"V1V2", "#8c6d31"}, {"V2V3", "#9467bd"}, {"V3V4", "#1a9a1a"},       {"V4V1", "#17becf"},
    {"rest", "#000000"}, {"infeasible", "#d4d4d4"}, {"ambiguous", "#d62728"}, {"singular", "#4d4d4d"},
};
// ω⁻ counts as "not falling" when V_{b+1} moves down slower than this × |ω⁻|·L (L = COM to vertex); the same
// fraction as the warnings of `rockfit impact facet`. Dimensionless.
constexpr double kFallingRelTol = 1e-9;
// Cells where the energy grows (ΔE > 0) are drawn in the colour mixed with this much white.
constexpr double kPaleWhiteFraction = 0.6;

std::array<double, 3> Rgb(const char* hex) {
  const unsigned long v = std::strtoul(hex + 1, nullptr, 16);
  return {double((v >> 16) & 0xff), double((v >> 8) & 0xff), double(v & 0xff)};
}

std::string FormatNumber(double v) { return fmt::format("{:g}", v); }

int RunPlotRegions(const RegionsCommand& cmd) {
  const core::Block block = MakeBlock(cmd.block);
  const int b = ParsePivotEdge(cmd.pivot_edge);
  const Eigen::Vector3d falling_B = (block.p_BV_B(b) - block.p_BV_B(b - 1)).normalized();  // core/README.md
  core::FacetRegionOptions options;
  options.pivot_b = b;
  options.w_minus_B = cmd.omega_minus.empty() ? falling_B : ParseVector3(cmd.omega_minus, "--omega-minus");
  options.tau_rule = cmd.tau ? core::FacetTauRule::kFixed : core::FacetTauRule::kNoSpin;
  options.tau = cmd.tau.value_or(0.0);
  const auto lat = ParseRange(cmd.lat_range, "--lat-range");
  const auto lon = ParseRange(cmd.lon_range, "--lon-range");
  options.lambda_lat_min = lat[0];
  options.lambda_lat_max = lat[1];
  options.lambda_lon_min = lon[0];
  options.lambda_lon_max = lon[1];
  options.n_lat = options.n_lon = cmd.points;
  if (cmd.points < 2 || cmd.points > core::kFacetRegionMaxPoints) {
    throw InvalidArgument(fmt::format("--points must be between 2 and {}, got {}", core::kFacetRegionMaxPoints, cmd.points));
  }
  ImageFormatFor(cmd.picture.output);  // reject a bad extension before the work
  // As `rockfit impact facet`: an ω⁻ that does not bring V_{b+1} down makes every cell infeasible.
  const Eigen::Vector3d& w_B = options.w_minus_B;
  const double velocity_scale = w_B.norm() * (block.p_BC_B() - block.p_BV_B(b)).norm();
  if (w_B.cross(block.p_BV_B(b + 1) - block.p_BV_B(b)).z() >= -kFallingRelTol * velocity_scale) {
    std::cerr << fmt::format("rockfit: warning: with this ω⁻ the base does not fall onto the ground about V{}V{}; in "
                             "rockfit's frame a falling block has ω⁻ = +ω·({:+.3g}, {:+.3g}, {:+.3g}), ω > 0 (the "
                             "paper's Fig. 11 writes [0, −1, 0] for V1V2 in its own axes; see core/README.md)\n",
                             core::Block::WrapVertex(b - 1), b, falling_B.x(), falling_B.y(), falling_B.z());
  }
  const core::FacetRegionGrid grid = core::EvaluateFacetRegions(block, options);

  // Background: one RGB pixel per grid point, pale where ΔE > 0.
  std::map<std::string, std::size_t> counts;
  std::size_t energy_gain = 0;
  std::vector<std::vector<double>> image(5);
  for (std::size_t j = 0; j < grid.lambda_lon.size(); ++j) {
    for (std::size_t i = 0; i < grid.lambda_lat.size(); ++i) {
      const core::FacetRegionCell& cell = grid.at(static_cast<int>(i), static_cast<int>(j));
      const std::string label = core::FacetRegionLabel(cell);
      ++counts[label];
      const char* colour = "#ffffff";
      for (const auto& style : kStyles) {
        if (label == style.label) colour = style.colour;
      }
      std::array<double, 3> rgb = Rgb(colour);
      const bool gain = cell.has_energy && cell.delta_energy_J > 0.0;
      if (gain) {
        ++energy_gain;
        for (double& c : rgb) c = c + kPaleWhiteFraction * (255.0 - c);
      }
      image[0].push_back(grid.lambda_lat[i]);
      image[1].push_back(grid.lambda_lon[j]);
      for (int c = 0; c < 3; ++c) image[2 + c].push_back(std::round(rgb[c]));
    }
  }

  GnuplotFigure figure;
  const std::string image_file = figure.AddData("regions", image);
  const auto add_lines = [&](const std::string& name, const std::vector<core::ContourSegment>& segments) {
    std::vector<std::vector<double>> columns(2);
    std::vector<std::size_t> starts;
    for (const auto& line : core::ChainSegments(segments)) {
      starts.push_back(columns[0].size());
      for (const auto& p : line) {
        columns[0].push_back(p.x());
        columns[1].push_back(p.y());
      }
    }
    return columns[0].empty() ? std::string() : figure.AddData(name, columns, starts);
  };
  const std::string energy_file = add_lines("energy", grid.energy_zero);
  const std::string singular_file = add_lines("singular", grid.singular);

  const Eigen::Vector3d& w = options.w_minus_B;
  const std::string tau_text = cmd.tau ? fmt::format("τ = {} N·m·s", FormatNumber(*cmd.tau)) : "τ from (24), no spin";
  // Two lines in a double-quoted gnuplot string (for the \n); the text holds no quote or backslash.
  const std::string title = fmt::format(
      "\"Facet impact after rocking about V{}V{}:  ω^- = ({}, {}, {}) rad/s,  {}\\nb_1 = {} m, b_2 = {} m, h = {} m, "
      "m = {} kg\"",
      core::Block::WrapVertex(b - 1), b, FormatNumber(w.x()), FormatNumber(w.y()), FormatNumber(w.z()), tau_text,
      FormatNumber(block.b1()), FormatNumber(block.b2()), FormatNumber(block.h()), FormatNumber(block.mass()));

  std::string body;
  body += fmt::format("set title {} font ',11'\n", title);
  body += fmt::format("set xrange [{}:{}]\nset yrange [{}:{}]\n", lat[0], lat[1], lon[0], lon[1]);
  body += "set xlabel 'λ_{lat}'\nset ylabel 'λ_{lon}'\nset size ratio -1\nset tics out\n";
  body += "set key outside right top vertical Left reverse samplen 2 spacing 1.2 font ',10'\nset rmargin 24\n";
  // (27): the dashed rectangle, clipped to the drawn range.
  body += "set object 1 rect from -1,-1 to 1,1 front fillstyle empty border lc rgb 'black' lw 2 dt 2 clip\n";
  std::string plot = fmt::format("plot {} using 1:2:3:4:5 with rgbimage notitle", image_file);
  for (const auto& style : kStyles) {
    if (counts.count(style.label)) {
      plot += fmt::format(", keyentry with boxes fs solid 1.0 border lc rgb '#666666' fc rgb '{}' title '{}'", style.colour,
                          style.label);
    }
  }
  if (energy_gain > 0) plot += ", keyentry with boxes fs solid 1.0 border lc rgb '#666666' fc rgb '#f2f2f2' title 'pale: ΔE > 0'";
  if (!energy_file.empty()) plot += fmt::format(", {} using 1:2 with lines lw 2.5 lc rgb 'black' title 'ΔE = 0 (26)'", energy_file);
  if (!singular_file.empty()) {
    plot += fmt::format(", {} using 1:2 with lines lw 2 dt 4 lc rgb '#7a0177' title '(18) singular'", singular_file);
  }
  plot += ", keyentry with lines lw 2 dt 2 lc rgb 'black' title 'region (27)'\n";
  body += plot;
  figure.Render(body, cmd.picture.output, cmd.picture.width_px, cmd.picture.height_px);

  nlohmann::json cells = nlohmann::json::object();
  for (const auto& [label, n] : counts) cells[label] = n;
  if (cmd.picture.json) {
    nlohmann::json j = PictureJson("regions", cmd.picture);
    j.update({{"pivot_edge", fmt::format("V{}V{}", core::Block::WrapVertex(b - 1), b)},
               {"omega_minus", ToJson(w)},
               {"tau_rule", core::ToString(options.tau_rule)},
               {"tau", cmd.tau ? nlohmann::json(*cmd.tau) : nlohmann::json(nullptr)},
               {"lambda_lat_range", {lat[0], lat[1]}},
               {"lambda_lon_range", {lon[0], lon[1]}},
               {"points", cmd.points},
               {"cells", cells},
               {"cells_energy_gain", energy_gain},
               {"energy_zero_segments", grid.energy_zero.size()},
               {"singular_segments", grid.singular.size()}});
    PrintJson(j);
  } else {
    std::cout << "written " << cmd.picture.output << "\n";
    for (const auto& [label, n] : counts) std::cout << fmt::format("  {:<11} {:>7} cells\n", label, n);
    std::cout << fmt::format("  ΔE > 0      {:>7} cells\n", energy_gain);
  }
  return kExitOk;
}

const CommandRegistration kRegistration([](CLI::App& root) {
  CLI::App& plot = PlotApp(root);
  auto cmd = std::make_shared<RegionsCommand>();
  CLI::App* r = plot.add_subcommand(
      "regions",
      "Facet-impact regions over (λ_lat, λ_lon) (the paper's Fig. 11): the contact after the impact (V1..V4, an edge "
      "such as V3V4, rest) or the status (infeasible, ambiguous, singular) as background colours, pale where the "
      "energy grows; the region (27) dashed, ΔE = 0 of (26) solid, singular curves of (18) dash-dotted.");
  AddBlockOptions(*r, cmd->block);
  r->add_option("--pivot-edge", cmd->pivot_edge,
                "Pre-impact pivot edge I,J of neighbouring vertices, taken in cyclic order as V_{b−1}V_b")
      ->capture_default_str()
      ->group("Impact");
  r->add_option("--omega-minus", cmd->omega_minus,
                "Pre-impact angular velocity X,Y,Z in B [rad/s] (default: 1 rad/s falling about the pivot edge, "
                "(0,1,0) for 1,2; the paper's [0,−1,0] in rockfit's axes, see core/README.md)")
      ->group("Impact");
  r->add_option("--tau", cmd->tau,
                "Fixed vertical angular impulse τ [N·m·s] (Fig. 11b,c); omitted: the unified no-spin map (24) (Fig. 11a)")
      ->group("Impact");
  r->add_option("--lat-range", cmd->lat_range, "λ_lat range MIN,MAX (horizontal axis)")
      ->capture_default_str()
      ->group("Grid");
  r->add_option("--lon-range", cmd->lon_range, "λ_lon range MIN,MAX (vertical axis)")->capture_default_str()->group("Grid");
  r->add_option("--points", cmd->points, "Grid points per axis (ends included)")->capture_default_str()->group("Grid");
  AddPictureOptions(*r, cmd->picture, 900, 720);
  r->footer("Exit codes: 0 written; 1 bad arguments; 2 unreadable manifest; 4 cannot write the picture, or gnuplot is "
            "missing (apt-get install gnuplot-nox). Infeasible or ambiguous cells are results, not errors.");
  r->callback([cmd] { SetExitCode(RunPlotRegions(*cmd)); });
});

}  // namespace
}  // namespace rockfit::tools
