// `rockfit plot euler` (raw and corrected Euler angles of one trial, the paper's Fig. 5) and `rockfit plot
// summary` (OPMF and AVRF mean ± std against b2 per position, Fig. 6), drawn with gnuplot (gnuplot.hpp).
#include <algorithm>
#include <cmath>
#include <iostream>
#include <limits>
#include <map>

#include <fmt/format.h>

#include "rockfit/app/campaign_run.hpp"
#include "cli_common.hpp"
#include "command_registry.hpp"
#include "rockfit/app/gnuplot.hpp"
#include "rockfit/app/metrics_options.hpp"
#include "rockfit/app/output_kind.hpp"
#include "plot_command.hpp"
#include "rockfit/app/recording_input.hpp"
#include "rockfit/core/errors.hpp"
#include "rockfit/io/campaign_hdf5.hpp"

namespace rockfit::tools {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
// Time shown before the first and after the last impact by default [s].
constexpr double kMarginAroundImpacts_s = 0.5;

// Colours of the three axes in every panel (x red, y blue, z green) and of the impact marks.
const char* kColourX = "#d62728";
const char* kColourY = "#1f77b4";
const char* kColourZ = "#2ca02c";
const char* kColourImpacts = "#000000";

// ---------------------------------------------------------------- plot euler

struct EulerCommand {
  RecordingArgs input;
  BlockArgs block;
  MetricsArgs metrics;
  PictureArgs picture;
  std::optional<double> from_s;
  std::optional<double> to_s;
};

// What the Euler figure shows, from a stored trial or computed now.
struct EulerData {
  std::string trial_id;
  std::vector<double> t;
  std::vector<Eigen::Vector3d> w;
  std::vector<Eigen::Vector3d> raw;        // (φz, φy, φx)
  std::vector<Eigen::Vector3d> corrected;
  std::vector<double> impact_times;
  std::optional<double> opmf, avrf;
};

// Linear interpolation of samples y(t) at time x (t increasing).
double Interpolate(const std::vector<double>& t, const std::vector<double>& y, double x) {
  if (t.empty()) return kNaN;
  if (x <= t.front()) return y.front();
  if (x >= t.back()) return y.back();
  const std::size_t k = static_cast<std::size_t>(std::upper_bound(t.begin(), t.end(), x) - t.begin());
  const double f = (x - t[k - 1]) / (t[k] - t[k - 1]);
  return y[k - 1] + f * (y[k] - y[k - 1]);
}

EulerData EulerDataFor(const EulerCommand& cmd) {
  const TrialInput input = LoadTrialInput(cmd.input);
  EulerData d;
  d.trial_id = input.trial_id;
  d.t = input.recording.t_s;
  d.w = input.recording.w_B;
  if (input.stored) {  // what the file holds
    d.raw = input.recording.euler_zyx;
    d.corrected = input.stored->euler_corrected_zyx;
    d.impact_times = input.stored->impact_times_s;
    d.opmf = input.stored->opmf;
    d.avrf = input.stored->avrf;
    return d;
  }
  std::optional<core::Block> block = MakeOptionalBlock(cmd.block);
  if (!block && input.manifest_block) block = input.manifest_block->ToBlock();
  const io::MetricsSummary m = io::ComputeTrialMetrics(input.recording, block, MakeMetricsOptions(cmd.metrics));
  d.raw = m.correction.euler_raw_zyx;
  d.corrected = m.correction.euler_corrected_zyx;
  for (const auto& a : m.correction.impacts_y) d.impact_times.push_back(a.t_s);
  if (m.opmf.ok()) d.opmf = m.opmf.opmf;
  if (m.avrf.ok()) d.avrf = m.avrf.avrf;
  return d;
}

int RunPlotEuler(const EulerCommand& cmd) {
  ImageFormatFor(cmd.picture.output);  // reject a wrong extension before any work
  const EulerData d = EulerDataFor(cmd);
  if (d.t.empty()) throw BadInput("the recording has no samples");
  double from = d.t.front(), to = d.t.back();
  if (!d.impact_times.empty()) {
    from = std::max(from, d.impact_times.front() - kMarginAroundImpacts_s);
    to = std::min(to, d.impact_times.back() + kMarginAroundImpacts_s);
  }
  if (cmd.from_s) from = *cmd.from_s;
  if (cmd.to_s) to = *cmd.to_s;
  if (!(to > from)) throw InvalidArgument(fmt::format("--from {} must be before --to {}", from, to));

  // φz has no reference in IMU mode (no magnetometer): shown relative to its value at the start of the window.
  std::size_t first = static_cast<std::size_t>(std::lower_bound(d.t.begin(), d.t.end(), from) - d.t.begin());
  if (first >= d.t.size()) throw InvalidArgument(fmt::format("--from {} s is after the end of the recording", from));
  const double yaw0_raw = d.raw[first][0], yaw0_corrected = d.corrected[first][0];
  std::vector<std::vector<double>> columns(12);
  for (std::size_t i = first; i < d.t.size() && d.t[i] <= to; ++i) {
    const double values[12] = {d.t[i],
                               d.w[i].x(),
                               d.w[i].y(),
                               d.w[i].z(),
                               d.raw[i][0] - yaw0_raw,
                               d.raw[i][1],
                               d.raw[i][2],
                               d.corrected[i][0] - yaw0_corrected,
                               d.corrected[i][1],
                               d.corrected[i][2],
                               d.raw[i][1] - d.corrected[i][1],
                               d.raw[i][2] - d.corrected[i][2]};
    for (int c = 0; c < 12; ++c) columns[c].push_back(values[c]);
  }
  // Impacts: on ω_y, on the raw φ_y (where the drift line passes) and at zero on the corrected φ_y.
  std::vector<double> wy, raw_y, drift_y;
  for (std::size_t i = 0; i < d.t.size(); ++i) {
    wy.push_back(d.w[i].y());
    raw_y.push_back(d.raw[i][1]);
    drift_y.push_back(d.raw[i][1] - d.corrected[i][1]);
  }
  std::vector<std::vector<double>> marks(4);
  for (double t : d.impact_times) {
    if (t < from || t > to) continue;
    marks[0].push_back(t);
    marks[1].push_back(Interpolate(d.t, wy, t));
    marks[2].push_back(Interpolate(d.t, drift_y, t));
    marks[3].push_back(0.0);
  }

  GnuplotFigure figure;
  const std::string data = figure.AddData("angles", columns);
  const std::string impacts = figure.AddData("impacts", marks);
  std::string title = "Trial " + d.trial_id;
  title += d.opmf ? fmt::format("     OPMF = {:.3f}", *d.opmf) : std::string("     OPMF = –");
  title += d.avrf ? fmt::format("     AVRF = {:.3f}", *d.avrf) : std::string("     AVRF = –");
  const bool have_marks = !marks[0].empty();
  const std::string impacts_y = have_marks ? fmt::format(
      ", {} using 1:2 with points pt 2 ps 0.7 lc rgb '{}' title 'impacts'", impacts, kColourImpacts) : "";
  const std::string impacts_raw = have_marks ? fmt::format(
      ", {} using 1:3 with points pt 7 ps 0.5 lc rgb '{}' title 'φ_y at the impacts'", impacts, kColourImpacts) : "";
  const std::string impacts_zero = have_marks ? fmt::format(
      ", {} using 1:4 with points pt 2 ps 0.7 lc rgb '{}' title 'impacts'", impacts, kColourImpacts) : "";

  std::string body;
  body += fmt::format("set multiplot layout 3,1 title {} font ',13'\n", GnuplotString(title));
  // Fixed margins keep the three time axes aligned; the keys sit in the right margin.
  body += fmt::format("set xrange [{}:{}]\nset grid lc rgb '#dddddd'\nset key outside right top vertical Left reverse font ',9' "
                      "samplen 2 spacing 1.1\nset lmargin 10\nset rmargin 25\nset format x ''\n", from, to);
  body += "set ylabel 'ω [rad/s]'\nset title '(a) angular velocity' offset 0,-0.6\n";
  body += fmt::format("plot {0} using 1:2 with lines lc rgb '{1}' title 'ω_x', {0} using 1:3 with lines lc rgb '{2}' "
                      "title 'ω_y', {0} using 1:4 with lines lc rgb '{3}' title 'ω_z'{4}\n",
                      data, kColourX, kColourY, kColourZ, impacts_y);
  body += "set ylabel 'Euler angles [rad]'\nset title '(b) measured Euler angles, ZYX' offset 0,-0.6\n";
  body += fmt::format("plot {0} using 1:7 with lines lc rgb '{1}' title 'φ_x', {0} using 1:6 with lines lc rgb '{2}' "
                      "title 'φ_y', {0} using 1:5 with lines lc rgb '{3}' title 'φ_z − φ_z(t_0)', {0} using 1:11 with "
                      "lines dt 2 lc rgb '#555555' title 'drift of φ_y'{4}\n",
                      data, kColourX, kColourY, kColourZ, impacts_raw);
  body += "set ylabel 'Euler angles [rad]'\nset title '(c) corrected Euler angles' offset 0,-0.6\n";
  body += "set xlabel 't [s]'\nset format x '%g'\n";
  body += fmt::format("plot {0} using 1:10 with lines lc rgb '{1}' title 'φ_x', {0} using 1:9 with lines lc rgb '{2}' "
                      "title 'φ_y', {0} using 1:8 with lines lc rgb '{3}' title 'φ_z − φ_z(t_0)'{4}\n",
                      data, kColourX, kColourY, kColourZ, impacts_zero);
  body += "unset multiplot\n";
  figure.Render(body, cmd.picture.output, cmd.picture.width_px, cmd.picture.height_px);

  return ReportPicture("euler", cmd.picture, {{"trial", d.trial_id},
               {"from_s", from},
               {"to_s", to},
               {"impacts", marks[0].size()}});
}

// ---------------------------------------------------------------- plot summary

struct SummaryPlotCommand {
  std::string path;
  MetricsArgs metrics;
  PictureArgs picture;
};

io::CampaignSummary SummaryFor(const SummaryPlotCommand& cmd) {
  if (LowerCaseExtension(cmd.path) == ".toml") {
    const CampaignRun run = RunCampaign(io::ReadManifest(cmd.path), MakeMetricsOptions(cmd.metrics));
    for (const io::TrialRow& t : run.summary.trials) {
      if (t.status == io::MetricsStatus::kLoadError) std::cerr << "rockfit: warning: trial " << t.trial_id << " left out: " << t.message << "\n";
    }
    return run.summary;
  }
  return io::ReadSummaryHdf5(cmd.path);
}

int RunPlotSummary(const SummaryPlotCommand& cmd) {
  ImageFormatFor(cmd.picture.output);
  const io::CampaignSummary summary = SummaryFor(cmd);
  std::vector<std::string> positions;
  for (const io::GroupRow& g : summary.groups) {
    if (std::find(positions.begin(), positions.end(), g.position) == positions.end()) positions.push_back(g.position);
  }
  std::sort(positions.begin(), positions.end());
  if (positions.empty()) throw BadInput(cmd.path + ": the summary has no groups to plot");
  double b2_min = std::numeric_limits<double>::infinity(), b2_max = -b2_min;
  for (const io::GroupRow& g : summary.groups) b2_min = std::min(b2_min, g.b2_m), b2_max = std::max(b2_max, g.b2_m);
  const double b2_span_cm = std::max(1.0, 100.0 * (b2_max - b2_min));
  // Positions side by side around each b2, so that their error bars do not overlap.
  const double offset_cm = 0.025 * b2_span_cm;

  GnuplotFigure figure;
  const char* palette[] = {kColourY, kColourX, kColourZ, "#9467bd", "#8c564b", "#e377c2"};
  std::vector<std::string> opmf_plots, avrf_plots;
  for (std::size_t p = 0; p < positions.size(); ++p) {
    std::vector<std::vector<double>> group_columns(5), trial_columns(3);
    const double shift = offset_cm * (static_cast<double>(p) - 0.5 * static_cast<double>(positions.size() - 1));
    for (const io::GroupRow& g : summary.groups) {
      if (g.position != positions[p]) continue;
      group_columns[0].push_back(100.0 * g.b2_m + shift);
      group_columns[1].push_back(g.opmf_mean.value_or(kNaN));
      group_columns[2].push_back(g.opmf_mean ? g.opmf_std.value_or(0.0) : kNaN);
      group_columns[3].push_back(g.avrf_mean.value_or(kNaN));
      group_columns[4].push_back(g.avrf_mean ? g.avrf_std.value_or(0.0) : kNaN);
    }
    for (const io::TrialRow& t : summary.trials) {
      if (t.position != positions[p]) continue;
      trial_columns[0].push_back(100.0 * t.b2_m + shift);
      trial_columns[1].push_back(t.opmf.value_or(kNaN));
      trial_columns[2].push_back(t.avrf.value_or(kNaN));
    }
    // Sort the groups by b2 so that the connecting line runs left to right.
    std::vector<std::size_t> order(group_columns[0].size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return group_columns[0][a] < group_columns[0][b]; });
    std::vector<std::vector<double>> sorted(5);
    for (std::size_t c = 0; c < 5; ++c) {
      for (std::size_t i : order) sorted[c].push_back(group_columns[c][i]);
    }
    const std::string groups = figure.AddData(fmt::format("groups_{}", p), sorted);
    const std::string trials = figure.AddData(fmt::format("trials_{}", p), trial_columns);
    const char* colour = palette[p % 6];
    const std::string label = GnuplotString("position " + positions[p]);
    opmf_plots.push_back(fmt::format("{} using 1:2 with points pt 6 ps 0.5 lc rgb '{}' notitle", trials, colour));
    opmf_plots.push_back(fmt::format("{} using 1:2:3 with yerrorlines pt 7 ps 1.1 lw 1.5 lc rgb '{}' title {}", groups,
                                     colour, label));
    avrf_plots.push_back(fmt::format("{} using 1:3 with points pt 6 ps 0.5 lc rgb '{}' notitle", trials, colour));
    avrf_plots.push_back(fmt::format("{} using 1:4:5 with yerrorlines pt 7 ps 1.1 lw 1.5 lc rgb '{}' title {}", groups,
                                     colour, label));
  }
  const auto join = [](const std::vector<std::string>& parts) {
    std::string out;
    for (const auto& p : parts) out += (out.empty() ? "" : ", ") + p;
    return out;
  };
  std::string body;
  body += "set multiplot layout 1,2 title 'Mean ± standard deviation per block and position (dots: single trials)' "
          "font ',12'\n";
  body += fmt::format("set grid lc rgb '#dddddd'\nset xlabel 'b_2 [cm]'\nset xrange [{}:{}]\nset key top right font ',10' "
                      "box opaque\nset offsets 0, 0, graph 0.05, graph 0.05\n",
                      100.0 * b2_min - 0.08 * b2_span_cm, 100.0 * b2_max + 0.08 * b2_span_cm);
  // Φ ≥ 0 by definition: its axis starts at 0.
  body += "set title '(a) out-of-plane motion factor'\nset ylabel 'OPMF Φ = max|φ_x| / max|φ_y|'\nset yrange [0:*]\n";
  body += "plot " + join(opmf_plots) + "\n";
  body += "set title '(b) angular velocity reduction factor'\nset ylabel 'AVRF r'\nset yrange [*:*]\n";
  body += "plot " + join(avrf_plots) + "\n";
  body += "unset multiplot\n";
  figure.Render(body, cmd.picture.output, cmd.picture.width_px, cmd.picture.height_px);

