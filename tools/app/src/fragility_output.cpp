#include "rockfit/app/fragility_output.hpp"

#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "rockfit/app/block_args.hpp"
#include "rockfit/app/json_values.hpp"
#include "rockfit/app/option_grammar.hpp"
#include "rockfit/core/simulator.hpp"

namespace rockfit::app {

std::string EndReasonName(std::int32_t code) {
  if (code == quake::kSampleInvalid) return "invalid";
  return core::ToString(static_cast<core::EndReason>(code));
}

namespace {

constexpr double kRadToDeg = 180.0 / M_PI;

template <class F>
std::vector<double> Column(const std::vector<quake::SampleOutcome>& outcomes, F f) {
  std::vector<double> out;
  out.reserve(outcomes.size());
  for (const auto& o : outcomes) out.push_back(f(o));
  return out;
}

template <class F>
std::vector<std::int64_t> IntColumn(const std::vector<quake::SampleOutcome>& outcomes, F f) {
  std::vector<std::int64_t> out;
  out.reserve(outcomes.size());
  for (const auto& o : outcomes) out.push_back(f(o));
  return out;
}

std::string LevelUnit(quake::IntensityMeasure m) { return m == quake::IntensityMeasure::kPga ? "g" : "1"; }

}  // namespace

std::string IntensityUnit(quake::IntensityMeasure measure) {
  return measure == quake::IntensityMeasure::kPga ? "g" : "";
}

void WriteFragilityHdf5(const io::hdf5::Group& root, const quake::FragilityStudyOptions& study,
                        const std::string& settings_hash, const std::vector<quake::SampleOutcome>& outcomes,
                        const quake::FragilitySummary& summary) {
  const io::hdf5::Group f = root.CreateGroup("fragility");
  f.SetString("settings_hash", settings_hash);
  f.SetString("settings", study.SettingsText());
  f.SetString("intensity_measure", quake::ToString(study.measure));
  f.SetInt("samples_per_level", study.samples_per_level);
  f.SetInt("num_samples", study.num_samples());
  f.SetString("seed", std::to_string(study.seed));
  f.SetString("angle", study.angle_rad ? fmt::format("{} deg", *study.angle_rad * kRadToDeg) : "uniform");
  f.SetDouble("confidence", 0.95);
  const std::string unit = LevelUnit(study.measure);
  f.WriteDoubles("levels", study.levels, unit);

  const io::hdf5::Group r = f.CreateGroup("records");
  std::vector<std::string> names;
  std::vector<double> dt, pga;
  std::vector<std::int64_t> npts;
  for (const auto& rec : study.records) {
    names.push_back(rec.name);
    dt.push_back(rec.ground.dt_s());
    npts.push_back(static_cast<std::int64_t>(rec.ground.size()));
    pga.push_back(rec.ground.PeakHorizontal() / core::kRecordGravity);
  }
  r.WriteStrings("name", names);
  r.WriteDoubles("dt_s", dt, "s");
  r.WriteInts("npts", npts, "1");
  r.WriteDoubles("pga_horizontal_g", pga, "g; as read, before scaling");

  const io::hdf5::Group s = f.CreateGroup("samples");
  using O = quake::SampleOutcome;
  s.WriteInts("index", IntColumn(outcomes, [](const O& o) { return o.index; }), "1");
  s.WriteInts("block", IntColumn(outcomes, [](const O& o) { return o.block; }), "1; row of /fragility/blocks/id");
  s.WriteInts("level", IntColumn(outcomes, [](const O& o) { return o.level; }), "1; row of /fragility/levels");
  s.WriteInts("record", IntColumn(outcomes, [](const O& o) { return o.record; }), "1; row of /fragility/records");
  s.WriteDoubles("intensity", Column(outcomes, [](const O& o) { return o.intensity; }), unit);
  s.WriteDoubles("scale", Column(outcomes, [](const O& o) { return o.scale; }), "1; factor applied to the record");
  s.WriteDoubles("angle_deg", Column(outcomes, [](const O& o) { return o.angle_rad * kRadToDeg; }), "deg");
  s.WriteDoubles("lambda", Column(outcomes, [](const O& o) { return o.lambda; }), "1");
  s.WriteDoubles("lambda_lat", Column(outcomes, [](const O& o) { return o.lambda_lat; }), "1");
  s.WriteDoubles("lambda_lon", Column(outcomes, [](const O& o) { return o.lambda_lon; }), "1");
  std::vector<std::string> reasons, seeds;
  for (const O& o : outcomes) {
    reasons.push_back(EndReasonName(o.end_reason));
    seeds.push_back(fmt::format("{:016x}", o.seed));
  }
  s.WriteStrings("end_reason", reasons);
  s.WriteStrings("seed", seeds);
  s.WriteInts("overturned", IntColumn(outcomes, [](const O& o) { return o.overturned; }), "1; 1 overturned");
  s.WriteInts("counted", IntColumn(outcomes, [](const O& o) { return o.counted; }),
              "1; 1 enters the probabilities (rest, t_max, overturned)");
  s.WriteDoubles("t_end_s", Column(outcomes, [](const O& o) { return o.t_end_s; }), "s");
  s.WriteDoubles("t_overturn_s", Column(outcomes, [](const O& o) { return o.t_overturn_s; }), "s; NaN: did not overturn");
  s.WriteDoubles("peak_tilt_rad", Column(outcomes, [](const O& o) { return o.peak_tilt_rad; }), "rad");
  s.WriteDoubles("peak_tilt_ratio", Column(outcomes, [](const O& o) { return o.peak_tilt_rad / o.critical_tilt_rad; }),
                 "1; peak tilt / critical tilt");
  s.WriteDoubles("peak_rotation_rad", Column(outcomes, [](const O& o) { return o.peak_rotation_rad; }), "rad");
  s.WriteDoubles("peak_rate_rad_s", Column(outcomes, [](const O& o) { return o.peak_rate_rad_s; }), "rad/s");
  s.WriteDoubles("pga_horizontal_g",
                 Column(outcomes, [](const O& o) { return o.pga_horizontal_m_s2 / core::kRecordGravity; }), "g");
  s.WriteInts("num_impacts", IntColumn(outcomes, [](const O& o) { return o.num_impacts; }), "1");
  s.WriteDoubles("max_discarded_rate_rad_s", Column(outcomes, [](const O& o) { return o.max_discarded_rate_rad_s; }),
                 "rad/s");

  const io::hdf5::Group blocks = f.CreateGroup("blocks");
  std::vector<std::string> ids;
  for (const auto& b : study.blocks) ids.push_back(b.id);
  blocks.WriteStrings("id", ids);
  for (std::size_t bi = 0; bi < study.blocks.size(); ++bi) {
    const quake::FragilityBlock& b = study.blocks[bi];
    const quake::FragilityBlockResult& res = summary.blocks[bi];
    const io::hdf5::Group g = blocks.CreateGroup(b.id);
    g.SetDouble("b1_m", b.block.b1());
    g.SetDouble("b2_m", b.block.b2());
    g.SetDouble("h_m", b.block.h());
    g.SetDouble("mass_kg", b.block.mass());
    g.SetDouble("critical_tilt_rad", std::atan(std::min(b.block.b1(), b.block.b2()) / b.block.h()));
    g.SetString("parameter_source", b.source);
    g.WriteStrings("parameters/name", {"lambda", "lambda_lat", "lambda_lon", "tau_edge"});
    g.WriteDoubles("parameters/mean", {b.lambda.mean, b.lambda_lat.mean, b.lambda_lon.mean, b.tau_edge},
                   "1 (tau_edge: N*m*s)");
    g.WriteDoubles("parameters/sd", {b.lambda.sd, b.lambda_lat.sd, b.lambda_lon.sd, 0.0}, "1; normal distribution");
    std::vector<std::int64_t> samples, counted, not_counted;
    for (const auto& l : res.levels) {
      samples.push_back(l.samples);
      counted.push_back(l.counted);
      not_counted.push_back(l.not_counted);
    }
    g.WriteDoubles("intensity", study.levels, unit);
    g.WriteInts("samples", samples, "1");
    g.WriteInts("counted", counted, "1");
    g.WriteInts("not_counted", not_counted, "1; failed, lift_off or invalid parameters");
    g.WriteStrings("limit_state_names", res.limit_states);
    for (std::size_t s_i = 0; s_i < res.limit_states.size(); ++s_i) {
      const io::hdf5::Group ls = g.CreateGroup("limit_states/" + res.limit_states[s_i]);
      std::vector<std::int64_t> exceeded;
      std::vector<double> p, wl, wu, cl, cu;
      for (const auto& l : res.levels) {
        const quake::LimitStateCount& c = l.limit_states[s_i];
        exceeded.push_back(c.exceeded);
        p.push_back(c.probability);
        wl.push_back(c.wilson_95[0]);
        wu.push_back(c.wilson_95[1]);
        cl.push_back(c.clopper_pearson_95[0]);
        cu.push_back(c.clopper_pearson_95[1]);
      }
      ls.WriteInts("exceeded", exceeded, "1");
      ls.WriteDoubles("probability", p, "1; NaN: no counted sample");
      ls.WriteDoubles("wilson_95_lower", wl, "1");
      ls.WriteDoubles("wilson_95_upper", wu, "1");
      ls.WriteDoubles("clopper_pearson_95_lower", cl, "1");
      ls.WriteDoubles("clopper_pearson_95_upper", cu, "1");
      const quake::LognormalFragilityFit& c = res.curves[s_i];
      const io::hdf5::Group cg = ls.CreateGroup("curve");
      cg.WriteStrings("status", {quake::ToString(c.status)});
      cg.WriteStrings("message", {c.message});
      cg.WriteDoubles("median", {c.median}, unit);
      cg.WriteDoubles("median_std_error", {c.median_std_error}, unit);
      cg.WriteDoubles("median_95", {c.median_interval_95[0], c.median_interval_95[1]}, unit);
      cg.WriteDoubles("beta", {c.beta}, "1");
      cg.WriteDoubles("beta_std_error", {c.beta_std_error}, "1");
      cg.WriteDoubles("correlation", {c.correlation}, "1; of ln(median) and beta");
      cg.WriteDoubles("log_likelihood", {c.log_likelihood}, "1");
    }
  }
}

std::string StoredFragilityHash(const std::filesystem::path& path) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec) || !io::hdf5::File::IsHdf5(path)) return "";
  const io::hdf5::File file = io::hdf5::File::Open(path);
  if (!file.Root().IsGroup("fragility")) return "";
  return file.Root().OpenGroup("fragility").GetString("settings_hash").value_or("");
}

