// `rockfit ground-motion`: read ground-motion records (header values, peak accelerations) and write generated
// Clough–Penzien records as PEER AT2 files, for samples and studies without external records.
#include <cmath>
#include <iostream>

#include <fmt/format.h>

#include "cli_common.hpp"
#include "command_registry.hpp"
#include "rockfit/app/ground_motion_args.hpp"
#include "rockfit/core/checks.hpp"
#include "rockfit/core/errors.hpp"
#include "rockfit/core/ground_motion.hpp"
#include "rockfit/io/atomic_file.hpp"
#include "rockfit/io/peer_at2.hpp"
#include "rockfit/io/stochastic_ground_motion.hpp"
#include "rockfit/app/run_limits.hpp"

namespace rockfit::tools {
namespace {

struct InspectCommand {
  std::vector<std::string> paths;
  bool json = false;
};

struct SynthCommand {
  io::CloughPenzienOptions options;
  double pga_g = 0.3;
  std::string output;
  bool json = false;
};

int RunInspect(const InspectCommand& cmd) {
  nlohmann::json records = nlohmann::json::array();
  if (!cmd.json) std::cout << fmt::format("{:<40} {:>7} {:>9} {:>10} {:>9} {:>10}\n", "record", "NPTS", "DT [s]", "duration", "PGA [g]", "at [s]");
  for (const std::string& path : cmd.paths) {
    const io::PeerRecord r = io::ReadPeerAt2(path);
    std::size_t at = 0;
    for (std::size_t k = 0; k < r.accel_g.size(); ++k) {
      if (std::abs(r.accel_g[k]) > std::abs(r.accel_g[at])) at = k;
    }
    const double duration = static_cast<double>(r.npts - 1) * r.dt_s;
    if (cmd.json) {
      records.push_back({{"path", path}, {"npts", r.npts}, {"dt_s", r.dt_s}, {"duration_s", duration},
                         {"pga_g", r.PeakAbs_g()}, {"pga_m_s2", r.PeakAbs_g() * core::kRecordGravity},
                         {"t_pga_s", static_cast<double>(at) * r.dt_s}, {"header", r.header_lines}});
    } else {
      std::cout << fmt::format("{:<40} {:>7} {:>9} {:>10.2f} {:>9.4f} {:>10.3f}\n", path, r.npts, r.dt_s, duration,
                               r.PeakAbs_g(), static_cast<double>(at) * r.dt_s);
    }
  }
  if (cmd.json) PrintJson({{"records", records}});
  return kExitOk;
}

int RunSynth(SynthCommand& cmd) {
  RequirePositive(cmd.pga_g, "--pga", "g");
  cmd.options.pga_m_s2 = cmd.pga_g * core::kRecordGravity;
  const std::vector<double> a = io::CloughPenzienRecord(cmd.options);
  io::PeerRecord record;
  const io::CloughPenzienOptions& o = cmd.options;
  record.header_lines = {
      "ROCKFIT GROUND-MOTION GENERATOR: CLOUGH-PENZIEN FILTERED WHITE NOISE, JENNINGS ENVELOPE",
      fmt::format("SEED {} WG={} ZG={} WF={} ZF={} T1={} T2={} C={}", o.seed, o.omega_g_rad_s, o.zeta_g, o.omega_f_rad_s,
                  o.zeta_f, o.t_rise_s, o.t_strong_end_s, o.decay_per_s),
      fmt::format("ACCELERATION TIME HISTORY IN UNITS OF G. PGA {} G", cmd.pga_g)};
  record.dt_s = o.dt_s;
  for (double v : a) record.accel_g.push_back(v / core::kRecordGravity);
  record.npts = record.accel_g.size();
  const std::string text = io::FormatPeerAt2(record);
  io::WriteFileAtomically(cmd.output, [&text](std::ostream& out) { out << text; });
  if (cmd.json) {
    PrintJson({{"output", cmd.output}, {"npts", record.npts}, {"dt_s", record.dt_s}, {"pga_g", record.PeakAbs_g()},
               {"seed", o.seed}});
  } else {
    std::cout << fmt::format("written {} ({} points at {} s, PGA {:.4f} g)\n", cmd.output, record.npts, record.dt_s,
                             record.PeakAbs_g());
  }
  return kExitOk;
}

const CommandRegistration kRegistration([](CLI::App& root) {
  CLI::App* gm = root.add_subcommand("ground-motion", "Ground-motion records: inspect AT2 files, generate records");
  gm->require_subcommand(1);
  gm->footer(LimitsHelp());

  auto inspect = std::make_shared<InspectCommand>();
  CLI::App* i = gm->add_subcommand("inspect", "NPTS, DT, duration and peak acceleration of PEER AT2 records");
  i->add_option("PATH", inspect->paths, "AT2 files")->required();
  i->add_flag("--json", inspect->json, "Print JSON: records (path, npts, dt_s, duration_s, pga_g, pga_m_s2, t_pga_s, header)");
  i->callback([inspect] { SetExitCode(RunInspect(*inspect)); });

  auto synth = std::make_shared<SynthCommand>();
  CLI::App* s = gm->add_subcommand(
      "synth", "Write a Clough–Penzien filtered white noise with a Jennings envelope as a PEER AT2 file "
               "(model and parameters: io/README.md, \"Stochastic ground motion\")");
  auto& o = synth->options;
  s->add_option("--seed", o.seed, "Random seed (the same seed gives the same file)")->capture_default_str();
  s->add_option("--pga", synth->pga_g, "Peak ground acceleration [g]")->capture_default_str();
  s->add_option("--duration", o.duration_s, "Duration [s]")->capture_default_str();
  s->add_option("--dt", o.dt_s, "Time step [s]")->capture_default_str();
  s->add_option("--omega-g", o.omega_g_rad_s, "Kanai–Tajimi ground frequency ω_g [rad/s]")->capture_default_str();
  s->add_option("--zeta-g", o.zeta_g, "Kanai–Tajimi damping ζ_g")->capture_default_str();
  s->add_option("--omega-f", o.omega_f_rad_s, "Clough–Penzien high-pass frequency ω_f [rad/s]")->capture_default_str();
  s->add_option("--zeta-f", o.zeta_f, "Clough–Penzien damping ζ_f")->capture_default_str();
  s->add_option("--t-rise", o.t_rise_s, "Envelope: end of the quadratic rise t_1 [s]")->capture_default_str();
  s->add_option("--t-strong", o.t_strong_end_s, "Envelope: end of the strong phase t_2 [s]")->capture_default_str();
  s->add_option("--decay", o.decay_per_s, "Envelope: exponential decay rate c [1/s]")->capture_default_str();
  s->add_option("-o,--output", synth->output, "Output AT2 file")->required();
  s->add_flag("--json", synth->json, "Print JSON: output, npts, dt_s, pga_g, seed");
  s->footer(LimitsHelp());
  s->callback([synth] { SetExitCode(RunSynth(*synth)); });
});

}  // namespace
}  // namespace rockfit::tools