  return ReportPicture("summary", cmd.picture, {{"groups", summary.groups.size()},
               {"positions", positions}});
}

const CommandRegistration kRegistration([](CLI::App& root) {
  CLI::App& plot = PlotApp(root);

  auto euler = std::make_shared<EulerCommand>();
  CLI::App* e = plot.add_subcommand(
      "euler",
      "Angular velocity, measured and corrected Euler angles of one trial with the detected impacts, OPMF and AVRF in "
      "the title (the paper's Fig. 5). PATH is a recording (corrected now) or rockfit's HDF5 (as stored).");
  AddRecordingOptions(*e, euler->input);
  AddPictureOptions(*e, euler->picture, 1000, 900);
  e->add_option("--from", euler->from_s, "Start of the time window [s] (default: 0.5 s before the first impact)")
      ->group("Output");
  e->add_option("--to", euler->to_s, "End of the time window [s] (default: 0.5 s after the last impact)")->group("Output");
  AddBlockOptions(*e, euler->block);
  AddMetricsOptions(*e, euler->metrics);
  e->footer("The block (optional) gives the AVRF in the title. Exit codes: 0 written; 1 bad arguments; 2 unreadable "
            "input; 4 cannot write the picture, or gnuplot is missing (apt-get install gnuplot-nox).");
  e->callback([euler] { SetExitCode(RunPlotEuler(*euler)); });

  auto summary = std::make_shared<SummaryPlotCommand>();
  CLI::App* s = plot.add_subcommand(
      "summary",
      "OPMF and AVRF, mean ± sample standard deviation per block and position against b2 (the paper's Fig. 6). PATH "
      "is an HDF5 file written by `rockfit summary -o` or a campaign manifest (computed now).");
  s->add_option("PATH", summary->path, "rockfit HDF5 with /summary, or a campaign manifest (.toml)")->required();
  AddPictureOptions(*s, summary->picture, 1200, 520);
  AddMetricsOptions(*s, summary->metrics);
  s->footer("Exit codes: 0 written; 1 bad arguments; 2 unreadable input; 4 cannot write the picture, or gnuplot is "
            "missing (apt-get install gnuplot-nox).");
  s->callback([summary] { SetExitCode(RunPlotSummary(*summary)); });
});

}  // namespace
}  // namespace rockfit::tools
