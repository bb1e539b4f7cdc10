// rockfit.validate: the predictive check of a campaign, as `rockfit validate MANIFEST --json` (the same code,
// tools/app/src/validation_run.cpp, and the same keys).
#include <fmt/format.h>

#include "bindings.hpp"
#include "rockfit/core/errors.hpp"
#include "rockfit/app/validation_run.hpp"

namespace rockfit::python {
namespace {

py::object Validate(const std::string& manifest, const std::optional<std::string>& fits, int jobs,
                    double ratio_warning, const std::string& method, const std::string& intervals,
                    const std::string& release_roll_mode) {
  app::ValidateArgs args;
  args.manifest = manifest;
  args.fits = fits.value_or("");
  args.jobs = jobs;
  args.ratio_warning = ratio_warning;
  args.fit.method = method;
  args.fit.intervals = intervals;
  args.fit.release_roll_mode = release_roll_mode;
  fitting::ValidationSummary summary;
  {
    py::gil_scoped_release release;
    summary = app::RunValidation(args);
  }
  nlohmann::json j = nlohmann::json::parse(fitting::ValidationJson(summary));
  j["manifest"] = manifest;
  j["fits"] = fits ? nlohmann::json(*fits) : nlohmann::json();
  return MakeRecord("Validation", FromJson(j).cast<py::dict>());
}

}  // namespace

void RegisterValidate(py::module_& m) {
  m.def("validate", &Validate, py::arg("manifest"), py::kw_only(), py::arg("fits") = py::none(), py::arg("jobs") = 0,
        py::arg("ratio_warning") = 1.5, py::arg("method") = "auto", py::arg("intervals") = "thorough",
        py::arg("release_roll_mode") = "auto",
        "The predictive check of a campaign, as `rockfit validate MANIFEST --json`: every trial of a block and\n"
        "position left out in turn, fitted only in its release (t0, α and, where its fit takes it, the release roll)\n"
        "with the others' pooled λ, λ_lat, λ_lon, its error (28) compared with its own fit's over the same window.\n\n"
        "fits: a file of `rockfit batch` holding every trial's own fit (default: fit them now, with method and\n"
        "intervals as `rockfit batch`); release_roll_mode: 'auto' (the release roll is fitted where the fall shows\n"
        "one), 'on' or 'off', as `--release-roll-mode`, for the own fits and the predictions; jobs: trials at once\n"
        "(0: all cores); ratio_warning: ε_pred/ε_own above it is reported as not transferring.\n\n"
        "Returns a Record 'Validation': trials (per trial: trial, block, position, predicted, message, n_others,\n"
        "epsilon_own, epsilon_pred, ratio, transfers, overlaps_all, t0, alpha, release_roll, release_roll_fitted,\n"
        "t_end, parameters: per λ name held, pooled, pooled_interval_95, n_pooled, overlaps), groups (block, position, n, n_predicted, median_ratio, max_ratio,\n"
        "n_transfer, n_overlap_all), ratio_warning, simulations, wall_s, manifest, fits. The GIL is released while\n"
        "it runs.");
}

}  // namespace rockfit::python
