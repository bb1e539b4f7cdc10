// rockfit.fit, rockfit.fit_campaign and rockfit.evaluate: the fitting problem of `rockfit fit` / `rockfit batch`
// (tools/app/src/fit_setup.cpp, the same code), solved with the GIL released; Ctrl-C stops a running fit.
//
// The result holds every key of `rockfit fit --json` (FitResultJson) and, added to it, every key of the fitting
// library's own summary (FitSummary::ToJson): new per-parameter or top-level fields of either appear in Python
// without changes here.
#include <atomic>
#include <chrono>
#include <future>
#include <memory>
#include <thread>

#include <fmt/format.h>
#include <tbb/info.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "bindings.hpp"
#include "rockfit/app/fit_setup.hpp"
#include "path_argument.hpp"
#include "rockfit/app/mounting_report.hpp"
#include "rockfit/app/recording_input.hpp"
#include "rockfit/core/errors.hpp"
#include "rockfit/fitting/recorded_fit.hpp"
#include "rockfit/io/manifest.hpp"

namespace rockfit::python {
namespace {

using Flag = std::shared_ptr<std::atomic<bool>>;

// How often a waiting call looks for Ctrl-C (Python handles signals in the main thread only, holding the GIL).
// Short against a fit (~0.5 s), long against the cost of taking the GIL.
constexpr std::chrono::milliseconds kSignalPollInterval{50};

// The fitting problem's model, forwarding to the simulator until `interrupted` is set; from then on every run
// fails at once, so that the optimizers exhaust their budgets in milliseconds and the fit returns.
class InterruptibleModel final : public fitting::TrajectoryModel {
 public:
  InterruptibleModel(std::shared_ptr<const fitting::Objective> owner, Flag interrupted)
      : owner_(std::move(owner)), interrupted_(std::move(interrupted)) {}
  void Evaluate(const core::ModelParameters& params, const std::vector<double>& t_after_release_s,
                fitting::ModelOutput* out) const override {
    if (interrupted_->load(std::memory_order_relaxed)) {
      out->Clear();
      out->failure = fitting::ModelFailure::kInterrupted;
      out->failure_detail = "the fit was interrupted (Ctrl-C)";
      return;
    }
    owner_->model().Evaluate(params, t_after_release_s, out);
  }
  std::string Describe() const override { return owner_->model().Describe(); }