nlohmann::json FragilitySummaryJson(const quake::FragilityStudyOptions& study, const quake::FragilitySummary& summary) {
  nlohmann::json blocks = nlohmann::json::array();
  for (const quake::FragilityBlockResult& b : summary.blocks) {
    nlohmann::json levels = nlohmann::json::array();
    for (const quake::FragilityLevel& l : b.levels) {
      nlohmann::json level{{"intensity", l.intensity}, {"samples", l.samples}, {"counted", l.counted},
                           {"not_counted", l.not_counted}};
      for (std::size_t s = 0; s < b.limit_states.size(); ++s) {
        const quake::LimitStateCount& c = l.limit_states[s];
        level[b.limit_states[s]] = {{"exceeded", c.exceeded},
                                    {"probability", OrNull(c.probability)},
                                    {"wilson_95", {c.wilson_95[0], c.wilson_95[1]}},
                                    {"clopper_pearson_95", {c.clopper_pearson_95[0], c.clopper_pearson_95[1]}}};
      }
      levels.push_back(level);
    }
    nlohmann::json curves = nlohmann::json::object();
    for (std::size_t s = 0; s < b.limit_states.size(); ++s) {
      const quake::LognormalFragilityFit& c = b.curves[s];
      curves[b.limit_states[s]] = {{"status", quake::ToString(c.status)},
                                   {"message", c.message},
                                   {"median", OrNull(c.median)},
                                   {"median_std_error", OrNull(c.median_std_error)},
                                   {"median_interval_95", {OrNull(c.median_interval_95[0]), OrNull(c.median_interval_95[1])}},
                                   {"beta", OrNull(c.beta)},
                                   {"beta_std_error", OrNull(c.beta_std_error)},
                                   {"correlation", OrNull(c.correlation)},
                                   {"log_likelihood", OrNull(c.log_likelihood)}};
    }
    blocks.push_back({{"id", b.id}, {"limit_states", b.limit_states}, {"levels", levels}, {"curves", curves}});
  }
  return {{"intensity_measure", quake::ToString(study.measure)}, {"blocks", blocks}};
}

