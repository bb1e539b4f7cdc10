#include "rockfit/app/ground_motion_args.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>

#include <fmt/format.h>

#include "rockfit/app/activity.hpp"
#include "rockfit/core/errors.hpp"
#include "rockfit/core/ground_motion.hpp"
#include "rockfit/io/ground_motion_csv.hpp"
#include "rockfit/io/peer_at2.hpp"

namespace rockfit::app {
namespace {

std::string Lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

bool IsCsv(const std::string& path, const std::string& format) {
  if (format == "csv") return true;
  if (format == "at2") return false;
  return Lower(std::filesystem::path(path).extension().string()) == ".csv";
}

io::RecordComponent FromPeer(const std::string& path, std::vector<std::string>* sources, const char* role) {
  const io::PeerRecord r = io::ReadPeerAt2(path);
  io::RecordComponent c;
  c.source = path;
  c.dt_s = r.dt_s;
  c.accel_m_s2.reserve(r.accel_g.size());
  for (double a : r.accel_g) c.accel_m_s2.push_back(core::kRecordGravity * a);
  sources->push_back(fmt::format("{} ({}): PEER AT2, NPTS {}, DT {} s, peak {:.4f} g", path, role, r.npts, r.dt_s,
                                 r.PeakAbs_g()));
  return c;
}

}  // namespace


LoadedGroundMotion LoadGroundMotion(const GroundMotionArgs& a) {
  if (a.csv_dt_s && !(*a.csv_dt_s > 0.0 && std::isfinite(*a.csv_dt_s))) {
    throw InvalidArgument(fmt::format("--dt must be a positive number of seconds (the step of a CSV record without a "
                                      "time column), got {}", *a.csv_dt_s));
  }
  const Activity activity(a.synthetic_seed ? fmt::format("generating a Clough–Penzien record of {} s at a step of {} s",
                                                         a.synthetic_duration_s, a.synthetic_dt_s)
                                           : "reading the ground motion " + a.record);
  LoadedGroundMotion out;
  io::GroundMotionAssembly assembly;
  if (a.synthetic_seed) {
    if (!a.record.empty()) throw InvalidArgument("give either --record or --synthetic, not both");
    io::CloughPenzienOptions o;
    o.seed = *a.synthetic_seed;
    o.duration_s = a.synthetic_duration_s;
    o.dt_s = a.synthetic_dt_s;
    io::RecordComponent c;
    c.source = "synthetic:" + std::to_string(o.seed);
    c.dt_s = o.dt_s;
    c.accel_m_s2 = io::CloughPenzienRecord(o);
    out.sources.push_back(fmt::format("Clough–Penzien record, seed {}, {} s at {} s, PGA {:.3f} g before scaling", o.seed,
                                      o.duration_s, o.dt_s, o.pga_m_s2 / core::kRecordGravity));
    assembly.horizontal_1 = std::move(c);
  } else if (a.record.empty()) {
    throw InvalidArgument("give a ground motion: --record FILE (PEER AT2 or CSV) or --synthetic SEED");
  } else if (IsCsv(a.record, a.record_format)) {
    io::CsvGroundMotionOptions o;
    o.unit = io::ParseGroundAccelerationUnit(a.units);
    o.dt_s = a.csv_dt_s;
    const io::GroundMotionComponents csv = io::ReadGroundMotionCsv(a.record, o);
    for (std::size_t k = 0; k < csv.roles.size(); ++k) {
      io::RecordComponent c{a.record + " [" + csv.roles[k] + "]", csv.dt_s, csv.accel_m_s2[k]};
      double peak = 0.0;
      for (double v : c.accel_m_s2) peak = std::max(peak, std::abs(v));
      out.sources.push_back(fmt::format("{} ({}): CSV, {} samples, DT {} s, peak {:.4f} g", a.record, csv.roles[k],
                                        c.accel_m_s2.size(), csv.dt_s, peak / core::kRecordGravity));
      (csv.roles[k] == "h1" ? assembly.horizontal_1 : csv.roles[k] == "h2" ? assembly.horizontal_2 : assembly.vertical) = c;
    }
  } else {
    assembly.horizontal_1 = FromPeer(a.record, &out.sources, "horizontal 1");
  }
  const auto other = [&](const std::string& path, std::optional<io::RecordComponent>& slot, const char* role) {
    if (path.empty()) return;
    if (slot) throw InvalidArgument(std::string("the ") + role + " component is given twice");
    if (IsCsv(path, a.record_format)) {
      io::CsvGroundMotionOptions o;
      o.unit = io::ParseGroundAccelerationUnit(a.units);
      o.dt_s = a.csv_dt_s;
      const io::GroundMotionComponents csv = io::ReadGroundMotionCsv(path, o);
      if (csv.roles.size() != 1) throw InvalidArgument(path + " must have one acceleration column for the " + role);
      slot = io::RecordComponent{path, csv.dt_s, csv.accel_m_s2[0]};
      out.sources.push_back(fmt::format("{} ({}): CSV, {} samples, DT {} s", path, role, csv.accel_m_s2[0].size(), csv.dt_s));
    } else {
      slot = FromPeer(path, &out.sources, role);
    }
  };
  other(a.record2, assembly.horizontal_2, "horizontal 2");
  other(a.vertical, assembly.vertical, "vertical");
  assembly.incidence_rad = a.angle_deg * M_PI / 180.0;
  if (a.scale) assembly.scale = *a.scale;
  if (a.pga_g) assembly.target_pga_m_s2 = *a.pga_g * core::kRecordGravity;
  out.assembled = io::AssembleGroundMotion(assembly);
  return out;
}

}  // namespace rockfit::app