 private:
  std::shared_ptr<const fitting::Objective> owner_;
  Flag interrupted_;
};

// The same problem with the interruptible model.
fitting::Objective Interruptible(const fitting::Objective& objective, const Flag& interrupted) {
  auto owner = std::make_shared<const fitting::Objective>(objective);
  return fitting::Objective(objective.signal(), objective.t_end_s(),
                            std::make_shared<InterruptibleModel>(owner, interrupted), objective.parameters(),
                            objective.options())
      .WithLaterWindowEnds(objective.later_window_ends_s());
}

// Runs `work` on a worker thread while this thread, without the GIL, waits for it and looks for Ctrl-C. On
// KeyboardInterrupt (or another exception a signal handler raises) the flag stops the work, which is joined
// before the exception propagates.
template <typename Result, typename Work>
Result RunInterruptibly(Work work, const Flag& interrupted) {
  std::packaged_task<Result()> task(std::move(work));
  std::future<Result> done = task.get_future();
  std::thread worker(std::move(task));
  for (;;) {
    bool ready = false;
    {
      py::gil_scoped_release release;
      ready = done.wait_for(kSignalPollInterval) == std::future_status::ready;
    }
    if (ready) break;
    if (PyErr_CheckSignals() != 0) {
      interrupted->store(true);
      {
        py::gil_scoped_release release;
        worker.join();
      }
      throw py::error_already_set();
    }
  }
  worker.join();
  return done.get();  // rethrows the work's C++ exception, translated by the module
}

// ------------------------------------------------------------------------------------------- options

std::string Number(double value) { return fmt::format("{}", value); }  // shortest text that reads back exactly

std::vector<std::string> Names(const py::object& value, const char* what) {
  std::vector<std::string> out;
  if (value.is_none()) return out;
  if (py::isinstance<py::str>(value)) return {value.cast<std::string>()};
  try {
    for (const py::handle item : value) out.push_back(py::cast<std::string>(item));
  } catch (const py::cast_error&) {
    throw InvalidArgument(fmt::format("{} must be a parameter name or a list of names (t0, alpha, lambda, lambda_lat, "
                                      "lambda_lon, tau_edge)", what));
  }
  return out;
}

// fix: "NAME", "NAME=VALUE", a list of those, or a dict NAME → value (None: held at the data estimate).
std::vector<std::string> FixEntries(const py::object& fix) {
  if (fix.is_none()) return {};
  if (py::isinstance<py::dict>(fix)) {
    std::vector<std::string> out;
    for (const auto& [key, value] : fix.cast<py::dict>()) {
      const std::string name = py::cast<std::string>(key);
      out.push_back(value.is_none() ? name : name + "=" + Number(py::cast<double>(value)));
    }
    return out;
  }
  return Names(fix, "fix");
}

std::vector<std::string> BoundEntries(const py::object& bounds, const char* what) {
  std::vector<std::string> out;
  if (bounds.is_none()) return out;
  if (!py::isinstance<py::dict>(bounds)) throw InvalidArgument(fmt::format("{} must be a dict NAME → value", what));
  for (const auto& [key, value] : bounds.cast<py::dict>()) {
    out.push_back(py::cast<std::string>(key) + "=" + Number(py::cast<double>(value)));
  }
  return out;
}

// The program's FitArgs from the keyword arguments: the same parsing and validation as its options.
app::FitArgs MakeFitArgs(const std::string& method, const py::object& bounds, const py::object& free,
                           const py::object& fix, const py::object& lower, const py::object& upper,
                           std::optional<double> t_end, int max_evaluations, bool global_stage, bool keep_bias,
                           int threads, const std::string& estimate_gyro_scale = "off",
                           bool fit_release_roll = false) {
  app::FitArgs args;
  args.method = method;
  if (py::isinstance<py::str>(bounds)) {
    args.bounds = bounds.cast<std::string>();
  } else if (py::isinstance<py::dict>(bounds)) {
    for (const auto& [key, value] : bounds.cast<py::dict>()) {
      const std::string name = py::cast<std::string>(key);
      const py::tuple pair = py::cast<py::tuple>(value);
      if (pair.size() != 2) throw InvalidArgument("bounds['" + name + "'] must be a pair (lower, upper)");
      if (!pair[0].is_none()) args.lower.push_back(name + "=" + Number(pair[0].cast<double>()));
      if (!pair[1].is_none()) args.upper.push_back(name + "=" + Number(pair[1].cast<double>()));
    }
  } else {
    throw InvalidArgument("bounds must be 'empirical', 'theoretical' or a dict NAME → (lower, upper)");
  }
  args.free = Names(free, "free");
  args.fix = FixEntries(fix);
  for (std::string& e : BoundEntries(lower, "lower")) args.lower.push_back(std::move(e));
  for (std::string& e : BoundEntries(upper, "upper")) args.upper.push_back(std::move(e));
  args.t_end_s = t_end;
  args.max_evaluations = max_evaluations;
  args.no_global = !global_stage;
  args.keep_bias = keep_bias;
  args.threads = threads;
  args.estimate_gyro_scale = estimate_gyro_scale;
  args.fit_release_roll = fit_release_roll;
  fitting::ParseGyroScaleMode(args.estimate_gyro_scale);
  app::MakeParameterSet(args);  // bad names, values and bounds before any work
  fitting::ParseFitMethod(args.method);
  return args;
}

// ------------------------------------------------------------------------------------------- results

struct FitOutcome {
  std::string trial;
  std::unique_ptr<app::PreparedFit> prepared;
  fitting::FitSummary summary;
  fitting::ErrorNodes nodes;
  fitting::ModelOutput output;
  nlohmann::json mounting;  // as `rockfit fit --json` reports it
  std::string error_type;  // empty when the fit ran; else the Python exception it would raise
  std::string message;
};

// One fit, all in C++ (runs on a worker thread).
FitOutcome RunFit(const std::string& trial, const io::Recording& recording, const core::Block& block,
                  const app::FitArgs& args, const Flag& interrupted) {
  FitOutcome o;
  o.trial = app::TrialNameFrom(trial);
  o.mounting = app::MountingJson(recording);
  o.prepared = std::make_unique<app::PreparedFit>(app::PrepareFit(recording, block, args));
  const fitting::Objective objective = Interruptible(o.prepared->objective, interrupted);
  o.summary = fitting::FitRecordedTrial(objective, o.prepared->start, o.prepared->options,
                                        o.prepared->release_roll_choice, &recording);
  // The nodes of (28) and the model at the result, for plots (one more simulation).
  // On the fit's window, which the fit may have extended (fitting/README.md, "End of the fitting window").
  o.prepared->objective.WithWindowEnd(o.summary.t_end_s).EvaluateDetailed(o.summary.parameters, &o.nodes, &o.output);
  return o;
}

py::object FitRecord(FitOutcome& o) {
  nlohmann::json merged = nlohmann::json::parse(o.summary.ToJson(o.trial));
  const nlohmann::json cli = app::FitResultJson(o.trial, o.summary);
  for (const auto& [key, value] : cli.items()) {
    if (key == "parameters") {
      for (const auto& [name, fields] : value.items()) merged["parameters"][name].update(fields);
    } else {
      merged[key] = value;
    }
  }
  merged["mounting"] = o.mounting;
  py::dict d = FromJson(merged).cast<py::dict>();
  py::dict parameters;
  py::dict values;
  const py::dict all = d["parameters"].cast<py::dict>();
  for (fitting::ParameterId id : fitting::kAllParameters) {  // the reported ones (release_roll only when estimated)
    if (!all.contains(fitting::Name(id))) continue;
    const py::dict fields = all[fitting::Name(id)].cast<py::dict>();
    parameters[fitting::Name(id)] = MakeRecord("Parameter", fields);
    values[fitting::Name(id)] = fields["value"];
  }
  d["parameters"] = parameters;
  d["values"] = values;
  py::list warnings;
  for (const py::handle w : d["warnings"]) warnings.append(MakeRecord("FitWarning", w.cast<py::dict>()));
  d["warnings"] = warnings;
  py::list stages;
  for (const py::handle s : d["stages"]) stages.append(MakeRecord("Stage", s.cast<py::dict>()));
  d["stages"] = stages;
  d["notes"] = o.prepared->notes;
  d["settings"] = o.prepared->settings;
  d["report"] = o.summary.FullReport();
  // The nodes of (28): measured ω (gyro bias at rest removed unless keep_bias) and the fitted simulation.
  const double t0 = o.summary.parameters.value(fitting::ParameterId::kT0);
  std::vector<double> impact_times;
  std::vector<std::string> impact_kinds;
  for (const fitting::ModelEvent& e : o.output.events) {
    impact_times.push_back(t0 + e.t_s);
    impact_kinds.push_back(core::ToString(e.kind));
  }
  const bool simulated = o.output.ok() && o.output.w_B.size() == o.nodes.size();
  d["t"] = OwnedArray(std::move(o.nodes.t_s));
  d["w_B_measured"] = OwnedArray(std::move(o.nodes.w_m_B));
  d["w_B_simulated"] = simulated ? py::object(OwnedArray(std::move(o.output.w_B))) : py::none();
  d["impact_times"] = OwnedArray(std::move(impact_times));
  d["impact_kinds"] = impact_kinds;
  // The program's keys first, in the order of its table; then the rest as the summary has them.
  py::dict ordered;
  for (const char* key : {"trial", "values", "epsilon", "epsilon_initial", "t_end", "feasible", "termination",
                          "warnings", "parameters", "simulations", "wall_s"}) {
    if (d.contains(key)) ordered[key] = d[key];
  }
  for (const auto& [key, value] : d) {
    if (!ordered.contains(key)) ordered[key] = value;
  }
  return MakeRecord("FitResult", ordered);
}

py::object Fit(const TrialRecording& r, const std::optional<core::Block>& given, const std::string& method,
               const py::object& bounds, const py::object& free, const py::object& fix, const py::object& lower,
               const py::object& upper, std::optional<double> t_end, int max_evaluations, bool global_stage,
               bool keep_bias, int threads, const std::string& estimate_gyro_scale, bool fit_release_roll) {
  const app::FitArgs args = MakeFitArgs(method, bounds, free, fix, lower, upper, t_end, max_evaluations, global_stage,
                                        keep_bias, threads, estimate_gyro_scale, fit_release_roll);
  const core::Block block = BlockFor(given, r, "the fit");
  auto interrupted = std::make_shared<std::atomic<bool>>(false);
  // The recording is shared with the worker: keep it alive even if Python drops it meanwhile.
  auto recording = std::make_shared<io::Recording>(r.recording);
  const std::string trial = r.trial;
  FitOutcome outcome = RunInterruptibly<FitOutcome>(
      [recording, block, args, interrupted, trial] { return RunFit(trial, *recording, block, args, interrupted); },
      interrupted);
  return FitRecord(outcome);
}

// ------------------------------------------------------------------------------------------- campaign

py::list FitCampaign(const PathArgument& manifest_argument, const py::object& trials, int jobs, const std::string& method,
                     const py::object& bounds, const py::object& free, const py::object& fix, const py::object& lower,
                     const py::object& upper, std::optional<double> t_end, int max_evaluations, bool global_stage,
                     bool keep_bias, const std::string& estimate_gyro_scale, bool fit_release_roll) {
  if (jobs < 0) throw InvalidArgument("jobs must be ≥ 0 (0: all cores)");
  const std::string& manifest_path = manifest_argument.path;
  app::FitArgs args =
      MakeFitArgs(method, bounds, free, fix, lower, upper, t_end, max_evaluations, global_stage, keep_bias, 1,
                  estimate_gyro_scale, fit_release_roll);
  args.threads = 1;  // parallel over trials, not inside one fit (as `rockfit batch`)
  const io::Manifest manifest = io::ReadManifest(manifest_path);
  std::vector<const io::TrialSpec*> selected;
  if (trials.is_none()) {
    for (const io::TrialSpec& t : manifest.trials) selected.push_back(&t);
  } else {
    for (const std::string& id : Names(trials, "trials")) selected.push_back(&manifest.FindTrial(id));
  }
  if (selected.empty()) throw BadInput(fmt::format("{}: the manifest lists no trials", manifest_path));

  auto interrupted = std::make_shared<std::atomic<bool>>(false);
  auto outcomes = std::make_shared<std::vector<FitOutcome>>(selected.size());
  const auto work = [&manifest, selected, args, interrupted, outcomes, jobs] {
    std::atomic<std::size_t> next{0};
    const auto worker = [&] {
      for (std::size_t i = next.fetch_add(1); i < selected.size(); i = next.fetch_add(1)) {
        const io::TrialSpec& spec = *selected[i];
        FitOutcome& o = (*outcomes)[i];
        try {
          const core::Block block = manifest.FindBlock(spec.block_id).ToBlock();
          o = RunFit(spec.id, app::LoadManifestTrial(spec), block, args, interrupted);
        } catch (const InvalidArgument& e) {
          o.error_type = "ValueError";
          o.message = e.what();
        } catch (const BadInput& e) {
          o.error_type = "InputError";
          o.message = e.what();
        } catch (const std::exception& e) {
          o.error_type = "NumericalError";
          o.message = e.what();
        }
        o.trial = app::TrialNameFrom(spec.id);
      }
    };
    // The TBB pool of the library and of `rockfit batch`: at most one trial per core (0: all cores).
    const int cores = tbb::info::default_concurrency();
    const int n = static_cast<int>(std::min<std::size_t>(selected.size(), static_cast<std::size_t>(jobs > 0 ? std::min(jobs, cores) : cores)));
    tbb::task_arena arena(std::max(1, n));
    arena.execute([&] { tbb::parallel_for(0, std::max(1, n), [&](int) { worker(); }); });
    return true;
  };
  RunInterruptibly<bool>(work, interrupted);

  py::list out;
  for (FitOutcome& o : *outcomes) {
    if (o.error_type.empty()) {
      out.append(FitRecord(o));
    } else {
      py::dict d;
      d["trial"] = o.trial;
      d["error"] = o.error_type;
      d["message"] = o.message;
      out.append(MakeRecord("FitFailure", d));
    }
  }
  return out;
}

// ------------------------------------------------------------------------------------------- evaluate

py::object Evaluate(const TrialRecording& r, const std::optional<core::Block>& given, std::optional<double> t0,
                    std::optional<double> alpha, std::optional<double> lambda, std::optional<double> lambda_lat,
                    std::optional<double> lambda_lon, const py::object& bounds, const py::object& fix,
                    std::optional<double> t_end, bool keep_bias) {
  const app::FitArgs args = MakeFitArgs("auto", bounds, py::none(), fix, py::none(), py::none(), t_end, 0, true,
                                          keep_bias, 1);
  const core::Block block = BlockFor(given, r, "evaluate");
  const std::pair<fitting::ParameterId, std::optional<double>> given_values[] = {
      {fitting::ParameterId::kT0, t0},           {fitting::ParameterId::kAlpha, alpha},
      {fitting::ParameterId::kLambda, lambda},   {fitting::ParameterId::kLambdaLat, lambda_lat},
      {fitting::ParameterId::kLambdaLon, lambda_lon}};
  fitting::Evaluation e;
  fitting::ParameterSet values;
  double window_end = 0.0;
  {
    py::gil_scoped_release release;
    const app::PreparedFit prepared = app::PrepareFit(r.recording, block, args);
    values = prepared.start;
    for (const auto& [id, v] : given_values) {
      if (v) values[id].value = *v;
    }
    e = prepared.objective.Evaluate(values);
    window_end = prepared.objective.t_end_s();
  }
  py::dict parameters;  // as `rockfit fit --evaluate --json`
  for (const auto& [id, v] : given_values) {
    parameters[fitting::Name(id)] = py::dict(py::arg("value") = values.value(id), py::arg("given") = v.has_value());
  }
  py::dict d;
  d["trial"] = r.trial;
  d["epsilon"] = e.feasible ? py::object(py::float_(e.epsilon_rad_s)) : py::none();
  d["feasible"] = e.feasible;
  d["failure"] = e.failure_category();
  d["t_end"] = window_end;
  d["parameters"] = parameters;
  return MakeRecord("Evaluation", d);
}

constexpr const char* kProblemArgs =
    "method: 'auto' (global stage, Nelder–Mead, Ceres polish), 'nelder-mead' or 'ceres'.\n"
    "bounds: 'empirical' (wider than (25)/(27)) or 'theoretical', or a dict NAME → (lower, upper) on top of the\n"
    "  empirical bounds (None keeps a side). Names: t0 [s], alpha [rad], lambda, lambda_lat, lambda_lon, tau_edge\n"
    "  [N·m·s], release_roll [rad].\n"
    "free: names to fit in addition to the defaults (t0, alpha, lambda, lambda_lat, lambda_lon; tau_edge and\n"
    "  release_roll are fixed at 0). fix: a name or list of names held at the data estimate, 'NAME=VALUE' entries, or a dict NAME → value\n"
    "  (None: at the data estimate). lower, upper: dicts NAME → bound.\n"
    "t_end: end of the fitting window in recording time [s] (default: 12 ms before the impact that ends phase 4).\n"
    "max_evaluations: Nelder–Mead budget (0: default). global_stage=False: local search from the data estimate.\n"
    "keep_bias=True: do not subtract the gyro bias measured at rest before the release.\n"
    "estimate_gyro_scale: 'off', 'common' or 'per-axis': a gyro scale factor estimated in the fit (the result's\n"
    "  gyro_scale: mode, value, interval_95), as `rockfit fit --estimate-gyro-scale`.\n"
    "fit_release_roll=True: estimate the release roll release_roll [rad] (the block released on one corner of its\n"
    "  release edge), as `rockfit fit --fit-release-roll` (the same as free='release_roll'). Without it the roll is\n"
    "  fitted when the fall before the first impact shows one (`rockfit fit`'s --release-roll-mode auto; the\n"
    "  result's release_roll_choice says whether and why); fix={'release_roll': 0} holds it at 0.\n";

}  // namespace

void RegisterFit(py::module_& m) {
  m.def("fit", &Fit, py::arg("recording"), py::arg("block") = py::none(), py::kw_only(), py::arg("method") = "auto",
        py::arg("bounds") = "empirical", py::arg("free") = py::none(), py::arg("fix") = py::none(),
        py::arg("lower") = py::none(), py::arg("upper") = py::none(), py::arg("t_end") = py::none(),
        py::arg("max_evaluations") = 0, py::arg("global_stage") = true, py::arg("keep_bias") = false,
        py::arg("threads") = 0, py::arg("estimate_gyro_scale") = "off", py::arg("fit_release_roll") = false,
        (std::string("Fits t0, α, λ, λ_lat, λ_lon of one trial by minimising the error (28) between measured and\n"
                     "simulated ω, from no starting point, as `rockfit fit --json` (the same code and result).\n\n"
                     "recording: a rockfit.Recording; block: a rockfit.Block (default: the recording's manifest block).\n") +
         kProblemArgs +
         "threads: threads of the global stage (0: all cores; 1 when running several fits in parallel).\n\n"
         "Returns a Record 'FitResult': trial; parameters, a dict name → Record 'Parameter' (value, lower, upper,\n"
         "fixed, std_error (None where not available), identifiable, at_bound, start, unit, and any further fields the\n"
         "fitter reports); values (name → value); epsilon and epsilon_initial (28) [rad/s]; t_end [s]; simulations;\n"
         "wall_s [s]; termination; warnings (Records kind, parameter, message); feasible, converged, method,\n"
         "kept_stage, stages, failures, model; notes (how the start was found), settings, report (the table); and\n"
         "for plots t [s] (the nodes of (28)), w_B_measured and w_B_simulated [rad/s] (N, 3), impact_times [s],\n"
         "impact_kinds. The GIL is released while the fit runs; Ctrl-C interrupts it (KeyboardInterrupt).")
            .c_str());
  m.def("fit_campaign", &FitCampaign, py::arg("manifest"), py::kw_only(), py::arg("trials") = py::none(),
        py::arg("jobs") = 0, py::arg("method") = "auto", py::arg("bounds") = "empirical", py::arg("free") = py::none(),
        py::arg("fix") = py::none(), py::arg("lower") = py::none(), py::arg("upper") = py::none(),
        py::arg("t_end") = py::none(), py::arg("max_evaluations") = 0, py::arg("global_stage") = true,
        py::arg("keep_bias") = false, py::arg("estimate_gyro_scale") = "off", py::arg("fit_release_roll") = false,
        (std::string("Fits every trial of a campaign manifest in parallel, as `rockfit batch` (one thread per trial,\n"
                     "jobs trials at once, at most one per core; 0: all cores), without writing a file.\n\n"
                     "trials: a list of trial ids (default: all).\n") +
         kProblemArgs +
         "\nReturns a list in manifest order: a 'FitResult' per fitted trial (see fit()), or a Record 'FitFailure'\n"
         "(trial, error: 'ValueError', 'InputError' or 'NumericalError', message) for a trial that could not be\n"
         "fitted. The GIL is released; Ctrl-C interrupts.")
            .c_str());
  m.def("evaluate", &Evaluate, py::arg("recording"), py::arg("block") = py::none(), py::kw_only(),
        py::arg("t0") = py::none(), py::arg("alpha") = py::none(), py::arg("lambda_") = py::none(),
        py::arg("lambda_lat") = py::none(), py::arg("lambda_lon") = py::none(), py::arg("bounds") = "empirical",
        py::arg("fix") = py::none(), py::arg("t_end") = py::none(), py::arg("keep_bias") = false,
        "The error (28) at given parameters, as `rockfit fit --evaluate --json`: t0 [s], alpha [rad], lambda_,\n"
        "lambda_lat, lambda_lon (None: the data estimate), over the fitting window of fit() (t_end [s]).\n\n"
        "Returns a Record 'Evaluation': trial, epsilon [rad/s] (None when the model cannot run), feasible, failure,\n"
        "t_end [s], parameters (name → {value, given}).");
}

}  // namespace rockfit::python
