// `rockfit plot fragility`: the fragility curves of a study (`rockfit fragility -o FILE`, /fragility in
// docs/file-formats.md): per block and limit state the observed probabilities with their 95 % Clopper–Pearson band
// and the fitted lognormal curve Φ(ln(x/θ)/β).
#include <algorithm>
#include <cmath>
#include <iostream>

#include <fmt/format.h>

#include "cli_common.hpp"
#include "command_registry.hpp"
#include "rockfit/app/gnuplot.hpp"
#include "rockfit/app/report_inputs.hpp"
#include "plot_command.hpp"
#include "rockfit/core/errors.hpp"
#include "rockfit/io/hdf5_file.hpp"

namespace rockfit::tools {
namespace {

struct FragilityPlotCommand {
  std::string path;
  std::string limit_states;  // empty: all
  PictureArgs picture;
};

const char* kPalette[] = {"#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#8c564b", "#e377c2", "#ff7f0e", "#17becf"};
const char* kDashes[] = {"1", "2", "4", "5", "3"};

int RunPlotFragility(const FragilityPlotCommand& cmd) {
  ImageFormatFor(cmd.picture.output);
  const io::hdf5::File file = io::hdf5::File::Open(cmd.path);
  const io::hdf5::Group root = file.Root();
  if (!root.IsGroup("fragility/blocks")) {
    throw BadInput(cmd.path + ": no /fragility/blocks; this plot reads the file of `rockfit fragility -o FILE`");
  }
  const io::hdf5::Group f = root.OpenGroup("fragility");
  const bool pga = f.GetString("intensity_measure").value_or("pga_g") == "pga_g";
  const std::vector<std::string> ids = f.ReadStrings("blocks/id");
  const std::vector<std::string> wanted = SplitList(cmd.limit_states);

  GnuplotFigure figure;
  std::vector<std::string> plots;
  double x_max = 0.0;
  std::size_t curves = 0, style = 0;
  for (std::size_t b = 0; b < ids.size(); ++b) {
    const io::hdf5::Group g = f.OpenGroup("blocks/" + ids[b]);
    const std::vector<double> x = g.ReadDoubles("intensity");
    const std::vector<std::string> states = g.ReadStrings("limit_state_names");
    for (double v : x) x_max = std::max(x_max, v);
    for (std::size_t s = 0; s < states.size(); ++s) {
      if (!wanted.empty() && std::find(wanted.begin(), wanted.end(), states[s]) == wanted.end()) continue;
      const io::hdf5::Group ls = g.OpenGroup("limit_states/" + states[s]);
      const std::vector<double> p = ls.ReadDoubles("probability");
      const std::vector<double> lo = ls.ReadDoubles("clopper_pearson_95_lower");
      const std::vector<double> hi = ls.ReadDoubles("clopper_pearson_95_upper");
      const std::string data = figure.AddData(fmt::format("b{}_s{}", b, s), {x, p, lo, hi});
      const char* colour = kPalette[style % 8];
      const char* dash = kDashes[s % 5];
      ++style;
      // "tilt_0.5" → "peak tilt ≥ 0.5 θ_c" (θ_c with a subscript in gnuplot's enhanced text).
      const std::string state = states[s].rfind("tilt_", 0) == 0 ? "peak tilt ≥ " + states[s].substr(5) + " θ_c" : states[s];
      const std::string label = ids.size() > 1 ? ids[b] + ": " + state : state;
      plots.push_back(fmt::format("{} using 1:3:4 with filledcurves fs transparent solid 0.15 noborder lc rgb '{}' notitle",
                                  data, colour));
      plots.push_back(fmt::format("{} using 1:2:3:4 with yerrorbars pt 7 ps 0.8 lc rgb '{}' title {}", data, colour,
                                  GnuplotString(label + " (95 % Clopper–Pearson)")));
      const std::string status = ls.ReadStrings("curve/status").at(0);
      const double median = ls.ReadDoubles("curve/median").at(0), beta = ls.ReadDoubles("curve/beta").at(0);
      if (CurveStatusIsOk(status, ls.file_name() + ": " + ls.path() + "/curve/status")) {
        plots.push_back(fmt::format("norm(log(x/{})/{}) with lines lw 2 dt {} lc rgb '{}' title {}", median, beta, dash,
                                    colour, GnuplotString(fmt::format("lognormal θ = {:.3g}, β = {:.2f}", median, beta))));
        ++curves;
      }
    }
  }
  if (plots.empty()) throw InvalidArgument("--limit-state names none of the study's limit states");
  std::string body;
  body += fmt::format("set title {} font ',12'\n", GnuplotString(fmt::format("Fragility: {}", cmd.path)));
  body += fmt::format("set xlabel {}\nset ylabel 'probability'\nset yrange [-0.02:1.02]\nset xrange [0:{}]\n",
                      GnuplotString(pga ? "peak horizontal ground acceleration [g]" : "scale factor of the records"),
                      1.1 * x_max);
  body += "set grid lc rgb '#dddddd'\nset key bottom right font ',9' box opaque\nset samples 400\n";
  std::string joined;
  for (const std::string& p : plots) joined += (joined.empty() ? "" : ", ") + p;
  body += "plot " + joined + "\n";
  figure.Render(body, cmd.picture.output, cmd.picture.width_px, cmd.picture.height_px);
  return ReportPicture("fragility", cmd.picture, {{"blocks", ids}, {"curves", curves}});
}

const CommandRegistration kRegistration([](CLI::App& root) {
  CLI::App& plot = PlotApp(root);
  auto cmd = std::make_shared<FragilityPlotCommand>();
  CLI::App* r = plot.add_subcommand(
      "fragility", "Fragility curves from the HDF5 file of `rockfit fragility -o FILE`: observed probabilities with "
                   "their 95 % Clopper–Pearson band and the fitted lognormal curve, per block and limit state.");
  r->add_option("PATH", cmd->path, "HDF5 file written by rockfit fragility")->required();
  r->add_option("--limit-state", cmd->limit_states, "Only these limit states (overturning, tilt_0.5, …; comma list)")
      ->group("Output");
  AddPictureOptions(*r, cmd->picture, 1000, 650);
  r->footer("Exit codes: 0 written; 1 bad arguments; 2 unreadable input; 4 cannot write the picture, or gnuplot is "
            "missing (apt-get install gnuplot-nox).");
  r->callback([cmd] { SetExitCode(RunPlotFragility(*cmd)); });
});

}  // namespace
}  // namespace rockfit::tools
