#include "rockfit/io/trajectory_hdf5.hpp"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <system_error>
#include <vector>

#include <hdf5.h>

#include "rockfit/core/errors.hpp"
#include "rockfit/io/atomic_file.hpp"

namespace rockfit::io {
namespace {

// Owns one HDF5 identifier and closes it with the matching H5*close function.
class Handle {
 public:
  Handle(hid_t id, herr_t (*close)(hid_t)) : id_(id), close_(close) {}
  ~Handle() {
    if (id_ >= 0) close_(id_);
  }
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  Handle(Handle&& other) noexcept : id_(other.id_), close_(other.close_) { other.id_ = -1; }
  Handle& operator=(Handle&&) = delete;
  hid_t get() const { return id_; }
  bool ok() const { return id_ >= 0; }

 private:
  hid_t id_;
  herr_t (*close_)(hid_t);
};

// The in-memory file grows in steps of this many bytes.
constexpr std::size_t kMemoryIncrement = std::size_t{1} << 20;

class Writer {
 public:
  explicit Writer(const std::filesystem::path& path) : path_(path) {}

  void Check(bool ok, const std::string& what) const {
    if (!ok) throw OutputError("cannot write " + what + " to the HDF5 file " + path_.string());
  }

  Handle Group(hid_t parent, const char* name) const {
    Handle group(H5Gcreate2(parent, name, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), &H5Gclose);
    Check(group.ok(), std::string("group ") + name);
    return group;
  }

  void Attribute(hid_t object, const char* name, double value) const {
    Handle space(H5Screate(H5S_SCALAR), &H5Sclose);
    Handle attribute(H5Acreate2(object, name, H5T_IEEE_F64LE, space.get(), H5P_DEFAULT, H5P_DEFAULT), &H5Aclose);
    Check(attribute.ok() && H5Awrite(attribute.get(), H5T_NATIVE_DOUBLE, &value) >= 0, std::string("attribute ") + name);
  }

  void Attribute(hid_t object, const char* name, long long value) const {
    Handle space(H5Screate(H5S_SCALAR), &H5Sclose);
    Handle attribute(H5Acreate2(object, name, H5T_STD_I64LE, space.get(), H5P_DEFAULT, H5P_DEFAULT), &H5Aclose);
    Check(attribute.ok() && H5Awrite(attribute.get(), H5T_NATIVE_LLONG, &value) >= 0, std::string("attribute ") + name);
  }

  void Attribute(hid_t object, const char* name, const std::string& value) const {
    Handle type = StringType();
    Handle space(H5Screate(H5S_SCALAR), &H5Sclose);
    Handle attribute(H5Acreate2(object, name, type.get(), space.get(), H5P_DEFAULT, H5P_DEFAULT), &H5Aclose);
    const char* text = value.c_str();
    Check(attribute.ok() && H5Awrite(attribute.get(), type.get(), &text) >= 0, std::string("attribute ") + name);
  }

