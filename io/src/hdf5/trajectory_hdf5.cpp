#include "rockfit/io/trajectory_hdf5.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <system_error>
#include <vector>

#include "rockfit/core/errors.hpp"
#include "rockfit/io/atomic_file.hpp"
#include "rockfit/io/hdf5_file.hpp"

namespace rockfit::io {
namespace {

// The quaternions as rows (w, x, y, z), scalar first.
std::vector<double> QuaternionRows(const std::vector<Eigen::Quaterniond>& q_WB) {
  std::vector<double> rows;
  rows.reserve(4 * q_WB.size());
  for (const Eigen::Quaterniond& q : q_WB) rows.insert(rows.end(), {q.w(), q.x(), q.y(), q.z()});
  return rows;
}

// An N×3 dataset with its `columns` attribute, as in every rockfit file (docs/file-formats.md).
void WriteXyz(const hdf5::Group& g, const std::string& name, const std::vector<Eigen::Vector3d>& rows,
              const std::string& units) {
  g.WriteVectors(name, rows, units);
  g.SetString("columns", "x, y, z", name);
}

// The extra contents of a response to ground motion.
struct ResponseContents {
  const core::Response* response;
  const core::GroundMotion* ground;
  const std::vector<std::string>* sources;
};

void WriteSetup(const hdf5::Group& root, const core::Block& block, const core::ModelParameters& params,
                const core::SimulationOptions& options) {
  const hdf5::Group b = root.CreateGroup("block");
  b.SetDouble("b1_m", block.b1());
  b.SetDouble("b2_m", block.b2());
  b.SetDouble("h_m", block.h());
  b.SetDouble("mass_kg", block.mass());
  b.SetDouble("density_kg_m3", block.density());
  const hdf5::Group p = root.CreateGroup("parameters");
  p.SetDouble("alpha_rad", params.alpha_rad);
  p.SetDouble("lambda", params.lambda);
  p.SetDouble("tau_edge_N_m_s", params.tau_edge);
  p.SetDouble("lambda_lat", params.lambda_lat);
  p.SetDouble("lambda_lon", params.lambda_lon);
  p.SetString("facet_tau_rule", core::ToString(params.facet_tau_rule));
  const hdf5::Group o = root.CreateGroup("options");
  o.SetDouble("rate_hz", options.rate_hz);
  o.SetString("stop", core::ToString(options.stop));
  o.SetDouble("t_max_s", options.t_max_s);
  o.SetDouble("zeno_dt_s", options.zeno_dt_s);
  o.SetDouble("rest_energy_height_m", options.rest_energy_height_m);
  o.SetDouble("gravity_m_s2", options.gravity_m_s2);
  o.SetString("release_edge",
              "V" + std::to_string(options.release_edge_first) + "V" + std::to_string(options.release_edge_second));
  o.SetDouble("rel_tol", options.rel_tol);
  o.SetDouble("abs_tol", options.abs_tol);
  o.SetDouble("event_time_tol_s", options.event_time_tol_s);
  o.SetDouble("max_step_s", options.max_step_s);
}

void WriteResult(const hdf5::Group& root, const core::Trajectory& trajectory) {
  const hdf5::Group g = root.CreateGroup("result");
  g.SetDouble("t_end_s", trajectory.t_end_s);
  g.SetString("end_reason", core::ToString(trajectory.end_reason));
  g.SetString("message", trajectory.message);
  g.SetDouble("wall_time_s", trajectory.wall_time_s);
  g.SetInt("num_steps", trajectory.num_steps);
  g.SetInt("num_evaluations", trajectory.num_evaluations);
}

void WriteSamples(const hdf5::Group& root, const core::Trajectory& trajectory, const ResponseContents* extra) {
  const hdf5::Group g = root.CreateGroup("samples");
  const std::size_t n = trajectory.t_s.size();
  g.WriteDoubles("time_s", trajectory.t_s, "s");
  WriteXyz(g, "w_B_rad_s", trajectory.w_B, "rad/s");
  g.WriteMatrix("q_WB", QuaternionRows(trajectory.q_WB), trajectory.q_WB.size(), 4, "1");
  g.SetString("columns", "w, x, y, z", "q_WB");
  g.WriteVectors("euler_zyx_rad", trajectory.euler_zyx, "rad");
  g.SetString("columns", "phi_z, phi_y, phi_x", "euler_zyx_rad");
  std::vector<std::string> modes;
  modes.reserve(n);
  for (const core::Mode& mode : trajectory.mode) modes.push_back(mode.ToString());
  g.WriteStrings("mode", modes);
  if (extra == nullptr) return;
  std::vector<Eigen::Vector3d> a_g;
  std::vector<double> tilt;
  for (std::size_t k = 0; k < n; ++k) a_g.push_back(extra->ground->Acceleration_W(trajectory.t_s[k]));
  for (const Eigen::Quaterniond& q : trajectory.q_WB) {
    tilt.push_back(std::acos(std::clamp(q.toRotationMatrix()(2, 2), -1.0, 1.0)));
  }
  WriteXyz(g, "a_g_W_m_s2", a_g, "m/s^2");
  g.WriteDoubles("tilt_rad", tilt, "rad");
}

void WriteGroundMotionAndResponse(const hdf5::Group& root, const ResponseContents& extra) {
  const core::GroundMotion& ground = *extra.ground;
  const hdf5::Group g = root.CreateGroup("ground_motion");
  std::vector<double> t;
  for (std::size_t k = 0; k < ground.size(); ++k) t.push_back(ground.SampleTime(k));
  g.WriteDoubles("time_s", t, "s");
  WriteXyz(g, "a_W_m_s2", ground.samples_W(), "m/s^2");
  g.SetDouble("dt_s", ground.dt_s());
  g.SetDouble("pga_horizontal_m_s2", ground.PeakHorizontal());
  g.SetDouble("pga_vertical_m_s2", ground.PeakVertical());
  if (!extra.sources->empty()) g.WriteStrings("sources", *extra.sources);
  const core::ResponseSummary& r = extra.response->summary;
  const hdf5::Group rg = root.CreateGroup("response");
  rg.SetInt("overturned", r.overturned ? 1 : 0);
  rg.SetDouble("t_overturn_s", r.t_overturn_s ? *r.t_overturn_s : std::nan(""));
  rg.SetString("overturn_rule", core::ToString(r.overturn_rule));
  rg.SetDouble("peak_tilt_rad", r.peak_tilt_rad);
  rg.SetDouble("t_peak_tilt_s", r.t_peak_tilt_s);
  rg.SetDouble("peak_rotation_rad", r.peak_rotation_rad);
  rg.SetDouble("peak_rate_rad_s", r.peak_rate_rad_s);
  rg.SetDouble("critical_tilt_rad", r.critical_tilt_rad);
  rg.SetInt("num_impacts", static_cast<std::int64_t>(r.num_impacts));
  rg.SetDouble("max_friction_ratio", r.max_friction_ratio);
  rg.SetDouble("min_normal_force_N", r.min_normal_force_N);
  rg.SetDouble("max_discarded_rate_rad_s", r.max_discarded_rate_rad_s);
  rg.WriteDoubles("uplift_times_s", r.uplift_times_s, "s");
}

void WriteImpacts(const hdf5::Group& root, const core::Trajectory& trajectory) {
  const hdf5::Group g = root.CreateGroup("impacts");
  std::vector<double> t, tau, energy;
  std::vector<Eigen::Vector3d> w_minus_B, w_plus_B, w_minus_W, w_plus_W;
  std::vector<std::string> kind, before, after, status;
  for (const core::ImpactRecord& impact : trajectory.impacts) {
    t.push_back(impact.t_s);
    tau.push_back(impact.tau);
    energy.push_back(impact.delta_energy_J);
    w_minus_B.push_back(impact.w_minus_B);
    w_plus_B.push_back(impact.w_plus_B);
    w_minus_W.push_back(impact.w_minus_W);
    w_plus_W.push_back(impact.w_plus_W);
    kind.push_back(core::ToString(impact.kind));
    before.push_back(impact.contact_before.ToString());
    after.push_back(impact.kind == core::ImpactKind::kRest ? std::string("base") : impact.contact_after.ToString());
    status.push_back(core::ToString(impact.status));
  }
  g.WriteDoubles("t_s", t, "s");
  g.WriteStrings("kind", kind);
  g.WriteStrings("contact_before", before);
  g.WriteStrings("contact_after", after);
  g.WriteStrings("status", status);
  WriteXyz(g, "w_minus_B_rad_s", w_minus_B, "rad/s");
  WriteXyz(g, "w_plus_B_rad_s", w_plus_B, "rad/s");
  WriteXyz(g, "w_minus_W_rad_s", w_minus_W, "rad/s");
  WriteXyz(g, "w_plus_W_rad_s", w_plus_W, "rad/s");
  g.WriteDoubles("tau_N_m_s", tau, "N*m*s");
  g.WriteDoubles("delta_energy_J", energy, "J");
}

void WriteSegments(const hdf5::Group& root, const core::Trajectory& trajectory) {
  const hdf5::Group g = root.CreateGroup("segments");
  std::vector<double> begin, end, normal, friction, drift;
  std::vector<std::string> mode;
  for (const core::SegmentDiagnostics& segment : trajectory.segments) {
    begin.push_back(segment.t_begin_s);
    end.push_back(segment.t_end_s);
    normal.push_back(segment.min_normal_force_N);
    friction.push_back(segment.max_friction_ratio);
    drift.push_back(segment.energy_drift_rel);
    mode.push_back(segment.mode.ToString());
  }
  g.WriteDoubles("t_begin_s", begin, "s");
  g.WriteDoubles("t_end_s", end, "s");
  g.WriteStrings("mode", mode);
  g.WriteDoubles("min_normal_force_N", normal, "N");
  g.WriteDoubles("max_friction_ratio", friction, "1");
  g.WriteDoubles("energy_drift_rel", drift, "1");
}

void WriteHdf5File(const std::filesystem::path& path, const core::Block& block, const core::ModelParameters& params,
                   const core::SimulationOptions& options, const core::Trajectory& trajectory,
                   const ResponseContents* extra) {
  const std::filesystem::path directory = path.has_parent_path() ? path.parent_path() : std::filesystem::path(".");
  std::error_code ec;
  if (!std::filesystem::is_directory(directory, ec)) {
    throw OutputError("cannot write " + path.string() + ": the directory " + directory.string() +
                      " does not exist; create it or choose another -o path");
  }
  // Built in memory and written in one go by WriteFileAtomically: a full disk is then an error of that write, never
  // one inside libhdf5 (hdf5_file.hpp, File::CreateInMemory).
  std::string image;
  {
    const hdf5::File file = hdf5::File::CreateInMemory(path);
    const hdf5::Group root = file.Root();
    root.SetString("schema", kTrajectorySchemaName);
    root.SetInt("rockfit_schema_version", kTrajectorySchemaVersion);
    root.SetString("created_by", extra != nullptr ? "rockfit respond" : "rockfit simulate");
    WriteSetup(root, block, params, options);
    WriteResult(root, trajectory);
    WriteSamples(root, trajectory, extra);
    if (extra != nullptr) WriteGroundMotionAndResponse(root, *extra);
    WriteImpacts(root, trajectory);
    WriteSegments(root, trajectory);
    image = file.Image();
  }
  WriteFileAtomically(path, [&image](std::ostream& out) {
    out.write(image.data(), static_cast<std::streamsize>(image.size()));
  });
}

}  // namespace

void WriteTrajectoryHdf5(const std::filesystem::path& path, const core::Block& block,
                         const core::ModelParameters& params, const core::SimulationOptions& options,
                         const core::Trajectory& trajectory) {
  WriteHdf5File(path, block, params, options, trajectory, nullptr);
}

void WriteResponseHdf5(const std::filesystem::path& path, const core::Block& block, const core::ModelParameters& params,
                       const core::SimulationOptions& options, const core::Response& response,
                       const core::GroundMotion& ground, const std::vector<std::string>& sources) {
  const ResponseContents extra{&response, &ground, &sources};
  WriteHdf5File(path, block, params, options, response.trajectory, &extra);
}

}  // namespace rockfit::io
