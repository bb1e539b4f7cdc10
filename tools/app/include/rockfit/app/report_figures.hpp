// The figures of a campaign report (report_builder.hpp) drawn with gnuplot's svg terminal and returned as SVG
// text ready to be placed inline in an HTML page: no XML prolog, element ids made unique per figure, no fixed
// size (the page scales it). Without gnuplot, or when gnuplot fails, a figure carries the reason instead of SVG.
#pragma once

#include <string>

#include "rockfit/app/report_inputs.hpp"

namespace rockfit::app {

struct ReportFigure {
  std::string svg;      // inline <svg>…</svg>; empty when missing
  std::string missing;  // why there is no picture (empty when there is one)
  bool ok() const { return !svg.empty(); }
};

// Makes gnuplot's SVG fit for inline use: drops everything before <svg and the fixed width/height, prefixes
// every id (and the references to it) with `id_prefix`, and labels it for assistive technology with `label`.
std::string InlineSvg(const std::string& gnuplot_svg, const std::string& id_prefix, const std::string& label);

// The figures; `id_prefix` must be unique within the page. Each draws what the data allow and fails (missing)
// only for a missing gnuplot, a gnuplot error, or no data at all.
// OPMF and AVRF mean ± std against b2 per position, single trials as dots (the paper's Fig. 6).
ReportFigure SummaryFigure(const io::CampaignSummary& summary, const std::string& id_prefix);
// Pooled λ, λ_lat, λ_lon with their 95 % intervals per block and position (Fig. 15).
ReportFigure ParameterRangesFigure(const std::vector<fitting::GroupSummary>& groups, const std::string& id_prefix);
// Raw and drift-corrected Euler angles of one trial with the detected impacts (Fig. 5).
ReportFigure AnglesFigure(const std::string& trial, const TrialAngles& angles, const std::string& id_prefix);
// Measured against simulated ω per component over the window of (28) (Fig. 14).
ReportFigure FitFigure(const std::string& trial, const TrialFit& fit, const std::string& id_prefix);
// Observed probabilities with their 95 % band and the lognormal curves of one block.
ReportFigure FragilityFigure(const FragilityBlock& block, const std::string& id_prefix);
// Ground acceleration, tilt and ω against time.
ReportFigure ResponseFigure(const ResponseHistory& response, const std::string& id_prefix);

}  // namespace rockfit::app
