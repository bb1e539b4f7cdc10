#include "ground_motion_args.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>

#include <fmt/format.h>

#include "activity.hpp"
#include "rockfit/core/errors.hpp"
#include "rockfit/core/ground_motion.hpp"
#include "rockfit/io/ground_motion_csv.hpp"
#include "rockfit/io/peer_at2.hpp"

namespace rockfit::tools {
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

void AddGroundMotionOptions(CLI::App& app, GroundMotionArgs& a) {
  const char* group = "Ground motion";
  app.add_option("--record", a.record,
                 "Ground-motion record acting along the incidence angle: a PEER AT2 file (values in g) or a CSV "
                 "(header; optional time column `time` [s]; one to three columns: horizontal 1, horizontal 2, "
                 "vertical, or named x, y, z)")
      ->group(group);
  app.add_option("--record2", a.record2, "Second horizontal component, acting 90° from --record (AT2 or one-column CSV)")
      ->group(group);
  app.add_option("--vertical", a.vertical, "Vertical component (AT2 or one-column CSV), positive up")->group(group);
  app.add_option("--record-format", a.record_format, "auto (by extension: .csv is CSV, else AT2), at2 or csv")
      ->check(CLI::IsMember({"auto", "at2", "csv"}))->capture_default_str()->group(group);
  app.add_option("--units", a.units, "Units of CSV records: g (9.80665 m/s²), m/s2 or cm/s2")
      ->check(CLI::IsMember({"g", "m/s2", "cm/s2"}))->capture_default_str()->group(group);
  app.add_option("--dt", a.csv_dt_s, "Time step [s] of CSV records without a time column")->group(group);
  app.add_option("--synthetic", a.synthetic_seed,
                 "Instead of a record: a generated Clough–Penzien record with this seed (io/README.md, \"Stochastic "
                 "ground motion\"; PGA 0.3 g unless --pga)")
      ->group(group);
  app.add_option("--synthetic-duration", a.synthetic_duration_s, "Duration of the generated record [s]")
      ->capture_default_str()->group(group);
  app.add_option("--synthetic-dt", a.synthetic_dt_s, "Step of the generated record [s]")->capture_default_str()->group(group);
  auto* scale = app.add_option("--scale", a.scale, "Multiply every component by this factor")->group(group);
  app.add_option("--pga", a.pga_g,
                 "Scale all components by one factor so that the peak horizontal acceleration (resultant of the "
                 "horizontal components) is this many g")
      ->excludes(scale)->group(group);
  app.add_option("--angle", a.angle_deg, "Incidence angle β [deg] of --record from the block's x axis")
      ->capture_default_str()->group(group);
}

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

}  // namespace rockfit::tools
