// The earthquake side in Python: rockfit.read_ground_motion, rockfit.generate_ground_motion, rockfit.respond and
// rockfit.fragility, thin over rockfit::app (respond_run.hpp, fragility_setup.hpp) so that their numbers are the
// program's (`rockfit respond --json`, `rockfit fragility --json`) bit for bit.
#include <cstdint>
#include <numeric>
#include <optional>
#include <string>
#include <vector>

#include "bindings.hpp"
#include "path_argument.hpp"
#include "rockfit/app/block_args.hpp"
#include "rockfit/app/fragility_output.hpp"
#include "rockfit/app/fragility_setup.hpp"
#include "rockfit/app/ground_motion_args.hpp"
#include "rockfit/app/respond_run.hpp"
#include "rockfit/core/errors.hpp"
#include "rockfit/fitting/fit_store.hpp"
#include "rockfit/quake/fragility_study.hpp"

namespace rockfit::python {
namespace {

// Lists of numbers (or of number lists) → float64 arrays; the values are the JSON's doubles, unchanged.
py::object AsArray(const py::handle& list) { return py::module_::import("numpy").attr("asarray")(list, "float64"); }

// The keyword arguments of a ground motion, as `--record … --pga …` give them to the program.
app::GroundMotionArgs GroundArgs(const std::string& record, const std::string& record2, const std::string& vertical,
                                 const std::string& format, const std::string& units, std::optional<double> dt,
                                 std::optional<double> scale, std::optional<double> pga, double angle) {
  app::GroundMotionArgs a;
  a.record = record;
  a.record2 = record2;
  a.vertical = vertical;
  a.record_format = format;
  a.units = units;
  a.csv_dt_s = dt;
  a.scale = scale;
  a.pga_g = pga;
  a.angle_deg = angle;
  return a;
}

py::object GroundMotionRecord(const app::LoadedGroundMotion& loaded) {
  const core::GroundMotion& g = loaded.assembled.ground;
  std::vector<double> t_s(g.size());
  for (std::size_t k = 0; k < g.size(); ++k) t_s[k] = g.SampleTime(k);
  py::dict d;
  d["t"] = OwnedArray(std::move(t_s));
  d["a_g_W"] = OwnedArray(g.samples_W());
  d["dt_s"] = g.dt_s();
  d["npts"] = g.size();
  d["duration_s"] = g.t_end_s();
  d["scale"] = loaded.assembled.scale;
  d["pga_horizontal_m_s2"] = g.PeakHorizontal();
  d["pga_vertical_m_s2"] = g.PeakVertical();
  d["sources"] = loaded.sources;
  d["notes"] = loaded.assembled.notes;
  d["units"] = py::dict(py::arg("t") = "s", py::arg("a_g_W") = "m/s^2", py::arg("dt_s") = "s");
  return MakeRecord("GroundMotion", d);
}

py::object ReadGroundMotion(const PathArgument& path, const std::optional<PathArgument>& record2,
                            const std::optional<PathArgument>& vertical, const std::string& format,
                            const std::string& units, std::optional<double> dt, std::optional<double> scale,
                            std::optional<double> pga, double angle) {
  const app::GroundMotionArgs a = GroundArgs(path.path, record2 ? record2->path : "", vertical ? vertical->path : "",
                                             format, units, dt, scale, pga, angle);
  app::LoadedGroundMotion loaded;
  {
    py::gil_scoped_release release;
    loaded = app::LoadGroundMotion(a);
  }
  return GroundMotionRecord(loaded);
}

py::object GenerateGroundMotion(std::uint64_t seed, double duration, double dt, std::optional<double> scale,
                                std::optional<double> pga, double angle) {
  app::GroundMotionArgs a = GroundArgs("", "", "", "auto", "g", std::nullopt, scale, pga, angle);
  a.synthetic_seed = seed;
  a.synthetic_duration_s = duration;
  a.synthetic_dt_s = dt;
  app::LoadedGroundMotion loaded;
  {
    py::gil_scoped_release release;
    loaded = app::LoadGroundMotion(a);
  }
  return GroundMotionRecord(loaded);
}

// The block: a rockfit.Block, or a block of a manifest (manifest=..., block_id=...).
app::BlockArgs BlockArguments(const std::optional<core::Block>& block, const std::optional<PathArgument>& manifest,
                              const std::string& block_id) {
  app::BlockArgs a;
  if (manifest) {
    if (block) throw InvalidArgument("give the block either as block=rockfit.Block(...) or by manifest= and block_id=");
    a.manifest_path = manifest->path;
    a.block_id = block_id;
    return a;
  }
  if (!block) throw InvalidArgument("the block is needed: block=rockfit.Block(...), or manifest= with block_id=");
  a.b1_m = block->b1();
  a.b2_m = block->b2();
  a.h_m = block->h();
  a.mass_kg = block->mass();
  return a;
}

py::object Respond(const std::optional<core::Block>& block_given, const std::optional<PathArgument>& manifest,
                   const std::string& block_id, const std::optional<PathArgument>& record,
                   const std::optional<PathArgument>& record2, const std::optional<PathArgument>& vertical,
                   const std::string& record_format, const std::string& units, std::optional<double> dt,
                   std::optional<std::uint64_t> synthetic, double synthetic_duration, double synthetic_dt,
                   std::optional<double> scale, std::optional<double> pga, double angle, double lambda,
                   double lambda_lat, double lambda_lon, double tau_edge, const std::string& facet_tau, double alpha,
                   const std::optional<PathArgument>& fits, const std::string& trial, const std::string& group,
                   const std::string& start, const std::string& until, const std::string& overturn, int round_off,
                   double tail, double rate, double gravity, int max_impacts) {
  const core::Block block = app::MakeBlock(BlockArguments(block_given, manifest, block_id));
  app::RespondArgs a;
  a.params.lambda = lambda;
  a.params.lambda_lat = lambda_lat;
  a.params.lambda_lon = lambda_lon;
  a.params.tau_edge = tau_edge;
  a.params.alpha_rad = alpha;
  a.facet_tau = facet_tau;
  a.fits = fits ? fits->path : "";
  a.trial = trial;
  a.group = group;
  a.ground = GroundArgs(record ? record->path : "", record2 ? record2->path : "", vertical ? vertical->path : "",
                        record_format, units, dt, scale, pga, angle);
  a.ground.synthetic_seed = synthetic;
  a.ground.synthetic_duration_s = synthetic_duration;
  a.ground.synthetic_dt_s = synthetic_dt;
  a.start = start;
  a.until = until;
  a.overturn = overturn;
  a.round_off_runs = round_off;
  a.options.tail_s = tail;
  a.options.simulation.rate_hz = rate;
  a.options.simulation.gravity_m_s2 = gravity;
  if (max_impacts < 1) throw InvalidArgument("max_impacts must be at least 1");
  a.options.simulation.max_impacts = max_impacts;
  app::RespondRun run;
  {
    py::gil_scoped_release release;
    run = app::RunRespond(block, a);
  }
  py::dict d = FromJson(app::ResponseJson(block, run));  // the keys of `rockfit respond --json`
  py::dict samples = d["samples"];
  for (const char* key : {"t", "a_g_W", "w_B", "q_WB", "tilt"}) samples[key] = AsArray(samples[key]);
  d["samples"] = MakeRecord("ResponseSamples", samples);
  d["summary"] = MakeRecord("ResponseSummary", d["summary"]);
  return MakeRecord("Response", d);
}

py::object Fragility(const std::optional<core::Block>& block_given, const std::optional<PathArgument>& manifest,
                     const std::string& block_id, const std::vector<PathArgument>& records, const std::string& record_format,
                     const std::string& units, std::optional<double> dt, int synthetic_records, std::uint64_t synthetic_seed,
                     double synthetic_duration, double synthetic_dt, const py::object& pga, const py::object& scale,
                     const py::object& angle, const py::object& tilts, double lambda, double lambda_lat,
                     double lambda_lon, double tau_edge, double lambda_sd, double lambda_lat_sd, double lambda_lon_sd,
                     const std::string& facet_tau, const std::optional<PathArgument>& fits, const std::string& group,
                     const std::string& position, std::int64_t samples, std::uint64_t seed, double tail, double rate,
                     const std::string& overturn, int threads) {
  app::FragilityArgs a;
  a.block = BlockArguments(block_given, manifest, block_id);
  a.fits = fits ? fits->path : "";
  a.group = group;
  a.position = position;
  a.lambda = lambda;
  a.lambda_lat = lambda_lat;
  a.lambda_lon = lambda_lon;
  a.tau_edge = tau_edge;
  a.lambda_sd = lambda_sd;
  a.lambda_lat_sd = lambda_lat_sd;
  a.lambda_lon_sd = lambda_lon_sd;
  a.facet_tau = facet_tau;
  for (const PathArgument& r : records) a.records.push_back(r.path);
  a.record_format = record_format;
  a.units = units;
  a.csv_dt_s = dt;
  a.synthetic_records = synthetic_records;
  a.synthetic_seed = synthetic_seed;
  a.synthetic_duration_s = synthetic_duration;
  a.synthetic_dt_s = synthetic_dt;
  // Levels as the program's text: a list of numbers or "FROM:TO:N".
  const auto levels = [](const py::object& value) -> std::string {
    if (value.is_none()) return "";
    if (py::isinstance<py::str>(value)) return value.cast<std::string>();
    std::string text;
    for (py::handle v : value) text += (text.empty() ? "" : ",") + py::repr(py::float_(v.cast<double>())).cast<std::string>();
    return text;
  };
  a.pga = levels(pga);
  a.scale = levels(scale);
  a.tilts = levels(tilts);
  a.angle = angle.is_none() ? "random" : py::repr(py::float_(angle.cast<double>())).cast<std::string>();
  a.samples = samples;
  a.seed = seed;
  a.tail_s = tail;
  a.rate_hz = rate;
  a.overturn = overturn;
  if (threads < 0) throw InvalidArgument("threads must be ≥ 0 (0: all cores)");

  quake::FragilityStudyOptions study;
  std::vector<quake::SampleOutcome> outcomes;
  quake::FragilitySummary summary;
  {
    py::gil_scoped_release release;
    study = app::MakeFragilityStudy(a);
    std::vector<std::int64_t> indices(static_cast<std::size_t>(study.num_samples()));
    std::iota(indices.begin(), indices.end(), std::int64_t{0});
    outcomes = quake::RunSamples(study, indices, threads);
    summary = quake::SummariseFragility(study, outcomes);
  }
  py::dict d = FromJson(app::FragilitySummaryJson(study, summary));  // the keys of `rockfit fragility --json`
  d["settings_hash"] = fitting::SettingsHash(study.SettingsText());
  d["samples"] = study.num_samples();
  d["not_counted"] = summary.not_counted;
  // Every sample's outcome, as the program's /fragility/samples table.
  std::vector<double> intensity, peak_tilt, overturned, counted, level, block, record, lambda_s, lambda_lat_s,
      lambda_lon_s;
  for (const quake::SampleOutcome& o : outcomes) {
    intensity.push_back(o.intensity);
    peak_tilt.push_back(o.peak_tilt_rad);
    overturned.push_back(o.overturned);
    counted.push_back(o.counted);
    level.push_back(o.level);
    block.push_back(o.block);
    record.push_back(o.record);
    lambda_s.push_back(o.lambda);
    lambda_lat_s.push_back(o.lambda_lat);
    lambda_lon_s.push_back(o.lambda_lon);
  }
  py::dict s;
  s["level"] = OwnedArray(std::move(level));
  s["block"] = OwnedArray(std::move(block));
  s["record"] = OwnedArray(std::move(record));
  s["intensity"] = OwnedArray(std::move(intensity));
  s["peak_tilt_rad"] = OwnedArray(std::move(peak_tilt));
  s["overturned"] = OwnedArray(std::move(overturned));
  s["counted"] = OwnedArray(std::move(counted));
  s["lambda"] = OwnedArray(std::move(lambda_s));
  s["lambda_lat"] = OwnedArray(std::move(lambda_lat_s));
  s["lambda_lon"] = OwnedArray(std::move(lambda_lon_s));
  d["sample_outcomes"] = MakeRecord("FragilitySamples", s);
  return MakeRecord("Fragility", d);
}

}  // namespace

void RegisterQuake(py::module_& m) {
  const app::GroundMotionArgs g;
  m.def("read_ground_motion", &ReadGroundMotion, py::arg("path"), py::kw_only(), py::arg("record2") = py::none(),
        py::arg("vertical") = py::none(), py::arg("format") = g.record_format, py::arg("units") = g.units,
        py::arg("dt") = py::none(), py::arg("scale") = py::none(), py::arg("pga") = py::none(),
        py::arg("angle") = g.angle_deg,
        "Reads a ground-motion record as `rockfit respond --record` does: a PEER AT2 file (values in g) or a CSV\n"
        "(format 'auto' by extension, 'at2' or 'csv'; units of a CSV 'g', 'm/s2' or 'cm/s2'; dt [s] for a CSV without\n"
        "a time column), with record2 (second horizontal, 90° from the first) and vertical components. scale\n"
        "multiplies every component, or pga [g] scales them so that the peak horizontal acceleration is that much;\n"
        "angle [deg] is the incidence of the first component from the block's x axis.\n\n"
        "Returns a Record 'GroundMotion': t [s] (N,), a_g_W [m/s²] (N, 3) (x, y, z of W), dt_s, npts, duration_s,\n"
        "scale, pga_horizontal_m_s2, pga_vertical_m_s2, sources (one line per component), notes, units.");
  m.def("generate_ground_motion", &GenerateGroundMotion, py::arg("seed"), py::kw_only(),
        py::arg("duration") = g.synthetic_duration_s, py::arg("dt") = g.synthetic_dt_s, py::arg("scale") = py::none(),
        py::arg("pga") = py::none(), py::arg("angle") = g.angle_deg,
        "A generated Clough–Penzien record, as `rockfit respond --synthetic SEED` makes it (io/README.md,\n"
        "\"Stochastic ground motion\"; PGA 0.3 g unless pga): seed, duration [s], dt [s], scale or pga [g], angle\n"
        "[deg]. Returns the Record of read_ground_motion.");
  const core::ModelParameters p;
  const core::ResponseOptions o;
  m.def("respond", &Respond, py::arg("block") = py::none(), py::kw_only(), py::arg("manifest") = py::none(),
        py::arg("block_id") = "", py::arg("record") = py::none(), py::arg("record2") = py::none(),
        py::arg("vertical") = py::none(), py::arg("record_format") = g.record_format, py::arg("units") = g.units,
        py::arg("dt") = py::none(), py::arg("synthetic") = py::none(),
        py::arg("synthetic_duration") = g.synthetic_duration_s, py::arg("synthetic_dt") = g.synthetic_dt_s,
        py::arg("scale") = py::none(), py::arg("pga") = py::none(), py::arg("angle") = g.angle_deg,
        py::arg("lambda_") = p.lambda, py::arg("lambda_lat") = p.lambda_lat, py::arg("lambda_lon") = p.lambda_lon,
        py::arg("tau_edge") = p.tau_edge, py::arg("facet_tau") = "no-spin", py::arg("alpha") = p.alpha_rad,
        py::arg("fits") = py::none(), py::arg("trial") = "", py::arg("group") = "", py::arg("start") = "flat",
        py::arg("until") = "rest", py::arg("overturn") = "support", py::arg("round_off") = 0,
        py::arg("tail") = o.tail_s, py::arg("rate") = o.simulation.rate_hz, py::arg("gravity") = o.simulation.gravity_m_s2,
        py::arg("max_impacts") = o.simulation.max_impacts,
        "Earthquake response of a block, as `rockfit respond --json`: the block stands flat on a table that moves\n"
        "with the ground acceleration (record=PATH with record2, vertical, record_format, units, dt, or\n"
        "synthetic=SEED with synthetic_duration [s], synthetic_dt [s]; scale or pga [g]; angle [deg]).\n\n"
        "block: a rockfit.Block, or manifest=PATH with block_id=ID. Parameters: lambda_ (19), lambda_lat,\n"
        "lambda_lon (21), tau_edge [N·m·s], facet_tau 'no-spin' or 'fixed', or fits=PATH (a file of `rockfit fit -o`\n"
        "or `batch`) with trial=ID or group='BLOCK,POSITION' (the group's pooled estimates). start 'flat' or\n"
        "'tilted' (released at alpha [rad]); until 'rest' or 't_max'; overturn 'support' or 'side'; round_off=N\n"
        "also runs the record scaled by 1 + k·1e-15; tail [s] after the record; rate [Hz] of the samples; gravity\n"
        "[m/s²]; max_impacts.\n\n"
        "Returns a Record 'Response' with the keys of the program's JSON: summary (end_reason, overturned,\n"
        "t_overturn [s], peak_tilt_rad, critical_tilt_rad, num_impacts, uplift_times [s], max_discarded_rate_rad_s,\n"
        "max_friction_ratio, …), block, parameters, ground_motion, impacts, samples (t [s] (N,), a_g_W [m/s²]\n"
        "(N, 3), w_B [rad/s] (N, 3), q_WB (N, 4) scalar first, tilt [rad] (N,), mode), round_off. A failed run is\n"
        "the end reason 'failed', not an exception. The GIL is released while it runs.");
  const quake::FragilityStudyOptions f;
  m.def("fragility", &Fragility, py::arg("block") = py::none(), py::kw_only(), py::arg("manifest") = py::none(),
        py::arg("block_id") = "", py::arg("records") = py::list(),
        py::arg("record_format") = "auto", py::arg("units") = "g", py::arg("dt") = py::none(),
        py::arg("synthetic_records") = 0, py::arg("synthetic_seed") = 1, py::arg("synthetic_duration") = 20.0,
        py::arg("synthetic_dt") = 0.005, py::arg("pga") = py::none(), py::arg("scale") = py::none(),
        py::arg("angle") = py::none(), py::arg("tilts") = py::none(), py::arg("lambda_") = 1.0,
        py::arg("lambda_lat") = 0.0, py::arg("lambda_lon") = 1.0, py::arg("tau_edge") = 0.0,
        py::arg("lambda_sd") = 0.0, py::arg("lambda_lat_sd") = 0.0, py::arg("lambda_lon_sd") = 0.0,
        py::arg("facet_tau") = "no-spin", py::arg("fits") = py::none(), py::arg("group") = "",
        py::arg("position") = "", py::arg("samples") = 100, py::arg("seed") = f.seed, py::arg("tail") = 5.0,
        py::arg("rate") = 200.0, py::arg("overturn") = "support", py::arg("threads") = 0,
        "Monte-Carlo overturning fragility, as `rockfit fragility --json` (fitting/quake/README.md): at each\n"
        "intensity level (pga=[g, …] or scale=[factors], or a text 'FROM:TO:N'), `samples` runs of `respond` with\n"
        "the impact parameters drawn from normal distributions (lambda_, lambda_lat, lambda_lon with their *_sd, or\n"
        "fits=PATH of `rockfit batch` with group='BLOCK,POSITION' or position= for the blocks of block_id='ID,ID'),\n"
        "the records (records=[PATH, …] and/or synthetic_records=N) used in turn, a random incidence unless angle\n"
        "[deg]. tilts: also the probability that the peak tilt reaches these fractions of the critical tilt.\n"
        "seed: sample i draws from its own stream (seed, i), so the numbers do not depend on threads (0: all cores).\n\n"
        "Returns a Record 'Fragility' with the keys of the program's JSON (intensity_measure, blocks with their\n"
        "levels, probabilities, Wilson and Clopper–Pearson intervals and lognormal curves), settings_hash, samples,\n"
        "not_counted, and sample_outcomes (arrays per sample: level, block, record, intensity, peak_tilt_rad,\n"
        "overturned, counted, lambda, lambda_lat, lambda_lon). The GIL is released while it runs.");
}

}  // namespace rockfit::python
