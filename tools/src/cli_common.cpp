#include "cli_common.hpp"

namespace rockfit::tools {

void AddBlockOptions(CLI::App& app, BlockArgs& args) {
  app.add_option("--b1", args.b1_m, "Block half-width along x (b1) [m]")->group("Block");
  app.add_option("--b2", args.b2_m, "Block half-depth along y (b2) [m]")->group("Block");
  app.add_option("--h", args.h_m, "Height of the centre of mass above the base (half the block height) [m]")
      ->group("Block");
  auto* density = app.add_option("--density", args.density_kg_m3, "Density [kg/m³] (granite: 2692)")->group("Block");
  auto* mass = app.add_option("--mass", args.mass_kg, "Total mass [kg]")->group("Block");
  density->excludes(mass);
  app.add_option("--manifest", args.manifest_path, "Campaign manifest (TOML) to take the block from")->group("Block");
  app.add_option("--block", args.block_id, "Block id in the manifest")->group("Block");
}

void AddFitOptions(CLI::App& app, FitArgs& args) {
  app.add_option("--method", args.method, "Back end: nelder-mead, ceres or auto (global stage, Nelder–Mead, Ceres polish)")
      ->capture_default_str();
  app.add_option("--bounds", args.bounds, "Default bounds: empirical (wider than (25)/(27)) or theoretical")
      ->capture_default_str();
  app.add_option("--free", args.free, "Parameters to fit in addition to the defaults (t0,alpha,lambda,lambda_lat,lambda_lon,tau_edge,release_roll)")
      ->delimiter(',');
  app.add_option("--fix", args.fix,
                 "Parameters to hold fixed: NAME (at the data estimate) or NAME=VALUE, e.g. --fix lambda_lat=0")
      ->delimiter(',');
  app.add_option("--lower", args.lower, "Lower bound NAME=VALUE (repeatable)");
  app.add_option("--upper", args.upper, "Upper bound NAME=VALUE (repeatable)");
  app.add_option("--t-end", args.t_end_s, "End of the fitting window in recording time [s] (default: 12 ms before the impact that ends phase 4)");
  app.add_option("--max-evaluations", args.max_evaluations, "Nelder–Mead evaluation budget (0: default)");
  app.add_flag("--no-global", args.no_global, "Skip the global stage (local search from the data estimate only)");
  app.add_flag("--keep-bias", args.keep_bias, "Do not subtract the gyro bias measured at rest before the release");
  app.add_option("--threads", args.threads, "Threads of the global stage and the intervals (0: all cores)");
  app.add_option("--intervals", args.intervals,
                 "68 % and 95 % intervals: thorough (95 %: profiles of (28)'s sum of squares, the others re-fitted, "
                 "the fit costs about 1.5 times as much; 68 %: linearised), fast (both linearised, nearly free) or none "
                 "(standard errors only)")
      ->capture_default_str();
  app.add_option("--model-error-widening", args.model_error_widening,
                 "Widen every 95 % interval for model error by √(1 + K²·(r² − 1)), r = ε/ε_noise over the noise floor at "
                 "rest (0: off; the default is calibrated: fitting/README.md, \"Intervals under model error\")")
      ->capture_default_str();
  app.add_option("--t0-floor-samples", args.t0_floor_samples,
                 "Floor of t0's 95 % half-widths in sample periods, added in quadrature (0: off)")
      ->capture_default_str();
  app.add_option("--estimate-gyro-scale", args.estimate_gyro_scale,
                 "Estimate a gyro scale factor in the fit (variable projection): off, common (one for the three axes) "
                 "or per-axis; the model is then compared scaled, and the scale is reported with its 95 % interval")
      ->capture_default_str()
      ->check(CLI::IsMember({"off", "common", "per-axis"}));
  app.add_flag("--fit-release-roll", args.fit_release_roll,
               "Estimate the release roll release_roll [rad] (the block released on one corner of its release edge, "
               "tilted alpha about the edge and rolled about the edge's inward axis), as --free release_roll or "
               "--release-roll-mode on");
  app.add_option("--release-roll-mode", args.release_roll_mode,
                 "Fit the release roll: off (held at 0), on, or auto (fitted when the gyro sees a roll in the fall "
                 "before the first impact, 8 times its noise at rest; started from the roll seen)")
      ->capture_default_str()
      ->check(CLI::IsMember({"off", "auto", "on"}));
}

void AddMetricsOptions(CLI::App& app, MetricsArgs& args) {
  io::MetricsOptions& o = args.options;
  app.add_option("--min-prominence", o.correction.impacts.min_prominence_rad_s,
                 "Impacts: peaks of |ω_y| (|ω_x|) at least this prominent [rad/s]")
      ->capture_default_str()->group("Drift correction");
  app.add_option("--min-separation", o.correction.impacts.min_separation_s,
                 "Impacts: of two peaks closer than this, the lower is ringing [s]")
      ->capture_default_str()->group("Drift correction");
  app.add_option("--anchors", args.anchors,
                 "Drift at an impact: subsample (impact located inside the sample interval) or sample (the angle at the "
                 "|ω| peak sample, as in the paper)")
      ->capture_default_str()->check(CLI::IsMember({"subsample", "sample"}))->group("Drift correction");
  app.add_option("--peaks", o.avrf.max_peaks, "AVRF: number of peak inclinations after the first impact (the paper: 10)")
      ->capture_default_str()->group("AVRF");
  app.add_option("--min-peaks", o.avrf.min_peaks, "AVRF: fewer usable peaks is the status too_few_peaks")
      ->capture_default_str()->group("AVRF");
  app.add_option("--uplift", args.uplift,
                 "AVRF: COM uplift u(φ): com = b1·sin φ − h·(1 − cos φ) (correct), paper = h·sin φ − b1·(1 − cos φ) (as "
                 "printed in the paper's Sect. 3.2)")
      ->capture_default_str()->check(CLI::IsMember({"com", "paper"}))->group("AVRF");
}

void AddRecordingOptions(CLI::App& app, RecordingArgs& args) {
  app.add_option("PATH", args.path,
                 "Recording: an x-IMU GUI prefix or file, an x-IMU3 directory, a CSV file, rockfit's HDF5 file, or a "
                 "campaign manifest (.toml) with --trial")
      ->required();
  app.add_option("--trial", args.trial_id, "Trial id, when PATH is a manifest or an HDF5 file with several trials")
      ->group("Input");
  app.add_option("--format", args.format, "Force an input format: auto, ximu-gui, ximu3, csv, rockfit-hdf5")
      ->capture_default_str()
      ->group("Input");
  app.add_option("--rate", args.rate_hz, "Gyro sample rate [Hz] when the files do not state it (x-IMU without "
                 "_Registers.csv, CSV without time)")->group("Input");
  app.add_option("--mounting", args.mounting,
                 kMountingHelp)
      ->group("Input");
  app.add_option("--columns", args.columns,
                 "Generic CSV column map, e.g. 'time=NAME@s;gyro=X,Y,Z@deg/s;euler=ROLL,PITCH,YAW@deg' (see `rockfit "
                 "inspect --help`)")
      ->group("Input");
  app.add_option("--orientation", args.orientation, "Attitude source: auto, euler, quaternion, matrix, or none (integrated from the gyro and levelled by the "
                 "accelerometer; also when the files hold no attitude)")
      ->capture_default_str()
      ->group("Input");
}

void AddGroundMotionOptions(CLI::App& app, GroundMotionArgs& a) {
  const char* group = "Ground motion";
  app.add_option("--record", a.record,
                 "Ground-motion record acting along the incidence angle: a PEER AT2 file (values in g) or a CSV "
                 "(header; optional time column `time` [s]; one to three columns: horizontal 1, horizontal 2, "
                 "vertical, or named x, y, z)")
      ->group(group);
  app.add_option("--record2", a.record2, "Second horizontal component, acting 90° from --record (AT2 or one-column CSV)")
      ->group(group);
  app.add_option("--vertical", a.vertical, "Vertical component (AT2 or one-column CSV), positive up")->group(group);
  app.add_option("--record-format", a.record_format, "auto (by extension: .csv is CSV, else AT2), at2 or csv")
      ->check(CLI::IsMember({"auto", "at2", "csv"}))->capture_default_str()->group(group);
  app.add_option("--units", a.units, "Units of CSV records: g (9.80665 m/s²), m/s2 or cm/s2")
      ->check(CLI::IsMember({"g", "m/s2", "cm/s2"}))->capture_default_str()->group(group);
  app.add_option("--dt", a.csv_dt_s, "Time step [s] of CSV records without a time column")->group(group);
  app.add_option("--synthetic", a.synthetic_seed,
                 "Instead of a record: a generated Clough–Penzien record with this seed (io/README.md, \"Stochastic "
                 "ground motion\"; PGA 0.3 g unless --pga)")
      ->group(group);
  app.add_option("--synthetic-duration", a.synthetic_duration_s, "Duration of the generated record [s]")
      ->capture_default_str()->group(group);
  app.add_option("--synthetic-dt", a.synthetic_dt_s, "Step of the generated record [s]")->capture_default_str()->group(group);
  auto* scale = app.add_option("--scale", a.scale, "Multiply every component by this factor")->group(group);
  app.add_option("--pga", a.pga_g,
                 "Scale all components by one factor so that the peak horizontal acceleration (resultant of the "
                 "horizontal components) is this many g")
      ->excludes(scale)->group(group);
  app.add_option("--angle", a.angle_deg, "Incidence angle β [deg] of --record from the block's x axis")
      ->capture_default_str()->group(group);
}

}  // namespace rockfit::tools