  // A dataset of rows × columns doubles (columns = 0: one dimension), with its units.
  void Numbers(hid_t group, const char* name, const std::vector<double>& data, std::size_t rows, std::size_t columns,
               const char* units) const {
    const hsize_t dims[2] = {rows, columns};
    Handle space(H5Screate_simple(columns == 0 ? 1 : 2, dims, nullptr), &H5Sclose);
    Handle dataset(H5Dcreate2(group, name, H5T_IEEE_F64LE, space.get(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
                   &H5Dclose);
    Check(dataset.ok(), std::string("dataset ") + name);
    if (!data.empty()) {
      Check(H5Dwrite(dataset.get(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, data.data()) >= 0,
            std::string("dataset ") + name);
    }
    Attribute(dataset.get(), "units", std::string(units));
  }

  void Strings(hid_t group, const char* name, const std::vector<std::string>& data) const {
    Handle type = StringType();
    const hsize_t dims[1] = {data.size()};
    Handle space(H5Screate_simple(1, dims, nullptr), &H5Sclose);
    Handle dataset(H5Dcreate2(group, name, type.get(), space.get(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), &H5Dclose);
    Check(dataset.ok(), std::string("dataset ") + name);
    if (!data.empty()) {
      std::vector<const char*> pointers;
      pointers.reserve(data.size());
      for (const auto& s : data) pointers.push_back(s.c_str());
      Check(H5Dwrite(dataset.get(), type.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, pointers.data()) >= 0,
            std::string("dataset ") + name);
    }
    Attribute(dataset.get(), "units", std::string());
  }

 private:
  Handle StringType() const {
    Handle type(H5Tcopy(H5T_C_S1), &H5Tclose);
    Check(type.ok() && H5Tset_size(type.get(), H5T_VARIABLE) >= 0 && H5Tset_cset(type.get(), H5T_CSET_UTF8) >= 0,
          "a string type");
    return type;
  }

  std::filesystem::path path_;
};

template <class Vector>
std::vector<double> Rows(const std::vector<Vector>& rows) {
  std::vector<double> flat;
  flat.reserve(rows.size() * Vector::RowsAtCompileTime);
  for (const auto& row : rows) {
    for (int i = 0; i < Vector::RowsAtCompileTime; ++i) flat.push_back(row[i]);
  }
  return flat;
}

// The extra contents of a response to ground motion.
struct ResponseContents {
  const core::Response* response;
  const core::GroundMotion* ground;
  const std::vector<std::string>* sources;
};

void WriteContents(const Writer& w, hid_t file, const core::Block& block, const core::ModelParameters& params,
                   const core::SimulationOptions& options, const core::Trajectory& trajectory,
                   const ResponseContents* extra = nullptr) {
  w.Attribute(file, "schema", std::string(kTrajectorySchemaName));
  w.Attribute(file, "schema_version", static_cast<long long>(kTrajectorySchemaVersion));
  w.Attribute(file, "created_by", std::string(extra != nullptr ? "rockfit respond" : "rockfit simulate"));
  {
    Handle g = w.Group(file, "block");
    w.Attribute(g.get(), "b1_m", block.b1());
    w.Attribute(g.get(), "b2_m", block.b2());
    w.Attribute(g.get(), "h_m", block.h());
    w.Attribute(g.get(), "mass_kg", block.mass());
    w.Attribute(g.get(), "density_kg_m3", block.density());
  }
  {
    Handle g = w.Group(file, "parameters");
    w.Attribute(g.get(), "alpha_rad", params.alpha_rad);
    w.Attribute(g.get(), "lambda", params.lambda);
    w.Attribute(g.get(), "tau_edge_N_m_s", params.tau_edge);
    w.Attribute(g.get(), "lambda_lat", params.lambda_lat);
    w.Attribute(g.get(), "lambda_lon", params.lambda_lon);
    w.Attribute(g.get(), "facet_tau_rule", std::string(core::ToString(params.facet_tau_rule)));
  }
  {
    Handle g = w.Group(file, "options");
    w.Attribute(g.get(), "rate_hz", options.rate_hz);
    w.Attribute(g.get(), "stop", std::string(core::ToString(options.stop)));
    w.Attribute(g.get(), "t_max_s", options.t_max_s);
    w.Attribute(g.get(), "zeno_dt_s", options.zeno_dt_s);
    w.Attribute(g.get(), "rest_energy_height_m", options.rest_energy_height_m);
    w.Attribute(g.get(), "gravity_m_s2", options.gravity_m_s2);
    w.Attribute(g.get(), "release_edge",
                "V" + std::to_string(options.release_edge_first) + "V" + std::to_string(options.release_edge_second));
    w.Attribute(g.get(), "rel_tol", options.rel_tol);
    w.Attribute(g.get(), "abs_tol", options.abs_tol);
    w.Attribute(g.get(), "event_time_tol_s", options.event_time_tol_s);
    w.Attribute(g.get(), "max_step_s", options.max_step_s);
  }
  {
    Handle g = w.Group(file, "result");
    w.Attribute(g.get(), "t_end_s", trajectory.t_end_s);
    w.Attribute(g.get(), "end_reason", std::string(core::ToString(trajectory.end_reason)));
    w.Attribute(g.get(), "message", trajectory.message);
    w.Attribute(g.get(), "wall_time_s", trajectory.wall_time_s);
    w.Attribute(g.get(), "num_steps", static_cast<long long>(trajectory.num_steps));
    w.Attribute(g.get(), "num_evaluations", static_cast<long long>(trajectory.num_evaluations));
  }
  {
    Handle g = w.Group(file, "samples");
    const std::size_t n = trajectory.t_s.size();
    w.Numbers(g.get(), "t", trajectory.t_s, n, 0, "s");
    w.Numbers(g.get(), "w_B", Rows(trajectory.w_B), n, 3, "rad/s");
    std::vector<double> q;
    q.reserve(4 * trajectory.q_WB.size());
    for (const auto& quaternion : trajectory.q_WB) {
      q.insert(q.end(), {quaternion.w(), quaternion.x(), quaternion.y(), quaternion.z()});
    }
    w.Numbers(g.get(), "q_WB", q, trajectory.q_WB.size(), 4, "1");
    w.Numbers(g.get(), "euler_zyx", Rows(trajectory.euler_zyx), trajectory.euler_zyx.size(), 3, "rad");
    std::vector<std::string> modes;
    modes.reserve(n);
    for (const auto& mode : trajectory.mode) modes.push_back(mode.ToString());
    w.Strings(g.get(), "mode", modes);
    if (extra != nullptr) {
      std::vector<Eigen::Vector3d> a_g;
      std::vector<double> tilt;
      for (std::size_t k = 0; k < n; ++k) a_g.push_back(extra->ground->Acceleration_W(trajectory.t_s[k]));
      for (const auto& quaternion : trajectory.q_WB) {
        tilt.push_back(std::acos(std::clamp(quaternion.toRotationMatrix()(2, 2), -1.0, 1.0)));
      }
      w.Numbers(g.get(), "a_g_W", Rows(a_g), n, 3, "m/s^2");
      w.Numbers(g.get(), "tilt", tilt, tilt.size(), 0, "rad");
    }
  }
  if (extra != nullptr) {
    const core::GroundMotion& ground = *extra->ground;
    Handle g = w.Group(file, "ground_motion");
    std::vector<double> t;
    for (std::size_t k = 0; k < ground.size(); ++k) t.push_back(ground.SampleTime(k));
    w.Numbers(g.get(), "t", t, t.size(), 0, "s");
    w.Numbers(g.get(), "a_W", Rows(ground.samples_W()), ground.size(), 3, "m/s^2");
    w.Attribute(g.get(), "dt_s", ground.dt_s());
    w.Attribute(g.get(), "pga_horizontal_m_s2", ground.PeakHorizontal());
    w.Attribute(g.get(), "pga_vertical_m_s2", ground.PeakVertical());
    if (!extra->sources->empty()) w.Strings(g.get(), "sources", *extra->sources);
    const core::ResponseSummary& r = extra->response->summary;
    Handle rg = w.Group(file, "response");
    w.Attribute(rg.get(), "overturned", static_cast<long long>(r.overturned ? 1 : 0));
    w.Attribute(rg.get(), "t_overturn_s", r.t_overturn_s ? *r.t_overturn_s : std::nan(""));
    w.Attribute(rg.get(), "peak_tilt_rad", r.peak_tilt_rad);
    w.Attribute(rg.get(), "t_peak_tilt_s", r.t_peak_tilt_s);
    w.Attribute(rg.get(), "peak_rotation_rad", r.peak_rotation_rad);
    w.Attribute(rg.get(), "peak_rate_rad_s", r.peak_rate_rad_s);
    w.Attribute(rg.get(), "critical_tilt_rad", r.critical_tilt_rad);
    w.Attribute(rg.get(), "num_impacts", static_cast<long long>(r.num_impacts));
    w.Attribute(rg.get(), "max_friction_ratio", r.max_friction_ratio);
    w.Attribute(rg.get(), "min_normal_force_N", r.min_normal_force_N);
    w.Numbers(rg.get(), "uplift_times", r.uplift_times_s, r.uplift_times_s.size(), 0, "s");
  }
  {
    Handle g = w.Group(file, "impacts");
    const std::size_t m = trajectory.impacts.size();
    std::vector<double> t, tau, energy;
    std::vector<Eigen::Vector3d> w_minus_B, w_plus_B, w_minus_W, w_plus_W;
    std::vector<std::string> kind, before, after, status;
    for (const auto& impact : trajectory.impacts) {
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
    w.Numbers(g.get(), "t", t, m, 0, "s");
    w.Strings(g.get(), "kind", kind);
    w.Strings(g.get(), "contact_before", before);
    w.Strings(g.get(), "contact_after", after);
    w.Strings(g.get(), "status", status);
    w.Numbers(g.get(), "omega_minus_B", Rows(w_minus_B), m, 3, "rad/s");
    w.Numbers(g.get(), "omega_plus_B", Rows(w_plus_B), m, 3, "rad/s");
    w.Numbers(g.get(), "omega_minus_W", Rows(w_minus_W), m, 3, "rad/s");
    w.Numbers(g.get(), "omega_plus_W", Rows(w_plus_W), m, 3, "rad/s");
    w.Numbers(g.get(), "tau", tau, m, 0, "N*m*s");
    w.Numbers(g.get(), "delta_energy", energy, m, 0, "J");
  }
  {
    Handle g = w.Group(file, "segments");
    const std::size_t s = trajectory.segments.size();
    std::vector<double> begin, end, normal, friction, drift;
    std::vector<std::string> mode;
    for (const auto& segment : trajectory.segments) {
      begin.push_back(segment.t_begin_s);
      end.push_back(segment.t_end_s);
      normal.push_back(segment.min_normal_force_N);
      friction.push_back(segment.max_friction_ratio);
      drift.push_back(segment.energy_drift_rel);
      mode.push_back(segment.mode.ToString());
    }
    w.Numbers(g.get(), "t_begin", begin, s, 0, "s");
    w.Numbers(g.get(), "t_end", end, s, 0, "s");
    w.Strings(g.get(), "mode", mode);
    w.Numbers(g.get(), "min_normal_force", normal, s, 0, "N");
    w.Numbers(g.get(), "max_friction_ratio", friction, s, 0, "1");
    w.Numbers(g.get(), "energy_drift_rel", drift, s, 0, "1");
  }
}

void WriteHdf5File(const std::filesystem::path& path, const core::Block& block, const core::ModelParameters& params,
                   const core::SimulationOptions& options, const core::Trajectory& trajectory,
                   const ResponseContents* extra) {
  // HDF5 prints its error stack to stderr by default; rockfit reports errors itself.
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  const std::filesystem::path directory = path.has_parent_path() ? path.parent_path() : std::filesystem::path(".");
  std::error_code ec;
  if (!std::filesystem::is_directory(directory, ec)) {
    throw OutputError("cannot write " + path.string() + ": the directory " + directory.string() +
                      " does not exist; create it or choose another -o path");
  }
  // Built in memory (HDF5's core driver) and written in one go through WriteFileAtomically: a full disk is then
  // an error of that write, never one inside libhdf5 (hdf5_file.hpp, File::CreateInMemory).
  const Writer writer(path);
  std::string image;
  {
    Handle fapl(H5Pcreate(H5P_FILE_ACCESS), &H5Pclose);
    writer.Check(fapl.ok() && H5Pset_fapl_core(fapl.get(), kMemoryIncrement, 0) >= 0, "an in-memory file");
    Handle file(H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl.get()), &H5Fclose);
    writer.Check(file.ok(), "the file header");
    WriteContents(writer, file.get(), block, params, options, trajectory, extra);
    writer.Check(H5Fflush(file.get(), H5F_SCOPE_GLOBAL) >= 0, "the file contents");
    const ssize_t size = H5Fget_file_image(file.get(), nullptr, 0);
    writer.Check(size >= 0, "the file image");
    image.resize(static_cast<std::size_t>(size));
    writer.Check(H5Fget_file_image(file.get(), image.data(), image.size()) == size, "the file image");
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
