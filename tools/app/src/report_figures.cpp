#include "rockfit/app/report_figures.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <iterator>
#include <limits>
#include <regex>
#include <set>

#include <fmt/format.h>

#include "rockfit/app/gnuplot.hpp"
#include "rockfit/app/html_escape.hpp"

namespace rockfit::app {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
// Time shown before the first and after the last detected impact in the angles figure [s] (as `plot euler`).
constexpr double kMarginAroundImpacts_s = 0.5;
// Every figure is drawn at this width [px]; the page scales it to the column (and to an A4 page when printed).
constexpr int kFigureWidth_px = 900;

const char* const kColours[3] = {"#d62728", "#1f77b4", "#2ca02c"};  // x, y, z
const char* const kPalette[] = {"#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#8c564b", "#e377c2"};

const char* kNoGnuplot =
    "gnuplot was not found when this report was written (install it with `apt-get install gnuplot-nox` and run "
    "`rockfit report` again)";

std::string Join(const std::vector<std::string>& parts, const std::string& separator) {
  std::string out;
  for (const std::string& p : parts) out += (out.empty() ? "" : separator) + p;
  return out;
}


// Draws `body` on `figure` and returns the inline SVG, or the reason it could not.
ReportFigure Draw(const GnuplotFigure& figure, const std::string& body, int height_px, const std::string& id_prefix,
                  const std::string& label) {
  ReportFigure result;
  if (!FindGnuplot()) {
    result.missing = kNoGnuplot;
    return result;
  }
  const std::filesystem::path output = figure.directory() / "figure.svg";
  try {
    figure.Render("set termoption font 'Sans,12'\n" + body, output, kFigureWidth_px, height_px);
    std::ifstream in(output, std::ios::binary);
    const std::string svg((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    result.svg = InlineSvg(svg, id_prefix, label);
  } catch (const std::exception& e) {
    result.missing = e.what();
  }
  return result;
}

ReportFigure NoData(const std::string& why) {
  ReportFigure f;
  f.missing = why;
  return f;
}

}  // namespace

std::string InlineSvg(const std::string& gnuplot_svg, const std::string& id_prefix, const std::string& label) {
  const std::size_t start = gnuplot_svg.find("<svg");
  if (start == std::string::npos) return "";
  std::string svg = gnuplot_svg.substr(start);
  // The opening tag: keep the viewBox and namespaces, drop the fixed size, add the label.
  const std::size_t tag_end = svg.find('>');
  std::string tag = svg.substr(0, tag_end);
  tag = std::regex_replace(tag, std::regex(R"(\s(width|height)="[^"]*")"), "");
  tag += fmt::format(" role=\"img\" aria-label=\"{}\" class=\"plot\"", EscapeHtml(label));
  svg = tag + svg.substr(tag_end);
  svg = std::regex_replace(svg, std::regex(R"(<title>[^<]*</title>)"), "<title>" + EscapeHtml(label) + "</title>");
  svg = std::regex_replace(svg, std::regex(R"(<desc>[^<]*</desc>)"), "");
  // Unique ids: id='x' → id='P-x', href='#x' → href='#P-x', url(#x) → url(#P-x).
  // gnuplot repeats the ids of its plot groups in every panel of a multiplot: a repeated id gets a suffix.
  std::string renamed;
  std::set<std::string> seen;
  const std::regex id_attribute(R"(\bid=(['"])([^'"]*)(['"]))");
  auto last = svg.cbegin();
  for (auto it = std::sregex_iterator(svg.cbegin(), svg.cend(), id_attribute); it != std::sregex_iterator(); ++it) {
    const std::smatch& m = *it;
    renamed.append(last, m[0].first);
    std::string id = id_prefix + "-" + m[2].str();
    for (int n = 2; !seen.insert(id).second; ++n) id = fmt::format("{}-{}-{}", id_prefix, m[2].str(), n);
    renamed += "id=" + m[1].str() + id + m[3].str();
    last = m[0].second;
  }
  renamed.append(last, svg.cend());
  svg = std::move(renamed);
  svg = std::regex_replace(svg, std::regex(R"(href=(['"])#)"), "href=$1#" + id_prefix + "-");
  svg = std::regex_replace(svg, std::regex(R"(url\(#)"), "url(#" + id_prefix + "-");
  return svg;
}

ReportFigure SummaryFigure(const io::CampaignSummary& summary, const std::string& id_prefix) {
  std::vector<std::string> positions;
  for (const io::GroupRow& g : summary.groups) {
    if (std::find(positions.begin(), positions.end(), g.position) == positions.end()) positions.push_back(g.position);
  }
  std::sort(positions.begin(), positions.end());
  if (positions.empty()) return NoData("the summary has no block and position with values");
  double b2_min = std::numeric_limits<double>::infinity(), b2_max = -b2_min;
  for (const io::GroupRow& g : summary.groups) b2_min = std::min(b2_min, g.b2_m), b2_max = std::max(b2_max, g.b2_m);
  const double span_cm = std::max(1.0, 100.0 * (b2_max - b2_min));
  const double offset_cm = 0.025 * span_cm;  // positions side by side so that their bars do not overlap
  GnuplotFigure figure;
  std::vector<std::string> opmf, avrf;
  for (std::size_t p = 0; p < positions.size(); ++p) {
    const double shift = offset_cm * (static_cast<double>(p) - 0.5 * static_cast<double>(positions.size() - 1));
    std::vector<std::pair<double, std::array<double, 4>>> rows;
    for (const io::GroupRow& g : summary.groups) {
      if (g.position != positions[p]) continue;
      rows.push_back({100.0 * g.b2_m + shift,
                      {g.opmf_mean.value_or(kNaN), g.opmf_mean ? g.opmf_std.value_or(0.0) : kNaN,
                       g.avrf_mean.value_or(kNaN), g.avrf_mean ? g.avrf_std.value_or(0.0) : kNaN}});
    }
    std::sort(rows.begin(), rows.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    std::vector<std::vector<double>> groups(5), trials(3);
    for (const auto& r : rows) {
      groups[0].push_back(r.first);
      for (int c = 0; c < 4; ++c) groups[1 + c].push_back(r.second[c]);
    }
    for (const io::TrialRow& t : summary.trials) {
      if (t.position != positions[p]) continue;
      trials[0].push_back(100.0 * t.b2_m + shift);
      trials[1].push_back(t.opmf.value_or(kNaN));
      trials[2].push_back(t.avrf.value_or(kNaN));
    }
    const std::string g = figure.AddData(fmt::format("groups_{}", p), groups);
    const std::string t = figure.AddData(fmt::format("trials_{}", p), trials);
    const char* colour = kPalette[p % 6];
    const std::string title = GnuplotString("position " + positions[p]);
    opmf.push_back(fmt::format("{} using 1:2 with points pt 6 ps 0.5 lc rgb '{}' notitle", t, colour));
    opmf.push_back(fmt::format("{} using 1:2:3 with yerrorlines pt 7 lc rgb '{}' title {} noenhanced", g, colour, title));
    avrf.push_back(fmt::format("{} using 1:3 with points pt 6 ps 0.5 lc rgb '{}' notitle", t, colour));
    avrf.push_back(fmt::format("{} using 1:4:5 with yerrorlines pt 7 lc rgb '{}' title {} noenhanced", g, colour, title));
  }
  std::string body = "set multiplot layout 1,2\nset grid lc rgb '#dddddd'\nset xlabel 'b_2 [cm]'\n";
  body += fmt::format("set xrange [{}:{}]\nset key top right box opaque\nset offsets 0, 0, graph 0.05, graph 0.05\n",
                      100.0 * b2_min - 0.08 * span_cm, 100.0 * b2_max + 0.08 * span_cm);
  body += "set title '(a) out-of-plane motion factor'\nset ylabel 'OPMF Φ [1]'\nset yrange [0:*]\n";
  body += "plot " + Join(opmf, ", ") + "\n";
  body += "set title '(b) angular velocity reduction factor'\nset ylabel 'AVRF r [1]'\nset yrange [*:*]\n";
  body += "plot " + Join(avrf, ", ") + "\nunset multiplot\n";
  return Draw(figure, body, 400, id_prefix, "OPMF and AVRF against b2 per position");
}

ReportFigure ParameterRangesFigure(const std::vector<fitting::GroupSummary>& groups, const std::string& id_prefix) {
  if (groups.empty()) return NoData("the fits file has no parameter table per block and position");
  GnuplotFigure figure;
  // One row per group: index, then per parameter value, lower, upper (pooled and its 95 % interval; else the mean).
  const char* const names[3] = {"lambda", "lambda_lat", "lambda_lon"};
  const char* const labels[3] = {"λ [1]", "λ_{lat} [1]", "λ_{lon} [1]"};
  std::vector<std::vector<double>> columns(10);
  std::vector<std::string> tics;
  for (std::size_t i = 0; i < groups.size(); ++i) {
    const fitting::GroupSummary& g = groups[i];
    columns[0].push_back(static_cast<double>(i));
    for (int k = 0; k < 3; ++k) {
      const auto pooled = g.pooled.find(names[k]);
      const auto mean = g.mean.find(names[k]);
      const bool has_pooled = pooled != g.pooled.end() && pooled->second.n_pooled > 0 && std::isfinite(pooled->second.pooled);
      const double value = has_pooled ? pooled->second.pooled : (mean != g.mean.end() ? mean->second : kNaN);
      columns[1 + 3 * k].push_back(value);
      columns[2 + 3 * k].push_back(has_pooled ? pooled->second.interval_95[0] : value);
      columns[3 + 3 * k].push_back(has_pooled ? pooled->second.interval_95[1] : value);
    }
    tics.push_back(fmt::format("{} {}", GnuplotString(g.block + " " + g.position), i));
  }
  const std::string data = figure.AddData("groups", columns);
  std::string body = "set multiplot layout 1,3\nset grid lc rgb '#dddddd'\nset key off\nset offsets 0.5, 0.5, 0, 0\n";
  body += "set xtics noenhanced (" + Join(tics, ", ") + ") rotate by 45 right\nset xlabel 'block and position'\n";
  for (int k = 0; k < 3; ++k) {
    body += fmt::format("set title {}\nset ylabel {}\n", GnuplotString(std::string("pooled ") + labels[k] + ", 95 % interval"),
                        GnuplotString(labels[k]));
    body += fmt::format("plot {} using 1:{}:{}:{} with yerrorbars pt 7 lc rgb '{}'\n", data, 2 + 3 * k, 3 + 3 * k,
                        4 + 3 * k, kPalette[k]);
  }
  body += "unset multiplot\n";
  return Draw(figure, body, 380, id_prefix, "Pooled impact parameters per block and position with 95 % intervals");
}

ReportFigure AnglesFigure(const std::string& trial, const TrialAngles& a, const std::string& id_prefix) {
  if (a.t_s.empty()) return NoData("the trial has no samples");
  double from = a.t_s.front(), to = a.t_s.back();
  if (!a.impact_t_s.empty()) {
    from = std::max(from, a.impact_t_s.front() - kMarginAroundImpacts_s);
    to = std::min(to, a.impact_t_s.back() + kMarginAroundImpacts_s);
  }
  std::vector<std::vector<double>> columns(5);
  for (std::size_t i = 0; i < a.t_s.size(); ++i) {
    if (a.t_s[i] < from || a.t_s[i] > to) continue;
    columns[0].push_back(a.t_s[i]);
    columns[1].push_back(a.raw_zyx_rad[i][2]);
    columns[2].push_back(a.raw_zyx_rad[i][1]);
    columns[3].push_back(a.corrected_zyx_rad[i][2]);
    columns[4].push_back(a.corrected_zyx_rad[i][1]);
  }
  std::vector<std::vector<double>> marks(2);
  for (double t : a.impact_t_s) {
    if (t < from || t > to) continue;
    marks[0].push_back(t);
    marks[1].push_back(0.0);
  }
  GnuplotFigure figure;
  const std::string d = figure.AddData("angles", columns);
  const std::string m = figure.AddData("impacts", marks);
  const std::string impacts =
      marks[0].empty() ? "" : fmt::format(", {} using 1:2 with points pt 2 ps 0.6 lc rgb '#000000' title 'impacts'", m);
  std::string body = fmt::format("set xrange [{}:{}]\nset grid lc rgb '#dddddd'\nset key outside right top Left reverse\n",
                                 from, to);
  body += "set multiplot layout 2,1\nset lmargin 10\nset rmargin 22\nset xlabel 't [s]'\n";
  body += "set title '(a) measured Euler angles (ZYX)'\nset ylabel 'angle [rad]'\n";
  body += fmt::format("plot {0} using 1:2 with lines lc rgb '{1}' title 'φ_x', {0} using 1:3 with lines lc rgb '{2}' "
                      "title 'φ_y'\n", d, kColours[0], kColours[1]);
  body += "set title '(b) drift-corrected Euler angles'\nset ylabel 'angle [rad]'\n";
  body += fmt::format("plot {0} using 1:4 with lines lc rgb '{1}' title 'φ_x', {0} using 1:5 with lines lc rgb '{2}' "
                      "title 'φ_y'{3}\n", d, kColours[0], kColours[1], impacts);
  body += "unset multiplot\n";
  return Draw(figure, body, 520, id_prefix, "Measured and drift-corrected Euler angles of trial " + trial);
}

ReportFigure FitFigure(const std::string& trial, const TrialFit& fit, const std::string& id_prefix) {
  if (fit.t_s.empty()) return NoData("the fit stores no measured signal (time_s, w_B_measured)");
  std::vector<std::vector<double>> columns(7);
  for (std::size_t i = 0; i < fit.t_s.size(); ++i) {
    columns[0].push_back(fit.t_s[i]);
    for (int c = 0; c < 3; ++c) {
      columns[1 + c].push_back(fit.w_measured_B[i][c]);
      columns[4 + c].push_back(fit.w_simulated_B.empty() ? kNaN : fit.w_simulated_B[i][c]);
    }
  }
  std::vector<std::vector<double>> marks(1, fit.impact_t_s);
  GnuplotFigure figure;
  const std::string d = figure.AddData("omega", columns);
  std::string body = fmt::format("set xrange [{}:{}]\nset grid lc rgb '#dddddd'\nset key outside right top Left reverse\n",
                                 fit.t_s.front(), fit.t_s.back());
  body += "set multiplot layout 3,1\nset lmargin 10\nset rmargin 22\nset xlabel 't [s]'\n";
  const char* const component[3] = {"ω_x", "ω_y", "ω_z"};
  for (int c = 0; c < 3; ++c) {
    body += fmt::format("set ylabel '{} [rad/s]'\n", component[c]);
    const std::string simulated =
        fit.w_simulated_B.empty() ? "" : fmt::format(", {} using 1:{} with lines lw 1.2 lc rgb '{}' title 'simulated'", d,
                                                     5 + c, kColours[c]);
    body += fmt::format("plot {} using 1:{} with lines lw 2.5 lc rgb '#bbbbbb' title 'measured'{}\n", d, 2 + c, simulated);
  }
  body += "unset multiplot\n";
  return Draw(figure, body, 680, id_prefix, "Measured and simulated angular velocity of trial " + trial);
}

ReportFigure FragilityFigure(const FragilityBlock& block, const std::string& id_prefix) {
  if (block.limit_states.empty()) return NoData("the study has no limit states for block " + block.block_id);
  GnuplotFigure figure;
  std::vector<std::string> plots;
  double x_max = 0.0;
  for (std::size_t s = 0; s < block.limit_states.size(); ++s) {
    const FragilityLimitState& ls = block.limit_states[s];
    for (double x : ls.intensity) x_max = std::max(x_max, x);
    const std::string d = figure.AddData(fmt::format("s{}", s), {ls.intensity, ls.probability, ls.lower_95, ls.upper_95});
    const char* colour = kPalette[s % 6];
    const std::string name = ls.name.rfind("tilt_", 0) == 0 ? "peak tilt ≥ " + ls.name.substr(5) + " θ_c" : ls.name;
    plots.push_back(fmt::format("{} using 1:3:4 with filledcurves fs transparent solid 0.15 noborder lc rgb '{}' notitle",
                                d, colour));
    plots.push_back(fmt::format("{} using 1:2:3:4 with yerrorbars pt 7 lc rgb '{}' title {}", d, colour,
                                GnuplotString(name + " (95 % Clopper–Pearson)")));
    if (ls.curve_ok) {
      plots.push_back(fmt::format("norm(log(x/{})/{}) with lines lw 2 lc rgb '{}' title {}", ls.median, ls.beta, colour,
                                  GnuplotString(fmt::format("lognormal θ = {:.3g}, β = {:.2f}", ls.median, ls.beta))));
    }
  }
  std::string body = fmt::format("set xlabel {}\nset ylabel 'probability [1]'\nset yrange [-0.02:1.02]\nset xrange [0:{}]\n",
                                 GnuplotString(block.intensity_is_pga_g ? "peak horizontal ground acceleration [g]"
                                                                        : "scale factor of the records [1]"),
                                 1.1 * std::max(x_max, 1e-3));
  body += "set grid lc rgb '#dddddd'\nset key bottom right box opaque\nset samples 300\n";
  body += "plot " + Join(plots, ", ") + "\n";
  return Draw(figure, body, 480, id_prefix, "Fragility curves of block " + block.block_id);
}

ReportFigure ResponseFigure(const ResponseHistory& r, const std::string& id_prefix) {
  if (r.t_s.empty()) return NoData("the response has no samples");
  std::vector<std::vector<double>> ground(4), samples(5);
  for (std::size_t k = 0; k < r.ground_t_s.size(); ++k) {
    ground[0].push_back(r.ground_t_s[k]);
    for (int i = 0; i < 3; ++i) ground[1 + i].push_back(r.ground_a_W_g[k][i]);
  }
  for (std::size_t k = 0; k < r.t_s.size(); ++k) {
    samples[0].push_back(r.t_s[k]);
    samples[1].push_back(r.tilt_rad[k]);
    for (int i = 0; i < 3; ++i) samples[2 + i].push_back(r.w_B_rad_s[k][i]);
  }
  const double t_end = std::max(r.t_s.back(), r.ground_t_s.empty() ? 0.0 : r.ground_t_s.back());
  GnuplotFigure figure;
  const std::string g = figure.AddData("ground", ground);
  const std::string s = figure.AddData("samples", samples);
  std::string body = fmt::format("set xrange [0:{}]\nset grid lc rgb '#dddddd'\nset key outside right top Left reverse\n", t_end);
  body += "set multiplot layout 3,1\nset lmargin 10\nset rmargin 22\nset xlabel 't [s]'\n";
  body += fmt::format("set ylabel 'a_g [g]'\nplot {0} using 1:2 with lines lc rgb '{1}' title 'x', {0} using 1:3 with "
                      "lines lc rgb '{2}' title 'y', {0} using 1:4 with lines lc rgb '{3}' title 'z'\n",
                      g, kColours[0], kColours[1], kColours[2]);
  const std::string critical =
      r.critical_tilt_rad > 0.0 ? fmt::format(", {} with lines dt 2 lc rgb '#555555' title 'critical tilt'", r.critical_tilt_rad) : "";
  body += fmt::format("set ylabel 'tilt [rad]'\nplot {} using 1:2 with lines lc rgb '#000000' title 'tilt'{}\n", s, critical);
  body += fmt::format("set ylabel 'ω_B [rad/s]'\nplot {0} using 1:3 with lines lc rgb '{1}' title 'ω_x', {0} using 1:4 "
                      "with lines lc rgb '{2}' title 'ω_y', {0} using 1:5 with lines lc rgb '{3}' title 'ω_z'\n",
                      s, kColours[0], kColours[1], kColours[2]);
  body += "unset multiplot\n";
  return Draw(figure, body, 620, id_prefix, "Response to ground motion: " + r.file);
}

}  // namespace rockfit::app
