// The `rockfit` Python module: the block model, recordings, drift correction and metrics, the impact maps, the
// simulator, the fitter and synthetic recordings of the C++ libraries, with numpy arrays (python/README.md).
#include "bindings.hpp"

PYBIND11_MODULE(rockfit, m) {
  m.doc() =
      "rockfit: experimental rocking dynamics of rigid blocks (Várkonyi, Kocsis & Ther 2021).\n\n"
      "Units are SI everywhere (m, kg, s, rad, rad/s, J, N*m*s). Body frame B: origin at the centre of the base,\n"
      "x along b1, y along b2, z up; base vertices V1 = (-b1, -b2, 0), V2 = (-b1, b2, 0), V3 = (b1, b2, 0),\n"
      "V4 = (b1, -b2, 0). Equation numbers such as (28) refer to the paper.\n\n"
      "  Block(b1, b2, h, density=... | mass=...), Block.from_manifest(path, id)\n"
      "  load_recording(path, trial=None, ...), Recording(t, w_B, euler, ...)\n"
      "  metrics(recording, block)              drift correction, OPMF, AVRF, λ of (6)\n"
      "  edge_impact(...), facet_impact(...)    the impact maps (19)-(20), (18)+(21)\n"
      "  simulate(block, alpha=..., ...)        the hybrid simulator\n"
      "  fit(recording, block), fit_campaign(manifest)   minimise (28)\n"
      "  synth(prefix, block, ...)              a synthetic x-IMU recording with known truth\n\n"
      "Errors: ValueError (bad arguments), rockfit.InputError (bad files, a ValueError with .path, .line,\n"
      ".column), rockfit.NumericalError, rockfit.OutputError (an OSError).";
  // Every array the module returns is a numpy array: without numpy the first call would fail far from here.
  try {
    pybind11::module_::import("numpy");
  } catch (const pybind11::error_already_set&) {
    const std::string running = pybind11::str(pybind11::module_::import("sys").attr("executable"));
    throw pybind11::import_error(
        "rockfit needs numpy, which this interpreter (" + running + ") cannot import. Run rockfit with the "
        "interpreter it was built for, " ROCKFIT_PYTHON_EXECUTABLE " (apt-get install python3-numpy gives it numpy), "
        "or build it for this one with cmake -DPython3_EXECUTABLE=" + running + ".");
  }
  m.attr("__version__") = ROCKFIT_VERSION;
  rockfit::python::RegisterErrors(m);
  rockfit::python::RegisterRecord(m);
  rockfit::python::RegisterBlock(m);
  rockfit::python::RegisterRecording(m);
  rockfit::python::RegisterMetrics(m);
  rockfit::python::RegisterImpacts(m);
  rockfit::python::RegisterSimulate(m);
  rockfit::python::RegisterFit(m);
  rockfit::python::RegisterSynth(m);
  rockfit::python::RegisterValidate(m);
  rockfit::python::RegisterQuake(m);
  rockfit::python::RegisterReport(m);
}
