// `rockfit plot response`: ground acceleration, tilt and angular velocity against time from the HDF5 file of
// `rockfit respond --format hdf5 -o FILE` (layout in io/trajectory_hdf5.hpp), impacts and uplifts marked.
#include <iostream>
#include <limits>

#include <fmt/format.h>

#include "cli_common.hpp"
#include "command_registry.hpp"
#include "rockfit/app/gnuplot.hpp"
#include "plot_command.hpp"
#include "rockfit/core/errors.hpp"
#include "rockfit/core/ground_motion.hpp"
#include "rockfit/core/simulator.hpp"
#include "rockfit/io/hdf5_file.hpp"
#include "rockfit/io/trajectory_hdf5.hpp"

namespace rockfit::tools {
namespace {

struct ResponsePlotCommand {
  std::string path;
  PictureArgs picture;
};

int RunPlotResponse(const ResponsePlotCommand& cmd) {
  const io::hdf5::File file = io::hdf5::File::Open(cmd.path);
  const io::hdf5::Group root = file.Root();
  // Schema 2 names its datasets with units (time_s, tilt_rad, …); files of schema 1 (`schema_version` 1) did not.
  const std::optional<std::int64_t> version = root.GetInt("rockfit_schema_version");
  if (version && *version > io::kTrajectorySchemaVersion) {
    throw BadInput(fmt::format("{}: schema version {} of a newer rockfit (this one reads up to {}); update rockfit",
                               cmd.path, *version, io::kTrajectorySchemaVersion));
  }
  const bool named_with_units = version.has_value();
  const auto name = [named_with_units](const char* with_units, const char* without) {
    return std::string(named_with_units ? with_units : without);
  };
  if (!root.IsGroup("ground_motion") || !root.IsDataset(name("samples/tilt_rad", "samples/tilt"))) {
    throw BadInput(cmd.path + ": no /ground_motion and /samples/tilt_rad; this plot reads the file of `rockfit respond "
                              "--format hdf5 -o FILE`");
  }
  const std::vector<double> t = root.ReadDoubles(name("samples/time_s", "samples/t"));
  const std::vector<Eigen::Vector3d> a = root.ReadVectors(name("samples/a_g_W_m_s2", "samples/a_g_W"));
  const std::vector<double> tilt = root.ReadDoubles(name("samples/tilt_rad", "samples/tilt"));
  const std::vector<Eigen::Vector3d> w = root.ReadVectors(name("samples/w_B_rad_s", "samples/w_B"));
  const std::vector<double> tg = root.ReadDoubles(name("ground_motion/time_s", "ground_motion/t"));
  const std::vector<Eigen::Vector3d> ag = root.ReadVectors(name("ground_motion/a_W_m_s2", "ground_motion/a_W"));
  const std::vector<double> impact_t = root.ReadDoubles(name("impacts/t_s", "impacts/t"));
  const std::vector<std::string> impact_kind = root.ReadStrings("impacts/kind");
  const std::string end_reason = root.GetString("end_reason", "result").value_or("?");
  const double critical = root.GetDouble("critical_tilt_rad", "response").value_or(0.0);

  std::vector<std::vector<double>> ground(4), samples(5), impacts(2), uplifts(2);
  for (std::size_t k = 0; k < tg.size(); ++k) {
    ground[0].push_back(tg[k]);
    for (int i = 0; i < 3; ++i) ground[1 + i].push_back(ag[k][i] / core::kRecordGravity);
  }
  for (std::size_t k = 0; k < t.size() && k < tilt.size(); ++k) {
    samples[0].push_back(t[k]);
    samples[1].push_back(tilt[k]);
    for (int i = 0; i < 3; ++i) samples[2 + i].push_back(w[k][i]);
  }
  for (std::size_t k = 0; k < impact_t.size(); ++k) {
    // Impacts and uplifts only: not the rest and Zeno records, nor a kind this version does not know.
    core::ImpactKind kind = core::ImpactKind::kRest;
    const bool known = core::FromString(impact_kind[k], &kind);
    if (!known || kind == core::ImpactKind::kRest || kind == core::ImpactKind::kZeno) continue;
    auto& into = kind == core::ImpactKind::kUplift ? uplifts : impacts;
    into[0].push_back(impact_t[k]);
    into[1].push_back(0.0);
  }
  double t_end = samples[0].empty() ? 1.0 : samples[0].back();
  if (!tg.empty()) t_end = std::max(t_end, tg.back());

  GnuplotFigure figure;
  const std::string g = figure.AddData("ground", ground);
  const std::string s = figure.AddData("samples", samples);
  const std::string im = figure.AddData("impacts", impacts);
  const std::string up = figure.AddData("uplifts", uplifts);
  std::string body;
  body += fmt::format("set multiplot layout 3,1 title {} font ',13'\n",
                      GnuplotString(fmt::format("Response to ground motion: {} ({} impacts)", end_reason, impacts[0].size())));
  body += fmt::format("set xrange [0:{}]\nset grid lc rgb '#dddddd'\nset key outside right top vertical Left reverse "
                      "font ',9'\nset lmargin 10\nset rmargin 22\nset format x ''\n", t_end);
  body += "set ylabel 'a_g [g]'\nset title '(a) ground acceleration' offset 0,-0.6\n";
  body += fmt::format("plot {0} using 1:2 with lines lc rgb '#d62728' title 'x', {0} using 1:3 with lines lc rgb '#1f77b4' "
                      "title 'y', {0} using 1:4 with lines lc rgb '#2ca02c' title 'z'\n", g);
  body += "set ylabel 'tilt [rad]'\nset title '(b) tilt of the block' offset 0,-0.6\n";
  std::string marks;
  if (!impacts[0].empty()) marks += fmt::format(", {} using 1:2 with points pt 2 ps 0.6 lc rgb '#000000' title 'impacts'", im);
  if (!uplifts[0].empty()) marks += fmt::format(", {} using 1:2 with points pt 9 ps 0.9 lc rgb '#9467bd' title 'uplift'", up);
  const std::string critical_line =
      critical > 0.0 ? fmt::format(", {} with lines dt 2 lc rgb '#555555' title 'critical tilt'", critical) : "";
  body += fmt::format("plot {0} using 1:2 with lines lc rgb '#000000' title 'tilt'{1}{2}\n", s, critical_line, marks);
  body += "set ylabel 'ω_B [rad/s]'\nset title '(c) angular velocity' offset 0,-0.6\nset xlabel 't [s]'\nset format x '%g'\n";
  body += fmt::format("plot {0} using 1:3 with lines lc rgb '#d62728' title 'ω_x', {0} using 1:4 with lines lc rgb "
                      "'#1f77b4' title 'ω_y', {0} using 1:5 with lines lc rgb '#2ca02c' title 'ω_z'\n", s);
  body += "unset multiplot\n";
  figure.Render(body, cmd.picture.output, cmd.picture.width_px, cmd.picture.height_px);
  return ReportPicture("response", cmd.picture, {{"end_reason", end_reason}, {"impacts", impacts[0].size()}, {"uplifts", uplifts[0].size()}});
}

const CommandRegistration kRegistration([](CLI::App& root) {
  CLI::App& plot = PlotApp(root);
  auto cmd = std::make_shared<ResponsePlotCommand>();
  CLI::App* r = plot.add_subcommand(
      "response", "Ground acceleration, tilt and ω against time, with impacts and uplifts, from the HDF5 file of "
                  "`rockfit respond --format hdf5 -o FILE`.");
  r->add_option("PATH", cmd->path, "HDF5 file written by rockfit respond")->required();
  AddPictureOptions(*r, cmd->picture, 1100, 900);
  r->footer("Exit codes: 0 written; 1 bad arguments; 2 unreadable input; 4 cannot write the picture, or gnuplot is "
            "missing (apt-get install gnuplot-nox).");
  r->callback([cmd] { SetExitCode(RunPlotResponse(*cmd)); });
});

}  // namespace
}  // namespace rockfit::tools
