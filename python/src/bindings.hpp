// What the files of the rockfit Python module share: one registration function per area, numpy conversions and
// the Record type that results are returned in.
//
// Arrays: results move their std::vector storage into the returned numpy array (no copy; a capsule owns and
// frees it). Recording arrays are writable views into the C++ recording, kept alive by the Python object.
// Arrays given to rockfit are copied once into the library's std::vector storage.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <nlohmann/json.hpp>
#include <pybind11/eval.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "rockfit/core/block.hpp"
#include "rockfit/io/recording.hpp"

namespace rockfit::python {

namespace py = pybind11;

void RegisterErrors(py::module_& m);
void RegisterRecord(py::module_& m);
void RegisterBlock(py::module_& m);
void RegisterRecording(py::module_& m);
void RegisterMetrics(py::module_& m);
void RegisterImpacts(py::module_& m);
void RegisterSimulate(py::module_& m);
void RegisterFit(py::module_& m);
void RegisterSynth(py::module_& m);
void RegisterValidate(py::module_& m);
void RegisterQuake(py::module_& m);
void RegisterReport(py::module_& m);

// A recording as Python sees it (rockfit.Recording): the samples and the readers' metadata, the trial id, and the
// block and labels when it came from a campaign manifest.
struct TrialRecording {
  io::Recording recording;
  std::string trial;
  std::optional<core::Block> block;
  std::string block_id;
  std::string position;
  std::string notes;
};

// `given`, else the recording's manifest block; InvalidArgument saying that `what` needs the block otherwise.
core::Block BlockFor(const std::optional<core::Block>& given, const TrialRecording& recording, const char* what);

// ---------------------------------------------------------------------------------------------- arrays

// (N,) float64 owning the moved vector's storage.
py::array_t<double> OwnedArray(std::vector<double>&& values);
// (N, 3) float64 owning the moved vector's storage (Eigen::Vector3d is three packed doubles).
py::array_t<double> OwnedArray(std::vector<Eigen::Vector3d>&& vectors);
// (N, 4) float64 quaternions, scalar first (w, x, y, z): a copy, since Eigen stores (x, y, z, w).
py::array_t<double> QuaternionArray(const std::vector<Eigen::Quaterniond>& quaternions);
// (3,) float64 copy.
py::array_t<double> Vector3Array(const Eigen::Vector3d& v);
// Writable views into storage that `owner` keeps alive (the vector is never resized while the view lives).
py::array_t<double> ViewArray(std::vector<double>& values, py::handle owner);
py::array_t<double> ViewArray(std::vector<Eigen::Vector3d>& vectors, py::handle owner);

// Array arguments: a 1-D float array of length 3 (`name` in messages; ValueError otherwise).
Eigen::Vector3d ToVector3(const py::handle& value, const char* name);
// (N,) and (N, 3) arrays (any array-like convertible to float64); ValueError naming `name` for another shape.
std::vector<double> ToDoubles(const py::handle& value, const char* name);
std::vector<Eigen::Vector3d> ToVectors3(const py::handle& value, const char* name);

// ---------------------------------------------------------------------------------------------- results

// A result: named fields readable as attributes (r.epsilon) and as a mapping (r["epsilon"], r.keys(),
// r.to_dict()); `type_name` is shown by repr(). Fields are whatever the producing function put in `fields`,
// so new fields appear without API changes.
py::object MakeRecord(const std::string& type_name, py::dict fields);

// JSON → Python: objects become dicts, arrays lists, null None.
py::object FromJson(const nlohmann::json& value);

// The block of a result ("b1", "b2", "h", "mass" as in the program's JSON).
py::dict BlockDict(const core::Block& block);

}  // namespace rockfit::python
