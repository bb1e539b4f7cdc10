// rockfit.report: the campaign report of `rockfit report` (tools/src/report_builder.cpp, the same code): one
// self-contained HTML page from a campaign's HDF5 files; returns what `rockfit report --json` prints.
#include <fmt/format.h>

#include "bindings.hpp"
#include "path_argument.hpp"
#include "rockfit/app/report_builder.hpp"

namespace rockfit::python {
namespace {

std::vector<std::filesystem::path> Paths(const std::optional<std::vector<PathArgument>>& paths) {
  std::vector<std::filesystem::path> out;
  if (!paths) return out;
  for (const PathArgument& p : *paths) out.emplace_back(p.path);
  return out;
}

py::object Report(const PathArgument& summary, const PathArgument& output, const std::optional<PathArgument>& fits,
                  const std::optional<PathArgument>& validation, const std::optional<std::vector<PathArgument>>& fragility,
                  const std::optional<std::vector<PathArgument>>& responses, const std::string& title, bool figures) {
  app::ReportOptions options;
  options.inputs.summary = summary.path;
  if (fits) options.inputs.fits = fits->path;
  if (validation) options.inputs.validation = validation->path;
  options.inputs.fragility = Paths(fragility);
  options.inputs.responses = Paths(responses);
  options.title = title;
  options.figures = figures;
  options.rockfit_version = ROCKFIT_VERSION;
  options.command_line = fmt::format("rockfit.report('{}', '{}', ...) from Python", summary.path, output.path);
  app::ReportSummary s;
  {
    py::gil_scoped_release release;
    s = app::WriteReport(options, output.path);
  }
  nlohmann::json gaps = nlohmann::json::array();
  for (const app::Gap& g : s.gaps) gaps.push_back({{"where", g.where}, {"what", g.what}});
  const nlohmann::json j = {{"output", output.path},   {"trials", s.trials},
                            {"trials_fitted", s.trials_fitted}, {"figures", s.figures},
                            {"figures_missing", s.figures_missing}, {"gaps", gaps}, {"bytes", s.bytes}};
  return MakeRecord("Report", FromJson(j).cast<py::dict>());
}

}  // namespace

void RegisterReport(py::module_& m) {
  m.def("report", &Report, py::arg("summary"), py::arg("output"), py::kw_only(), py::arg("fits") = py::none(),
        py::arg("validation") = py::none(), py::arg("fragility") = py::none(),
        py::arg("responses") = py::none(), py::arg("title") = "Campaign report",
        py::arg("figures") = true,
        "One self-contained HTML page of a campaign, as `rockfit report SUMMARY -o OUTPUT`: overview (OPMF, AVRF,\n"
        "parameter ranges, warnings), one section per trial (angles, measured against simulated ω, parameters with\n"
        "68/95 % intervals, model error, mounting), the earthquake side and the provenance.\n\n"
        "summary: HDF5 of `rockfit summary -o`; fits: of `rockfit batch -o`; validation: of `rockfit validate -o`;\n"
        "fragility, responses: lists of files of `rockfit fragility -o` and `rockfit respond --format hdf5 -o`;\n"
        "figures=False writes tables only. Figures need gnuplot; without it the page names the missing ones.\n\n"
        "Returns a Record 'Report': output, trials, trials_fitted, figures, figures_missing, gaps (where, what:\n"
        "what the inputs lack, also stated on the page), bytes. Raises InputError for an unreadable summary file.\n"
        "The GIL is released while it runs.");
}

}  // namespace rockfit::python
