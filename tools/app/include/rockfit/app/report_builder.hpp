// The campaign report (`rockfit report`, `rockfit.report(...)` in Python): one self-contained HTML page from a
// campaign's HDF5 files (report_inputs.hpp) with inline CSS, inline SVG figures (report_figures.hpp) and a few
// lines of inline JavaScript that sort the tables. No network access is needed to open it, and it prints on A4
// without cutting a figure. No command-line parsing here: the program and the Python module share this code.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "rockfit/app/report_inputs.hpp"

namespace rockfit::app {

struct ReportOptions {
  ReportInputs inputs;
  std::string title = "Campaign report";
  std::string rockfit_version;  // shown in the provenance section
  std::string command_line;     // how the report was made (shown as given)
  std::string date_utc;         // ISO 8601; empty: now
  bool figures = true;          // false: tables only (every figure is listed as not drawn)
  // InvalidArgument when the summary is not given or the title is empty.
  void Validate() const;
};

struct ReportSummary {
  std::size_t trials = 0;          // trial sections on the page (the summary's trials)
  std::size_t trials_fitted = 0;   // of them, with a fit
  std::size_t figures = 0;         // figures drawn
  std::vector<std::string> figures_missing;  // "figure: reason" for every figure not drawn
  std::vector<Gap> gaps;           // what the inputs lack (also stated on the page)
  std::size_t bytes = 0;           // size of the page
};

// The page as text.
std::string BuildReportHtml(const ReportOptions& options, ReportSummary* summary = nullptr);
// Builds the page and writes it to `output` atomically (io/atomic_file.hpp). BadInput for an unreadable summary
// file, OutputError when `output` cannot be written.
ReportSummary WriteReport(const ReportOptions& options, const std::filesystem::path& output);

}  // namespace rockfit::app
