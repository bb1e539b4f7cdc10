// `rockfit plot validation FILE`: the figure of the predictive check from /validation (plot_validation.hpp).
#include "plot_validation.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "cli_common.hpp"
#include "command_registry.hpp"
#include "rockfit/app/gnuplot.hpp"
#include "plot_command.hpp"
#include "rockfit/fitting/validation_store.hpp"
#include "rockfit/io/hdf5_file.hpp"

namespace rockfit::tools {

void RenderValidationPlot(const fitting::ValidationSummary& s, const std::filesystem::path& output, int width_px,
                          int height_px) {
  ImageFormatFor(output);
  // Trials in group order (stable: the manifest's order within a group), one x position each.
  std::vector<const fitting::TrialPrediction*> order;
  for (const fitting::TrialPrediction& t : s.trials) order.push_back(&t);
  std::stable_sort(order.begin(), order.end(), [](const auto* a, const auto* b) {
    return std::tie(a->block, a->position) < std::tie(b->block, b->position);
  });
  std::vector<double> x, overlap, apart;
  std::string xtics;
  std::vector<double> separators;
  double y_max = s.options.ratio_warning;
  for (std::size_t i = 0; i < order.size(); ++i) {
    const fitting::TrialPrediction& t = *order[i];
    x.push_back(static_cast<double>(i));
    const double r = t.predicted ? t.ratio : std::nan("");
    overlap.push_back(t.overlaps_all ? r : std::nan(""));
    apart.push_back(t.overlaps_all ? std::nan("") : r);
    if (std::isfinite(r)) y_max = std::max(y_max, r);
    xtics += fmt::format("{}{} {}", xtics.empty() ? "" : ", ", GnuplotString(t.trial), i);
    if (i > 0 && std::tie(t.block, t.position) != std::tie(order[i - 1]->block, order[i - 1]->position)) {
      separators.push_back(static_cast<double>(i) - 0.5);
    }
  }
  GnuplotFigure figure;
  const std::string data = figure.AddData("ratios", {x, overlap, apart});
  std::string body;
  body += fmt::format("set title {} font ',12'\n",
                      GnuplotString("Predictive check: ε_{pred}/ε_{own} with the others' pooled λ, λ_{lat}, λ_{lon}"));
  body += "set ylabel 'ε_{pred} / ε_{own}'\nset grid ytics lc rgb '#dddddd'\n";
  body += fmt::format("set xrange [-0.5:{}]\nset yrange [0:{}]\n", static_cast<double>(order.size()) - 0.5, 1.15 * y_max);
  body += "set xtics rotate by -45 font ',8' (" + xtics + ")\n";
  for (double sx : separators) body += fmt::format("set arrow from {0},graph 0 to {0},graph 1 nohead lc rgb '#999999' dt 2\n", sx);
  body += "set key top left font ',9' box opaque\n";
  body += fmt::format("plot 1 with lines lc rgb '#555555' title 'ε_{{pred}} = ε_{{own}}', {} with lines dt 2 lc rgb '#d62728' "
                      "title {}, {} using 1:2 with points pt 7 ps 1.3 lc rgb '#2ca02c' title 'own 95 % intervals overlap "
                      "the pooled ones', {} using 1:3 with points pt 6 ps 1.3 lw 2 lc rgb '#d62728' title 'they do not "
                      "(λ, λ_{{lat}} or λ_{{lon}})'\n",
                      s.options.ratio_warning, GnuplotString(fmt::format("warning ratio {:g}", s.options.ratio_warning)),
                      data, data);
  figure.Render(body, output, width_px, height_px);
}

namespace {

struct ValidationPlotCommand {
  std::string path;
  PictureArgs picture;
};

const CommandRegistration kRegistration([](CLI::App& root) {
  CLI::App& plot = PlotApp(root);
  auto cmd = std::make_shared<ValidationPlotCommand>();
  CLI::App* r = plot.add_subcommand(
      "validation", "The predictive check from the HDF5 file of `rockfit validate -o FILE`: ε_pred/ε_own per trial, "
                    "grouped by block and position, marked where the intervals overlap the pooled ones.");
  r->add_option("PATH", cmd->path, "HDF5 file written by rockfit validate")->required();
  AddPictureOptions(*r, cmd->picture, 1000, 600);
  r->footer("Exit codes: 0 written; 1 bad arguments; 2 unreadable input; 4 cannot write the picture, or gnuplot is "
            "missing (apt-get install gnuplot-nox).");
  r->callback([cmd] {
    ImageFormatFor(cmd->picture.output);
    const io::hdf5::File file = io::hdf5::File::Open(cmd->path);
    const fitting::ValidationSummary s = fitting::ReadValidationGroup(file.Root());
    RenderValidationPlot(s, cmd->picture.output, cmd->picture.width_px, cmd->picture.height_px);
    SetExitCode(ReportPicture("validation", cmd->picture, {{"trials", s.trials.size()}}));
  });
});

}  // namespace
}  // namespace rockfit::tools