std::string FragilityTable(const quake::FragilityStudyOptions& study, const quake::FragilitySummary& summary) {
  const std::string unit = IntensityUnit(study.measure);
  const std::string level_head = study.measure == quake::IntensityMeasure::kPga ? "PGA [g]" : "scale";
  std::string out;
  std::string records = fmt::format("{} record(s):", study.records.size());
  for (std::size_t r = 0; r < study.records.size() && r < 4; ++r) records += " " + study.records[r].name;
  if (study.records.size() > 4) records += " …";
  out += fmt::format("study      {}; angle {}; {} samples per level, seed {}\n", records,
                     study.angle_rad ? fmt::format("{}°", *study.angle_rad * kRadToDeg) : std::string("uniform"),
                     study.samples_per_level, study.seed);
  for (const quake::FragilityBlock& b : study.blocks) {
    out += fmt::format("parameters {}: λ {:.4g} ± {:.2g}, λ_lat {:.4g} ± {:.2g}, λ_lon {:.4g} ± {:.2g} ({})\n", b.id,
                       b.lambda.mean, b.lambda.sd, b.lambda_lat.mean, b.lambda_lat.sd, b.lambda_lon.mean, b.lambda_lon.sd,
                       b.source);
  }
  for (const quake::FragilityBlockResult& b : summary.blocks) {
    out += fmt::format("{:<10} {:>8} {:>5} {:>5}  {:<28}", "block", level_head, "n", "excl.", "P(overturning) [95 % CP]");
    for (std::size_t s = 1; s < b.limit_states.size(); ++s) {
      out += fmt::format("  {:<28}", fmt::format("P(tilt ≥ {} θc)", study.tilt_fractions[s - 1]));
    }
    out += "\n";
    for (const quake::FragilityLevel& l : b.levels) {
      out += fmt::format("{:<10} {:>8.4g} {:>5} {:>5}", b.id, l.intensity, l.counted, l.not_counted);
      for (const quake::LimitStateCount& c : l.limit_states) {
        const std::string cell = std::isfinite(c.probability)
                                     ? fmt::format("{:.3f} [{:.3f}, {:.3f}]", c.probability, c.clopper_pearson_95[0],
                                                   c.clopper_pearson_95[1])
                                     : std::string("—");
        out += fmt::format("  {:<28}", cell);
      }
      out += "\n";
    }
    for (std::size_t s = 0; s < b.limit_states.size(); ++s) {
      const quake::LognormalFragilityFit& c = b.curves[s];
      std::string text;
      if (c.status == quake::LognormalFitStatus::kOk) {
        text = fmt::format("median {:.4g}{} ± {:.2g} (95 % {:.4g}–{:.4g}), β {:.3f} ± {:.3f}", c.median,
                           unit.empty() ? "" : " " + unit, c.median_std_error, c.median_interval_95[0],
                           c.median_interval_95[1], c.beta, c.beta_std_error);
      } else {
        text = fmt::format("{}: {}", quake::ToString(c.status), c.message);
      }
      out += fmt::format("{:<10} curve {:<12} {}\n", b.id, b.limit_states[s], text);
    }
  }
  return out;
}

}  // namespace rockfit::app
