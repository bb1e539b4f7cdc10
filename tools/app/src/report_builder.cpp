#include "rockfit/app/report_builder.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>
#include <cctype>
#include <functional>
#include <map>
#include <set>
#include <sstream>

#include <fmt/format.h>

#include "rockfit/app/html_escape.hpp"
#include "rockfit/app/report_figures.hpp"
#include "rockfit/core/errors.hpp"
#include "rockfit/io/atomic_file.hpp"

namespace rockfit::app {
namespace {

// ------------------------------------------------------------------ text helpers

// An id usable in HTML and in a URL fragment: letters, digits, '-' and '_' kept, anything else as '_'.
std::string Slug(const std::string& text) {
  std::string out;
  for (unsigned char c : text) out += std::isalnum(c) || c == '-' || c == '_' ? static_cast<char>(c) : '_';
  return out;
}

// A number with `digits` significant digits, "–" when not finite.
std::string Num(double v, int digits = 4) {
  if (!std::isfinite(v)) return "–";
  return fmt::format("{:.{}g}", v, digits);
}
std::string Num(const std::optional<double>& v, int digits = 4) { return v ? Num(*v, digits) : "–"; }

// An interval "[a, b]" whose open ends (NaN) read "open".
std::string IntervalText(double lower, double upper) {
  if (!std::isfinite(lower) && !std::isfinite(upper)) return "–";
  return fmt::format("[{}, {}]", std::isfinite(lower) ? Num(lower) : "open", std::isfinite(upper) ? Num(upper) : "open");
}

// A table cell whose sort key is numeric (data-sort), shown as text.
std::string NumCell(double v, int digits = 4) {
  return fmt::format("<td class=\"num\" data-sort=\"{}\">{}</td>", std::isfinite(v) ? fmt::format("{}", v) : "", Num(v, digits));
}
std::string NumCell(const std::optional<double>& v, int digits = 4) { return NumCell(v.value_or(std::nan("")), digits); }
std::string TextCell(const std::string& text) { return "<td>" + EscapeHtml(text) + "</td>"; }
// A cell sorted by `value` and showing `text` (a value with its interval).
std::string ValueCell(double value, const std::string& text) {
  return fmt::format("<td class=\"interval\" data-sort=\"{}\">{}</td>", std::isfinite(value) ? fmt::format("{}", value) : "",
                     EscapeHtml(text));
}
std::string IntervalCell(const std::string& text) { return "<td class=\"interval\">" + EscapeHtml(text) + "</td>"; }

// <table> with caption and header row; `sortable` adds the sort buttons (script below).
std::string TableStart(const std::string& caption, const std::vector<std::string>& headers, bool sortable = true) {
  std::string out = fmt::format("<div class=\"table-wrap\"><table{}>\n<caption>{}</caption>\n<thead><tr>",
                                sortable ? " class=\"sortable\"" : "", EscapeHtml(caption));
  for (const std::string& h : headers) out += "<th scope=\"col\">" + EscapeHtml(h) + "</th>";
  return out + "</tr></thead>\n<tbody>\n";
}
const char* kTableEnd = "</tbody></table></div>\n";

// The trial's parameters as the paper writes them.
std::string ParameterLabel(const std::string& name) {
  static const std::map<std::string, std::string> kLabels = {{"t0", "t₀"},           {"alpha", "α"},
                                                             {"lambda", "λ"},        {"lambda_lat", "λ_lat"},
                                                             {"lambda_lon", "λ_lon"}, {"tau_edge", "τ_edge"}};
  const auto it = kLabels.find(name);
  return it == kLabels.end() ? name : it->second;
}

// The kind of a warning "kind: message".
std::string WarningKind(const std::string& warning) {
  const std::size_t colon = warning.find(':');
  return colon == std::string::npos ? warning : warning.substr(0, colon);
}

std::string NowUtc() {
  const std::time_t now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  std::tm tm{};
  gmtime_r(&now, &tm);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return text;
}

// ------------------------------------------------------------------ page pieces

const char* kStyle = R"CSS(
:root { --ink: #1a1a1a; --muted: #555; --rule: #ccc; --warn: #8a4b00; --warn-bg: #fff6e5; --bad: #a40000; }
* { box-sizing: border-box; }
body { font: 15px/1.45 system-ui, -apple-system, "Segoe UI", Roboto, "DejaVu Sans", sans-serif; color: var(--ink);
       margin: 0 auto; max-width: 1000px; padding: 1rem 1.5rem 3rem; }
h1 { font-size: 1.7rem; margin: 0.5rem 0 0.2rem; }
h2 { font-size: 1.35rem; border-bottom: 2px solid var(--rule); padding-bottom: 0.2rem; margin-top: 2.2rem; }
h3 { font-size: 1.1rem; margin-top: 1.6rem; }
.meta { color: var(--muted); margin: 0; }
nav > ol { padding-left: 1.2rem; }
nav ol ol { display: flex; flex-wrap: wrap; gap: 0 1rem; list-style: none; padding-left: 0; }
.table-wrap { overflow-x: auto; margin: 0.8rem 0 1.2rem; }
table { border-collapse: collapse; font-size: 0.9rem; }
caption { text-align: left; font-weight: 600; padding-bottom: 0.3rem; caption-side: top; }
th, td { border-bottom: 1px solid var(--rule); padding: 0.25rem 0.6rem; text-align: left; vertical-align: top; }
th { background: #f2f2f2; }
td.num { text-align: right; font-variant-numeric: tabular-nums; white-space: nowrap; }
td.interval { white-space: nowrap; font-variant-numeric: tabular-nums; }
th button { all: inherit; display: inline; border: 0; background: none; cursor: pointer; padding: 0; }
th button::after { content: "\00a0↕"; color: #999; }
th[aria-sort="ascending"] button::after { content: "\00a0↑"; color: var(--ink); }
th[aria-sort="descending"] button::after { content: "\00a0↓"; color: var(--ink); }
figure { margin: 1rem 0 1.4rem; break-inside: avoid; page-break-inside: avoid; }
figure svg.plot { display: block; width: 100%; height: auto; max-width: 900px; }
figcaption { color: var(--muted); font-size: 0.9rem; margin-top: 0.3rem; }
.figure-missing .missing { border: 1px dashed var(--bad); color: var(--bad); padding: 1rem; margin: 0; }
.notice { background: var(--warn-bg); border-left: 4px solid var(--warn); padding: 0.5rem 1rem; margin: 1rem 0; }
.notice h3 { margin-top: 0.3rem; }
.warnings li { color: var(--warn); }
dl.facts { display: grid; grid-template-columns: max-content 1fr; gap: 0.15rem 1rem; margin: 0.5rem 0; }
dl.facts dt { color: var(--muted); }
dl.facts dd { margin: 0; }
code { font-size: 0.85rem; word-break: break-all; }
section.trial { border-top: 1px solid var(--rule); }
@page { size: A4; margin: 14mm 12mm; }
@media print {
  body { max-width: none; padding: 0; font-size: 10.5pt; }
  nav, th button::after { display: none; }
  h2, h3 { break-after: avoid; page-break-after: avoid; }
  section.trial { break-before: page; page-break-before: always; border-top: none; }
  table { break-inside: auto; font-size: 8.5pt; }
  tr { break-inside: avoid; }
  .table-wrap { overflow: visible; }
  figure svg.plot { max-width: 100%; max-height: 230mm; }
}
)CSS";

// Sorts a table by a column on a click on its header button; numbers by data-sort, text otherwise.
const char* kScript = R"JS(
(function () {
  'use strict';
  document.querySelectorAll('table.sortable').forEach(function (table) {
    var headers = table.tHead.rows[0].cells;
    Array.prototype.forEach.call(headers, function (th, column) {
      var button = document.createElement('button');
      button.type = 'button';
      button.textContent = th.textContent;
      th.textContent = '';
      th.appendChild(button);
      button.addEventListener('click', function () {
        var ascending = th.getAttribute('aria-sort') !== 'ascending';
        Array.prototype.forEach.call(headers, function (h) { h.removeAttribute('aria-sort'); });
        th.setAttribute('aria-sort', ascending ? 'ascending' : 'descending');
        var body = table.tBodies[0];
        var rows = Array.prototype.slice.call(body.rows);
        var key = function (row) {
          var cell = row.cells[column];
          if (!cell) return '';
          var sort = cell.getAttribute('data-sort');
          if (sort !== null) return sort === '' ? NaN : parseFloat(sort);
          return cell.textContent.trim();
        };
        rows.sort(function (a, b) {
          var x = key(a), y = key(b), order;
          if (typeof x === 'number' && typeof y === 'number') {
            if (isNaN(x)) return 1;
            if (isNaN(y)) return -1;
            order = x - y;
          } else {
            order = String(x).localeCompare(String(y), undefined, { numeric: true });
          }
          return ascending ? order : -order;
        });
        rows.forEach(function (row) { body.appendChild(row); });
      });
    });
  });
})();
)JS";

class Page {
 public:
  Page(const ReportOptions& options, ReportSummary& summary) : options_(options), summary_(summary) {}

  // A figure with its caption, or the statement that it is missing and why.
  void Figure(const std::string& name, ReportFigure figure, const std::string& caption) {
    ++figure_number_;
    const std::string label = fmt::format("Figure {}.", figure_number_);
    if (figure.ok()) {
      ++summary_.figures;
      out_ << fmt::format("<figure class=\"figure\" data-figure=\"{}\">\n{}\n<figcaption><strong>{}</strong> {}</figcaption>"
                          "</figure>\n",
                          EscapeHtml(name), figure.svg, label, EscapeHtml(caption));
    } else {
      summary_.figures_missing.push_back(name + ": " + figure.missing);
      out_ << fmt::format("<figure class=\"figure figure-missing\" data-figure=\"{}\">\n<p class=\"missing\" role=\"note\">"
                          "Figure missing: {}</p>\n<figcaption><strong>{}</strong> {}</figcaption></figure>\n",
                          EscapeHtml(name), EscapeHtml(figure.missing), label, EscapeHtml(caption));
    }
  }
  ReportFigure Draw(const std::function<ReportFigure()>& draw) {
    if (!options_.figures) {
      ReportFigure f;
      f.missing = "figures were turned off when this report was written (--no-figures)";
      return f;
    }
    return draw();
  }
  std::string NextId() { return fmt::format("f{}", figure_number_ + 1); }
  std::ostringstream& out() { return out_; }

 private:
  const ReportOptions& options_;
  ReportSummary& summary_;
  std::ostringstream out_;
  int figure_number_ = 0;
};

void WriteGaps(Page& page, const std::vector<Gap>& gaps) {
  if (gaps.empty()) return;
  auto& out = page.out();
  out << "<section class=\"notice\" id=\"missing\" aria-labelledby=\"missing-title\">\n"
         "<h3 id=\"missing-title\">What this report could not show</h3>\n<ul>\n";
  for (const Gap& g : gaps) out << "<li><strong>" << EscapeHtml(g.where) << "</strong> " << EscapeHtml(g.what) << "</li>\n";
  out << "</ul></section>\n";
}

void WriteOverview(Page& page, const ReportData& data) {
  auto& out = page.out();
  const io::CampaignSummary& s = data.summary;
  std::set<std::string> blocks, positions;
  for (const io::GroupRow& g : s.groups) blocks.insert(g.block_id), positions.insert(g.position);
  std::size_t fitted = 0;
  for (const ReportTrial& t : data.trials) fitted += t.fit ? 1 : 0;
  out << "<section id=\"overview\" aria-labelledby=\"overview-title\">\n<h2 id=\"overview-title\">Overview</h2>\n";
  out << fmt::format("<p>{} blocks, {} positions, {} trials ({} with a fit).</p>\n", blocks.size(), positions.size(),
                     data.trials.size(), fitted);
  WriteGaps(page, data.gaps);

  out << TableStart("Blocks and positions: OPMF and AVRF, mean ± sample standard deviation over the trials",
                    {"block", "position", "b₁ [m]", "b₂ [m]", "h [m]", "trials", "OPMF mean [1]", "OPMF std [1]",
                     "AVRF mean [1]", "AVRF std [1]"});
  for (const io::GroupRow& g : s.groups) {
    out << "<tr>" << TextCell(g.block_id) << TextCell(g.position) << NumCell(g.b1_m) << NumCell(g.b2_m) << NumCell(g.h_m)
        << NumCell(static_cast<double>(g.n_trials)) << NumCell(g.opmf_mean) << NumCell(g.opmf_std)
        << NumCell(g.avrf_mean) << NumCell(g.avrf_std) << "</tr>\n";
  }
  out << kTableEnd;
  page.Figure("summary", page.Draw([&] { return SummaryFigure(s, page.NextId()); }),
              "Out-of-plane motion factor Φ and angular velocity reduction factor r against the base length b₂, mean ± "
              "sample standard deviation per block and position; circles: single trials (the paper's Fig. 6).");

  if (!data.fit_groups.empty()) {
    out << TableStart("Impact parameters per block and position: pooled estimate [95 % interval] (else the mean of "
                      "the trials, marked “mean”); α: mean ± spread between the trials",
                      {"block", "position", "fits", "λ [1]", "λ_lat [1]", "λ_lon [1]", "α [rad]"});
    for (const fitting::GroupSummary& g : data.fit_groups) {
      out << "<tr>" << TextCell(g.block) << TextCell(g.position) << NumCell(static_cast<double>(g.n));
      for (const char* name : {"lambda", "lambda_lat", "lambda_lon"}) {
        const auto p = g.pooled.find(name);
        const bool pooled = p != g.pooled.end() && p->second.n_pooled > 0 && std::isfinite(p->second.pooled);
        const auto mean = g.mean.find(name);
        const double value = pooled ? p->second.pooled : (mean != g.mean.end() ? mean->second : std::nan(""));
        const std::string text = pooled ? Num(value) + " " + IntervalText(p->second.interval_95[0], p->second.interval_95[1])
                                        : Num(value) + " (mean)";
        out << ValueCell(value, text);
      }
      const auto alpha = g.mean.find("alpha");
      const auto alpha_sd = g.std_dev.find("alpha");
      const double alpha_mean = alpha != g.mean.end() ? alpha->second : std::nan("");
      out << ValueCell(alpha_mean, Num(alpha_mean) + " ± " + Num(alpha_sd != g.std_dev.end() ? alpha_sd->second : std::nan(""), 2))
          << "</tr>\n";
    }
    out << kTableEnd;
    page.Figure("parameter-ranges", page.Draw([&] { return ParameterRangesFigure(data.fit_groups, page.NextId()); }),
                "Pooled impact parameters λ, λ_lat, λ_lon per block and position with their 95 % intervals (the "
                "paper's Fig. 15).");
  }

  // Warnings counted by kind: the fits' warnings and the trials whose metrics or mounting were not clean.
  std::map<std::string, int> counts;
  for (const ReportTrial& t : data.trials) {
    if (t.row.status != io::MetricsStatus::kOk) ++counts[std::string("metrics: ") + io::ToString(t.row.status)];
    if (!t.row.mounting_check.warning.empty()) ++counts["mounting"];
    if (t.fit) {
      std::set<std::string> kinds;
      for (const std::string& w : t.fit->warnings) kinds.insert(WarningKind(w));
      for (const std::string& k : kinds) ++counts["fit: " + k];
      if (!t.fit->labels.feasible) ++counts["fit: infeasible"];
    }
  }
  if (counts.empty()) {
    out << "<p>No trial has a warning.</p>\n";
  } else {
    out << TableStart("Warnings by kind (trials with at least one of that kind; each is explained in its trial's section)",
                      {"kind", "trials"});
    for (const auto& [kind, n] : counts) out << "<tr>" << TextCell(kind) << NumCell(static_cast<double>(n)) << "</tr>\n";
    out << kTableEnd;
  }
  out << "</section>\n";
}

bool HasModelError(const TrialFit& fit) {
  return fit.labels.model_error_dominates >= 0 && std::isfinite(fit.labels.noise_floor_rad_s);
}

void WriteModelError(Page& page, const ReportData& data) {
  bool any = false;
  for (const ReportTrial& t : data.trials) any = any || (t.fit && HasModelError(*t.fit));
  if (!any) return;
  auto& out = page.out();
  out << "<section id=\"model-error\" aria-labelledby=\"model-error-title\">\n<h2 id=\"model-error-title\">Model error"
         "</h2>\n<p>The fitted error ε of (28) splits into the sensor noise measured at rest before the release (the "
         "noise floor) and the model error, which add in quadrature: ε² ≈ ε_noise² + ε_model².</p>\n";
  out << TableStart("Error of each fit: noise floor and model error",
                    {"trial", "block", "position", "ε [rad/s]", "noise floor [rad/s]", "model error [rad/s]",
                     "noise share of ε² [%]", "model error dominates"});
  for (const ReportTrial& t : data.trials) {
    if (!t.fit || !HasModelError(*t.fit)) continue;
    const fitting::StoredFitLabels& l = t.fit->labels;
    out << "<tr>" << TextCell(t.row.trial_id) << TextCell(t.row.block_id) << TextCell(t.row.position)
        << NumCell(l.epsilon_rad_s) << NumCell(l.noise_floor_rad_s) << NumCell(l.model_error_rad_s)
        << NumCell(100.0 * l.noise_share, 3) << TextCell(l.model_error_dominates == 1 ? "yes" : "no") << "</tr>\n";
  }
  out << kTableEnd << "</section>\n";
}

void WriteValidation(Page& page, const ReportData& data) {
  if (!data.validation) return;
  const fitting::ValidationSummary& v = *data.validation;
  auto& out = page.out();
  out << "<section id=\"validation\" aria-labelledby=\"validation-title\">\n<h2 id=\"validation-title\">Predictive "
         "check</h2>\n<p>Each trial left out of its block and position in turn, fitted only in t₀ and α with the other "
         "trials' pooled λ, λ_lat, λ_lon; ε_pred/ε_own near 1 means the parameters transfer between trials of the "
         "group.</p>\n";
  out << TableStart("Predictive check per trial",
                    {"trial", "block", "position", "predicted", "ε_own [rad/s]", "ε_pred [rad/s]", "ε_pred/ε_own [1]",
                     "transfers", "intervals overlap", "note"});
  for (const fitting::TrialPrediction& t : v.trials) {
    out << "<tr>" << TextCell(t.trial) << TextCell(t.block) << TextCell(t.position) << TextCell(t.predicted ? "yes" : "no")
        << NumCell(t.epsilon_own_rad_s) << NumCell(t.predicted ? t.epsilon_pred_rad_s : std::nan(""))
        << NumCell(t.predicted ? t.ratio : std::nan("")) << TextCell(t.predicted ? (t.transfers ? "yes" : "no") : "–")
        << TextCell(t.predicted ? (t.overlaps_all ? "all" : "not all") : "–") << TextCell(t.message) << "</tr>\n";
  }
  out << kTableEnd;
  if (!v.groups.empty()) {
    out << TableStart("Predictive check per block and position",
                      {"block", "position", "trials", "predicted", "median ratio [1]", "largest ratio [1]", "transfer"});
    for (const fitting::GroupValidation& g : v.groups) {
      out << "<tr>" << TextCell(g.block) << TextCell(g.position) << NumCell(g.n) << NumCell(g.n_predicted)
          << NumCell(g.median_ratio) << NumCell(g.max_ratio) << NumCell(g.n_transfer) << "</tr>\n";
    }
    out << kTableEnd;
  }
  out << "</section>\n";
}

void WriteEarthquake(Page& page, const ReportData& data) {
  if (data.fragility.empty() && data.responses.empty()) return;
  auto& out = page.out();
  out << "<section id=\"earthquake\" aria-labelledby=\"earthquake-title\">\n<h2 id=\"earthquake-title\">Earthquake "
         "side</h2>\n";
  for (const FragilityBlock& b : data.fragility) {
    out << "<h3>Fragility of " << EscapeHtml(b.block_id) << "</h3>\n";
    out << TableStart("Lognormal fragility curves of " + b.block_id + " (" + b.file + ")",
                      {"limit state", "curve", b.intensity_is_pga_g ? "median θ [g]" : "median θ [1]", "β [1]", "note"});
    for (const FragilityLimitState& s : b.limit_states) {
      const bool ok = s.curve_ok;
      out << "<tr>" << TextCell(s.name) << TextCell(s.curve_status) << NumCell(ok ? s.median : std::nan(""))
          << NumCell(ok ? s.beta : std::nan("")) << TextCell(s.curve_message) << "</tr>\n";
    }
    out << kTableEnd;
    page.Figure("fragility-" + Slug(b.block_id), page.Draw([&] { return FragilityFigure(b, page.NextId()); }),
                "Fragility of " + b.block_id + ": observed probabilities with their 95 % Clopper–Pearson band "
                "and the fitted lognormal curves.");
  }
  for (const ResponseHistory& r : data.responses) {
    const std::string name = r.block_id.empty() ? "a block of another size" : r.block_id;
    out << "<h3>Response of " << EscapeHtml(name) << "</h3>\n";
    out << fmt::format("<p>{}: {}; peak tilt {} rad ({} % of the critical tilt {} rad); {}.</p>\n", EscapeHtml(r.file),
                       EscapeHtml(r.end_reason.empty() ? "end not recorded" : r.end_reason), Num(r.peak_tilt_rad),
                       r.critical_tilt_rad > 0 ? Num(100.0 * r.peak_tilt_rad / r.critical_tilt_rad, 3) : "–",
                       Num(r.critical_tilt_rad), r.overturned ? "the block overturned" : "the block did not overturn");
    page.Figure("response-" + Slug(r.file), page.Draw([&] { return ResponseFigure(r, page.NextId()); }),
                "Response of " + name + " to ground motion: ground acceleration, tilt and angular velocity against time.");
  }
  out << "</section>\n";
}

void WriteTrial(Page& page, const ReportTrial& t) {
  auto& out = page.out();
  const io::TrialRow& r = t.row;
  const std::string id = "trial-" + Slug(r.trial_id);
  out << fmt::format("<section class=\"trial\" id=\"{}\" data-trial=\"{}\" aria-labelledby=\"{}-title\">\n"
                     "<h3 id=\"{}-title\">Trial {}</h3>\n",
                     id, EscapeHtml(r.trial_id), id, id, EscapeHtml(r.trial_id));
  out << "<dl class=\"facts\">\n";
  out << "<dt>block, position</dt><dd>" << EscapeHtml(r.block_id) << ", " << EscapeHtml(r.position) << "</dd>\n";
  out << "<dt>metrics</dt><dd>" << EscapeHtml(io::ToString(r.status)) << (r.message.empty() ? "" : " — " + EscapeHtml(r.message)) << "</dd>\n";
  out << fmt::format("<dt>OPMF, AVRF</dt><dd>Φ = {}, r = {} ({} impacts detected)</dd>\n", Num(r.opmf), Num(r.avrf), r.impacts);
  std::string mounting = r.mounting + (r.mounting_check.estimated ? " (estimated from the data)" : " (given)");
  if (r.mounting_check.status != io::MountingStatus::kNotChecked) {
    mounting += std::string("; check: ") + io::ToString(r.mounting_check.status);
  }
  if (!r.mounting_check.message.empty()) mounting += " — " + r.mounting_check.message;
  out << "<dt>mounting</dt><dd>" << EscapeHtml(mounting) << "</dd>\n";
  if (t.fit) {
    const fitting::StoredFitLabels& l = t.fit->labels;
    std::string split;
    if (HasModelError(*t.fit)) {
      split = fmt::format("ε = {} rad/s: the sensor noise explains {} % of ε² (noise floor {} rad/s), the model error is "
                          "{} rad/s; {}.",
                          Num(l.epsilon_rad_s), Num(100.0 * l.noise_share, 3), Num(l.noise_floor_rad_s),
                          Num(l.model_error_rad_s),
                          l.model_error_dominates == 1 ? "the model error dominates" : "the noise dominates");
    } else {
      split = fmt::format("ε = {} rad/s; its split into noise and model error was not measured (no rest before the "
                          "release, or a fit written before the split existed).", Num(l.epsilon_rad_s));
    }
    out << "<dt>error (28)</dt><dd>" << EscapeHtml(split) << "</dd>\n";
    if (!l.release_tilt_check.empty()) {
      out << "<dt>α against the tilt at rest</dt><dd>" << EscapeHtml(l.release_tilt_check) << "</dd>\n";
    }
    out << "<dt>fit</dt><dd>" << (l.feasible ? "feasible" : "infeasible") << ", " << l.simulations << " simulations"
        << (t.fit->termination.empty() ? "" : ", " + EscapeHtml(t.fit->termination)) << "</dd>\n";
  }
  out << "</dl>\n";

  // Warnings in words.
  std::vector<std::string> warnings;
  if (!r.mounting_check.warning.empty()) warnings.push_back("mounting: " + r.mounting_check.warning);
  if (t.fit) warnings.insert(warnings.end(), t.fit->warnings.begin(), t.fit->warnings.end());
  if (!warnings.empty()) {
    out << "<h4>Warnings</h4>\n<ul class=\"warnings\">\n";
    for (const std::string& w : warnings) out << "<li>" << EscapeHtml(w) << "</li>\n";
    out << "</ul>\n";
  }

  if (t.angles) {
    page.Figure("angles-" + r.trial_id, page.Draw([&] { return AnglesFigure(r.trial_id, *t.angles, page.NextId()); }),
                "Trial " + r.trial_id + ": measured (a) and drift-corrected (b) Euler angles φ_x, φ_y with the detected "
                "impacts (the paper's Fig. 5).");
  }
  if (t.fit) {
    page.Figure("fit-" + r.trial_id, page.Draw([&] { return FitFigure(r.trial_id, *t.fit, page.NextId()); }),
                "Trial " + r.trial_id + ": measured (grey) and simulated (colour) angular velocity ω_x, ω_y, ω_z at the "
                "fitted parameters over the window of (28) (the paper's Fig. 14).");
    const fitting::StoredParameters& p = t.fit->parameters;
    out << TableStart("Fitted parameters of " + r.trial_id + " with 68 % and 95 % intervals",
                      {"parameter", "unit", "value", "68 % interval", "95 % interval", "determined"}, false);
    for (std::size_t k = 0; k < p.size(); ++k) {
      const bool intervals = p.has_intervals && k < p.interval_95_lower.size();
      out << "<tr><th scope=\"row\">" << EscapeHtml(ParameterLabel(p.name[k])) << "</th>" << TextCell(p.unit[k])
          << NumCell(p.value[k], 5)
          << IntervalCell(intervals ? IntervalText(p.interval_68_lower[k], p.interval_68_upper[k]) : "–")
          << IntervalCell(intervals ? IntervalText(p.interval_95_lower[k], p.interval_95_upper[k]) : "–")
          << TextCell(k < p.determined.size() ? p.determined[k] : (k < p.fixed.size() && p.fixed[k] ? "fixed" : "–"))
          << "</tr>\n";
    }
    out << kTableEnd;
  } else {
    out << "<p class=\"notice\">No fit of this trial in the inputs: no fitted parameters, no measured-against-simulated "
           "figure.</p>\n";
  }
  out << "</section>\n";
}

void WriteProvenance(Page& page, const ReportData& data, const ReportOptions& options, const std::string& date) {
  auto& out = page.out();
  out << "<section id=\"provenance\" aria-labelledby=\"provenance-title\">\n<h2 id=\"provenance-title\">Provenance</h2>\n"
         "<dl class=\"facts\">\n";
  out << "<dt>written</dt><dd>" << EscapeHtml(date) << "</dd>\n";
  out << "<dt>rockfit</dt><dd>" << EscapeHtml(options.rockfit_version.empty() ? "unknown" : options.rockfit_version) << "</dd>\n";
  out << "<dt>command</dt><dd><code>" << EscapeHtml(options.command_line.empty() ? "(not given)" : options.command_line)
      << "</code></dd>\n";
  out << "</dl>\n";
  if (!data.fit_settings.empty()) {
    out << TableStart("Settings of the fits (the canonical text stored with each fit and its FNV-1a 64 hash)",
                      {"settings hash", "fits", "settings"}, false);
    for (const auto& [hash, settings] : data.fit_settings) {
      std::string trials;
      for (const std::string& t : settings.trials) trials += (trials.empty() ? "" : ", ") + t;
      out << "<tr><td><code>" << EscapeHtml(hash) << "</code></td>" << TextCell(trials) << "<td><code>"
          << EscapeHtml(settings.text) << "</code></td></tr>\n";
    }
    out << kTableEnd;
  }
  out << TableStart("Input files (content hash: FNV-1a 64 of the bytes)",
                    {"role", "file", "size [bytes]", "content hash", "written by rockfit", "study settings hash"}, false);
  for (const InputFile& f : data.files) {
    out << "<tr>" << TextCell(f.role) << "<td><code>" << EscapeHtml(f.path.string()) << "</code></td>"
        << NumCell(static_cast<double>(f.size_bytes), 12) << "<td><code>" << EscapeHtml(f.content_hash) << "</code></td>"
        << TextCell(f.rockfit_version.empty() ? "–" : f.rockfit_version) << "<td><code>"
        << EscapeHtml(f.settings_hash.empty() ? "–" : f.settings_hash) << "</code></td></tr>\n";
  }
  out << kTableEnd << "</section>\n";
}

}  // namespace

void ReportOptions::Validate() const {
  if (inputs.summary.empty()) {
    throw InvalidArgument("the report needs the campaign summary: the HDF5 file of `rockfit summary MANIFEST -o FILE`");
  }
  if (title.empty()) throw InvalidArgument("the report title is empty");
}

std::string BuildReportHtml(const ReportOptions& options, ReportSummary* summary_out) {
  options.Validate();
  ReportSummary summary;
  const ReportData data = ReadReportData(options.inputs);
  const std::string date = options.date_utc.empty() ? NowUtc() : options.date_utc;
  Page page(options, summary);
  WriteOverview(page, data);
  WriteModelError(page, data);
  WriteValidation(page, data);
  WriteEarthquake(page, data);
  page.out() << "<section id=\"trials\" aria-labelledby=\"trials-title\">\n<h2 id=\"trials-title\">Trials</h2>\n";
  for (const ReportTrial& t : data.trials) {
    WriteTrial(page, t);
    ++summary.trials;
    summary.trials_fitted += t.fit ? 1 : 0;
  }
  page.out() << "</section>\n";
  WriteProvenance(page, data, options, date);

  std::ostringstream html;
  html << "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
          "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n"
       << "<meta name=\"generator\" content=\"rockfit " << EscapeHtml(options.rockfit_version) << "\">\n"
       << "<title>" << EscapeHtml(options.title) << "</title>\n<style>" << kStyle << "</style>\n</head>\n<body>\n";
  html << "<header>\n<h1>" << EscapeHtml(options.title) << "</h1>\n<p class=\"meta\">Written " << EscapeHtml(date)
       << " by rockfit " << EscapeHtml(options.rockfit_version) << " from " << EscapeHtml(options.inputs.summary.filename().string())
       << (options.inputs.fits.empty() ? "" : " and " + EscapeHtml(options.inputs.fits.filename().string()))
       << " (all inputs under <a href=\"#provenance\">Provenance</a>).</p>\n</header>\n";
  html << "<nav aria-label=\"Contents\"><ol>\n<li><a href=\"#overview\">Overview</a></li>\n";
  if (page.out().str().find("id=\"model-error\"") != std::string::npos) html << "<li><a href=\"#model-error\">Model error</a></li>\n";
  if (data.validation) html << "<li><a href=\"#validation\">Predictive check</a></li>\n";
  if (!data.fragility.empty() || !data.responses.empty()) html << "<li><a href=\"#earthquake\">Earthquake side</a></li>\n";
  html << "<li><a href=\"#trials\">Trials</a><ol>\n";
  for (const ReportTrial& t : data.trials) {
    html << "<li><a href=\"#trial-" << Slug(t.row.trial_id) << "\">" << EscapeHtml(t.row.trial_id) << "</a></li>\n";
  }
  html << "</ol></li>\n<li><a href=\"#provenance\">Provenance</a></li>\n</ol></nav>\n<main>\n"
       << page.out().str() << "</main>\n<script>" << kScript << "</script>\n</body>\n</html>\n";
  summary.gaps = data.gaps;
  std::string text = html.str();
  summary.bytes = text.size();
  if (summary_out) *summary_out = summary;
  return text;
}

ReportSummary WriteReport(const ReportOptions& options, const std::filesystem::path& output) {
  ReportSummary summary;
  const std::string html = BuildReportHtml(options, &summary);
  io::WriteFileAtomically(output, [&](std::ostream& out) { out << html; });
  return summary;
}

}  // namespace rockfit::app
