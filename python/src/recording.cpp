// rockfit.Recording and rockfit.load_recording: the readers of io/ (every format the program reads, a trial of a
// manifest or of rockfit's HDF5 file), with the samples as numpy arrays.
#include <cmath>

#include <fmt/format.h>

#include "bindings.hpp"
#include "path_argument.hpp"
#include "rockfit/app/recording_input.hpp"
#include "rockfit/core/errors.hpp"

namespace rockfit::python {

core::Block BlockFor(const std::optional<core::Block>& given, const TrialRecording& recording, const char* what) {
  if (given) return *given;
  if (recording.block) return *recording.block;
  throw InvalidArgument(fmt::format("{} needs the block geometry: pass block=rockfit.Block(b1, b2, h, density=…) or "
                                    "Block.from_manifest(path, id), or load the recording from a manifest with trial=ID",
                                    what));
}

namespace {

using RecordingPtr = std::shared_ptr<TrialRecording>;

TrialRecording FromArrays(const py::object& t, const py::object& w_B, const py::object& euler,
                          const py::object& accel_B, std::optional<double> rate_hz, const std::string& trial) {
  TrialRecording r;
  io::Recording& rec = r.recording;
  rec.t_s = ToDoubles(t, "t");
  rec.w_B = ToVectors3(w_B, "w_B");
  if (!euler.is_none()) rec.euler_zyx = ToVectors3(euler, "euler");
  if (!accel_B.is_none()) rec.accel_B = ToVectors3(accel_B, "accel_B");
  const std::size_t n = rec.t_s.size();
  if (n < 2) throw InvalidArgument("a recording needs at least 2 samples");
  if (rec.w_B.size() != n || (rec.has_euler() && rec.euler_zyx.size() != n) || (rec.has_accel() && rec.accel_B.size() != n)) {
    throw InvalidArgument(fmt::format("t has {} samples, w_B {}, euler {}, accel_B {}: every array needs one row per "
                                      "sample", n, rec.w_B.size(), rec.euler_zyx.size(), rec.accel_B.size()));
  }
  for (std::size_t k = 0; k < n; ++k) {
    if (!std::isfinite(rec.t_s[k]) || (k > 0 && !(rec.t_s[k] > rec.t_s[k - 1]))) {
      throw InvalidArgument(fmt::format("t must be finite and strictly increasing; it is not at index {}", k));
    }
  }
  if (rate_hz && !(std::isfinite(*rate_hz) && *rate_hz > 0.0)) throw InvalidArgument("rate must be a positive number of Hz");
  rec.rate_hz = rate_hz.value_or(static_cast<double>(n - 1) / (rec.t_s.back() - rec.t_s.front()));
  rec.rate_source = rate_hz ? io::RateSource::kOption : io::RateSource::kTimestamps;
  rec.format = "python";
  rec.source = "python arrays";
  rec.mounting = "identity";
  r.trial = trial;
  return r;
}

std::string Repr(const TrialRecording& r) {
  const io::Recording& rec = r.recording;
  return fmt::format("Recording(trial='{}', format='{}', samples={}, rate_hz={:g}, duration_s={:.6g}, euler={}, "
                     "block={})",
                     r.trial, rec.format, rec.size(), rec.rate_hz, rec.duration_s(), rec.has_euler() ? "yes" : "no",
                     r.block ? "yes" : "no");
}

}  // namespace

void RegisterRecording(py::module_& m) {
  py::class_<TrialRecording, RecordingPtr>(
      m, "Recording",
      "IMU samples of one trial in SI units and block axes, with what the readers report.\n\n"
      "Arrays (views into the recording, no copies; change them in place to feed your own preprocessing into\n"
      "metrics() or fit()):\n"
      "  t        (N,)   sample times [s]\n"
      "  w_B      (N, 3) angular velocity in the block frame [rad/s]\n"
      "  euler    (N, 3) ZYX Euler angles (φz, φy, φx) of R_WB [rad], unwrapped; (0, 3) without attitude\n"
      "  accel_B  (N, 3) specific force in the block frame [m/s²]; (0, 3) when absent\n"
      "Metadata: trial, format, source, rate_hz, rate_source, orientation_source, orientation_rate_hz, mounting,\n"
      "columns, gaps, warnings; block, block_id, position, notes for a trial of a manifest.\n\n"
      "Recording(t, w_B, euler=None, accel_B=None, rate=None, trial='python') makes one from arrays (copied once);\n"
      "rate defaults to (N − 1)/(t[-1] − t[0]).")
      .def(py::init([](const py::object& t, const py::object& w_B, const py::object& euler, const py::object& accel_B,
                       std::optional<double> rate, const std::string& trial) {
             return std::make_shared<TrialRecording>(FromArrays(t, w_B, euler, accel_B, rate, trial));
           }),
           py::arg("t"), py::arg("w_B"), py::arg("euler") = py::none(), py::kw_only(), py::arg("accel_B") = py::none(),
           py::arg("rate") = py::none(), py::arg("trial") = "python")
      .def_property_readonly(
          "t", [](py::object self) { return ViewArray(self.cast<TrialRecording&>().recording.t_s, self); },
          "Sample times [s], shape (N,)")
      .def_property_readonly(
          "w_B", [](py::object self) { return ViewArray(self.cast<TrialRecording&>().recording.w_B, self); },
          "Angular velocity in the block frame [rad/s], shape (N, 3)")
      .def_property_readonly(
          "euler", [](py::object self) { return ViewArray(self.cast<TrialRecording&>().recording.euler_zyx, self); },
          "ZYX Euler angles (φz, φy, φx) of R_WB [rad], shape (N, 3); (0, 3) without attitude")
      .def_property_readonly(
          "accel_B", [](py::object self) { return ViewArray(self.cast<TrialRecording&>().recording.accel_B, self); },
          "Specific force in the block frame [m/s²], shape (N, 3); (0, 3) when absent")
      .def_readonly("trial", &TrialRecording::trial, "Trial id (the manifest's, or made from the file name)")
      .def_property_readonly("format", [](const TrialRecording& r) { return r.recording.format; },
                             "'ximu-gui', 'ximu3', 'generic-csv', 'rockfit-hdf5' or 'python'")
      .def_property_readonly("source", [](const TrialRecording& r) { return r.recording.source; }, "The path read")
      .def_property_readonly("rate_hz", [](const TrialRecording& r) { return r.recording.rate_hz; },
                             "Nominal gyro sample rate [Hz]")
      .def_property_readonly("rate_source",
                             [](const TrialRecording& r) { return io::ToString(r.recording.rate_source); },
                             "Where the rate came from: registers, timestamps, manifest, option, file")
      .def_property_readonly("orientation_source", [](const TrialRecording& r) { return r.recording.orientation_source; },
                             "File(s) the attitude was read from ('' without attitude)")
      .def_property_readonly("orientation_rate_hz", [](const TrialRecording& r) { return r.recording.orientation_rate_hz; },
                             "Rate of the attitude files before resampling onto t [Hz] (0 without attitude)")
      .def_property_readonly("mounting", [](const TrialRecording& r) { return r.recording.mounting; },
                             "The sensor → block mounting that was applied")
      .def_property_readonly("columns", [](const TrialRecording& r) { return r.recording.columns; },
                             "Source columns read, as 'file: header'")
      .def_property_readonly(
          "gaps",
          [](const TrialRecording& r) {
            py::list out;
            for (const io::Gap& g : r.recording.gaps) {
              py::dict d;
              d["index"] = g.index;
              d["t_s"] = g.t_s;
              d["duration_s"] = g.duration_s;
              d["missing"] = g.missing;
              out.append(MakeRecord("Gap", d));
            }
            return out;
          },
          "Dropped samples: Records with index, t_s [s], duration_s [s], missing")
      .def_property_readonly("warnings", [](const TrialRecording& r) { return r.recording.warnings; },
                             "Documented repairs that were applied")
      .def_readonly("block", &TrialRecording::block, "The manifest's block of this trial (rockfit.Block), or None")
      .def_readonly("block_id", &TrialRecording::block_id)
      .def_readonly("position", &TrialRecording::position)
      .def_readonly("notes", &TrialRecording::notes)
      .def_property_readonly("duration_s", [](const TrialRecording& r) { return r.recording.duration_s(); },
                             "t[-1] − t[0] [s]")
      .def("__len__", [](const TrialRecording& r) { return r.recording.size(); })
      .def("__repr__", &Repr);

  m.def(
      "load_recording",
      [](const PathArgument& path, std::optional<std::string> trial, const std::string& format,
         std::optional<double> rate, std::optional<std::string> mounting, std::optional<std::string> columns,
         const std::string& orientation) {
        app::RecordingArgs args;
        args.path = path.path;
        args.trial_id = trial.value_or("");
        args.format = format;
        args.rate_hz = rate;
        args.mounting = mounting.value_or("");
        args.columns = columns.value_or("");
        args.orientation = orientation;
        app::TrialInput input;
        {
          py::gil_scoped_release release;
          input = app::LoadTrialInput(args);
        }
        auto r = std::make_shared<TrialRecording>();
        r->recording = std::move(input.recording);
        r->trial = input.trial_id;
        if (input.manifest_block) r->block = input.manifest_block->ToBlock();
        r->block_id = input.labels.block_id;
        r->position = input.labels.position;
        r->notes = input.labels.notes;
        return r;
      },
      py::arg("path"), py::arg("trial") = py::none(), py::kw_only(), py::arg("format") = "auto",
      py::arg("rate") = py::none(), py::arg("mounting") = py::none(), py::arg("columns") = py::none(),
      py::arg("orientation") = "auto",
      "Reads one recording, as `rockfit inspect/metrics/fit PATH` do.\n\n"
      "path: an x-IMU GUI prefix (dir/LoggedData for dir/LoggedData_*.csv) or file, an x-IMU3 logger directory, a\n"
      "  CSV file, rockfit's HDF5 file, or a campaign manifest (.toml) with trial=ID (the recording then carries\n"
      "  the manifest's block, format, rate and mounting).\n"
      "trial: the trial id of a manifest or of an HDF5 file with several trials.\n"
      "format: 'auto', 'ximu-gui', 'ximu3', 'csv' (generic CSV) or 'rockfit-hdf5'.\n"
      "rate: gyro sample rate [Hz] when the files do not state it (x-IMU CSV without _Registers.csv).\n"
      "mounting: sensor axes on the block, 'x,-y,-z' or a quaternion 'w,x,y,z' (q_BS); default identity.\n"
      "columns: generic CSV column map, e.g. 'time=NAME@s;gyro=X,Y,Z@deg/s;euler=ROLL,PITCH,YAW@deg', or a preset\n"
      "  'phyphox' or 'sensor-logger' (a manifest trial or block gives it with columns = ...).\n"
      "orientation: attitude source 'auto', 'euler', 'quaternion', 'matrix' or 'none' (metrics then integrate the\n"
      "  attitude from the gyro, as for files without one).\n\n"
      "Returns a rockfit.Recording. Raises rockfit.InputError (file, line, column, what to do) for files that\n"
      "cannot be read, ValueError for options that do not fit.");
}

}  // namespace rockfit::python
