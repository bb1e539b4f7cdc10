#!/usr/bin/env python3
"""How far the attitude integrated from the gyro moves the OPMF and AVRF (io/README.md, "Attitude from the gyro").

   tools/gyro_attitude_study.py [--rockfit PROGRAM] [--manifest MANIFEST] [--variants DIR TRIAL]
                                [--held-out DIR N] [--anchors TRIAL...]

For every trial of the sample campaign (data-samples/manifest.toml) it runs `rockfit metrics` twice: with the
attitude files (`file`) and with `--orientation none`, where the attitude is integrated from the gyro and levelled
by the accelerometer (`gyro`), and prints both beside the truth of the synthetic trial (its _truth.json: the OPMF of
the true motion; the AVRF has no closed form and is not in the truth).

--variants DIR TRIAL makes TRIAL again with `rockfit synth` (the command in its truth file) in DIR, also without the
gyro's ringing (--no-ringing), without the attitude drift (--no-drift) and as an ideal sensor (--no-noise), and
prints the same comparison for each: which artefact of the device moves which reading.

--held-out DIR N makes N further synthetic trials with `rockfit synth` in DIR, their parameters and device
artefacts drawn (fixed seed) from the ranges of the sample campaign (tools/make_samples.sh), and prints the same
comparison: trials the sample campaign's numbers were not seen on. --held-out-seed S draws another set (default
29; the synth seeds are 100·S + k). With --truth each trial is also made as an ideal sensor (its attitude files
are then the true angles) and the AVRF read from it is printed beside the others: how far each path is from the
truth, as the attitude files have errors of their own; and the AVRF's sensitivity, how much 0.1 mrad at the two
peaks of the median ratio (each moved to widen it) moves the AVRF read from the files.

--anchors TRIAL... prints, for each anchor of φ_y of each TRIAL (a manifest trial id, or the prefix of a synth
recording with its _truth.json), its time minus the nearest true impact's, read with the attitude files and
without (through the Python module built in build/python), and the drift-corrected φ_y at the AVRF's peaks
both ways: where the gyro-only path misplaces the impacts, and what that does to the peaks.

Run once and report; the CI checks the small form (tests/tools/cli_csv_campaign_test.cpp).
"""
import argparse
import json
import os
import shlex
import subprocess
import sys

HERE = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
# The held-out blocks' half-width and height [m] (tools/make_samples.sh); their depth b2 varies.
B1_M, H_M = 0.05000453, 0.2
# The options `rockfit synth` takes for a measurement artefact; an ideal sensor (--no-noise) takes none of them.
MEASUREMENT_OPTIONS = ("--gyro-noise-dps", "--gyro-bias-dps", "--ringing-gain", "--ringing-frequency-hz",
                       "--ringing-decay-time-s", "--drift-slope-dps", "--drift-walk-deg-per-rt-s", "--accel-noise-g")


def metrics(rockfit, args):
    run = subprocess.run([rockfit, "metrics"] + args + ["--json"], capture_output=True, text=True, check=False)
    if run.returncode != 0:
        sys.exit("rockfit metrics %s failed (exit %d): %s" % (" ".join(args), run.returncode, run.stderr.strip()))
    return json.loads(run.stdout)


def row(label, file_m, gyro_m, truth_opmf):
    d_opmf = gyro_m["opmf"] - file_m["opmf"]
    d_avrf = gyro_m["avrf"] / file_m["avrf"] - 1.0
    return ("%-12s %8.4f %8.4f %8.4f %+8.4f %+8.4f %+8.4f %8.4f %8.4f %+7.2f%%" %
            (label, file_m["opmf"], gyro_m["opmf"], truth_opmf, d_opmf, file_m["opmf"] - truth_opmf,
             gyro_m["opmf"] - truth_opmf, file_m["avrf"], gyro_m["avrf"], 100.0 * d_avrf))


HEADER = ("%-12s %8s %8s %8s %8s %8s %8s %8s %8s %8s" %
          ("trial", "OPMF", "OPMF", "OPMF", "gyro-", "file-", "gyro-", "AVRF", "AVRF", "gyro/"))
HEADER2 = ("%-12s %8s %8s %8s %8s %8s %8s %8s %8s %8s" %
           ("", "file", "gyro", "truth", "file", "truth", "truth", "file", "gyro", "file-1"))


def campaign(rockfit, manifest):
    import tomllib
    with open(manifest, "rb") as f:
        trials = tomllib.load(f)["trials"]
    recordings = os.path.join(os.path.dirname(manifest), "recordings")
    print(HEADER)
    print(HEADER2)
    worst_opmf = worst_avrf = 0.0
    for trial in trials:
        file_m = metrics(rockfit, [manifest, "--trial", trial["id"]])
        gyro_m = metrics(rockfit, [manifest, "--trial", trial["id"], "--orientation", "none"])
        with open(os.path.join(recordings, trial["id"] + "_truth.json"), encoding="utf-8") as f:
            truth_opmf = json.load(f)["summary"]["opmf"]
        print(row(trial["id"], file_m, gyro_m, truth_opmf))
        worst_opmf = max(worst_opmf, abs(gyro_m["opmf"] - file_m["opmf"]))
        worst_avrf = max(worst_avrf, abs(gyro_m["avrf"] / file_m["avrf"] - 1.0))
    print("largest |OPMF gyro − file| %.4f, largest |AVRF gyro/file − 1| %.2f %%" % (worst_opmf, 100.0 * worst_avrf))


def variants(rockfit, manifest, out_dir, trial_id):
    import tomllib
    with open(manifest, "rb") as f:
        spec = tomllib.load(f)
    trial = next(t for t in spec["trials"] if t["id"] == trial_id)
    recordings = os.path.join(os.path.dirname(manifest), "recordings")
    with open(os.path.join(recordings, trial_id + "_truth.json"), encoding="utf-8") as f:
        truth = json.load(f)
    command = shlex.split(truth["command"])[1:]  # without the program name
    out_at = command.index("-o")
    del command[out_at:out_at + 2]
    os.makedirs(out_dir, exist_ok=True)
    print(HEADER)
    print(HEADER2)
    for label, synth_args in (("as sampled", command), ("no ringing", command + ["--no-ringing"]),
                              ("no drift", command + ["--no-drift"]), ("ideal", ideal_command(command))):
        prefix = os.path.join(out_dir, label.replace(" ", "-"))
        subprocess.run([rockfit] + synth_args + ["-o", prefix], check=True, capture_output=True)
        common = ["--manifest", manifest, "--block", trial["block"]]
        if trial.get("mounting"):
            common += ["--mounting", trial["mounting"]]
        file_m = metrics(rockfit, [prefix] + common)
        gyro_m = metrics(rockfit, [prefix] + common + ["--orientation", "none"])
        print(row(label, file_m, gyro_m, truth["summary"]["opmf"]))


def ideal_command(command):
    """The synth command without the measurement artefacts, as an ideal sensor (--no-noise)."""
    ideal, skip = [], False
    for word in command:
        if skip:
            skip = False
            continue
        name = word.split("=", 1)[0]
        if name in MEASUREMENT_OPTIONS:
            skip = "=" not in word
            continue
        ideal.append(word)
    return ideal + ["--no-noise"]


def median_sensitivity(m, b1, h):
    """|ΔAVRF|/AVRF [%] when the two peaks of the median ratio move by 0.1 mrad each, so as to widen it."""
    import math
    ratios, peaks = m["avrf_ratios"], m["avrf_peak_angles"]
    order = sorted(range(len(ratios)), key=lambda i: ratios[i])
    i = order[len(order) // 2]
    def relative(phi):
        return 1e-4 * abs(b1 * math.cos(phi) - h * math.sin(phi)) / (b1 * math.sin(phi) - h * (1.0 - math.cos(phi)))
    return 100.0 * 0.5 * (relative(peaks[i]) + relative(peaks[i + 1]))


def held_out(rockfit, out_dir, count, seed, truth=False):
    import random
    draw = random.Random(seed)
    os.makedirs(out_dir, exist_ok=True)
    print(HEADER + ("  %8s %8s %8s %8s" % ("AVRF", "gyro/", "file/", "0.1mrad") if truth else ""))
    print(HEADER2 + ("  %8s %8s %8s %8s" % ("ideal", "ideal-1", "ideal-1", "moves") if truth else ""))
    worst_opmf = worst_avrf = 0.0
    beyond_opmf = beyond_avrf = 0
    gaps = {"gyro": [], "file": []}
    for k in range(count):
        b2 = (0.025, 0.035, 0.045, 0.06)[k % 4]
        block = ["--b1", repr(B1_M), "--b2", repr(b2), "--h", repr(H_M), "--density", "2692"]
        bias = ",".join("%.3f" % draw.uniform(-0.06, 0.06) for _ in range(3))
        synth = block + ["--alpha", "%.3f" % draw.uniform(0.17, 0.24), "--lambda", "%.2f" % draw.uniform(1.0, 2.5),
                         "--lambda-lat", "%.2f" % draw.uniform(-4.5, 4.5),
                         "--lambda-lon", "%.2f" % draw.uniform(0.2, 1.3), "--t0", "%.2f" % draw.uniform(1.2, 2.0),
                         "--duration", "5.5", "--rate", "256", "--quaternion-rate", "256", "--no-rotation-matrix",
                         "--seed", str(100 * seed + k), "--gyro-noise-dps", "0.1", "--gyro-bias-dps=" + bias,
                         "--ringing-gain", "%.2f" % draw.uniform(0.18, 0.32),
                         "--ringing-frequency-hz", "%.1f" % draw.uniform(34, 45),
                         "--ringing-decay-time-s", "%.3f" % draw.uniform(0.022, 0.04),
                         "--drift-slope-dps=0.02,-0.03,0.3", "--drift-walk-deg-per-rt-s=0.01,0.01,0.03"]
        prefix = os.path.join(out_dir, "held-%02d" % k)
        made = subprocess.run([rockfit, "synth"] + synth + ["-o", prefix], capture_output=True, text=True, check=False)
        if made.returncode != 0:
            print("%-12s synth: %s" % ("held-%02d" % k, made.stderr.strip().splitlines()[-1]))
            continue
        file_m = metrics(rockfit, [prefix] + block)
        gyro_m = metrics(rockfit, [prefix] + block + ["--orientation", "none"])
        with open(prefix + "_truth.json", encoding="utf-8") as f:
            truth_opmf = json.load(f)["summary"]["opmf"]
        line = row("held-%02d" % k, file_m, gyro_m, truth_opmf)
        if truth:
            ideal_prefix = prefix + "-ideal"
            subprocess.run([rockfit, "synth"] + ideal_command(synth) + ["-o", ideal_prefix], capture_output=True,
                           check=True)
            ideal_m = metrics(rockfit, [ideal_prefix] + block)
            for label, m in (("gyro", gyro_m), ("file", file_m)):
                gaps[label].append(m["avrf"] / ideal_m["avrf"] - 1.0)
            line += "  %8.4f %+7.2f%% %+7.2f%% %7.2f%%" % (ideal_m["avrf"], 100.0 * gaps["gyro"][-1],
                                                        100.0 * gaps["file"][-1],
                                                        median_sensitivity(file_m, B1_M, H_M))
        print(line)
        d_opmf = abs(gyro_m["opmf"] - file_m["opmf"])
        d_avrf = abs(gyro_m["avrf"] / file_m["avrf"] - 1.0)
        worst_opmf, worst_avrf = max(worst_opmf, d_opmf), max(worst_avrf, d_avrf)
        beyond_opmf += d_opmf > 0.003
        beyond_avrf += d_avrf > 0.01
    print("largest |OPMF gyro − file| %.4f (%d beyond 0.003), largest |AVRF gyro/file − 1| %.2f %% (%d beyond 1 %%)" %
          (worst_opmf, beyond_opmf, 100.0 * worst_avrf, beyond_avrf))
    for label in gaps if truth else ():
        values = [abs(v) for v in gaps[label]]
        print("largest |AVRF %s/ideal − 1| %.2f %% (%d beyond 1 %%), mean %.2f %%" %
              (label, 100.0 * max(values), sum(v > 0.01 for v in values), 100.0 * sum(values) / len(values)))


def anchors(manifest, trials):
    sys.path.insert(0, os.path.join(HERE, "build", "python"))
    import numpy
    import rockfit
    for trial in trials:
        if os.path.exists(trial + "_truth.json"):
            path, trial_id, truth_path = trial, None, trial + "_truth.json"
        else:
            path, trial_id = manifest, trial
            truth_path = os.path.join(os.path.dirname(manifest), "recordings", trial + "_truth.json")
        with open(truth_path, encoding="utf-8") as f:
            truth = json.load(f)
        impacts = truth["impacts"]
        columns = truth["impact_columns"]
        true_t = numpy.array([i[columns.index("t_s")] for i in impacts])
        w_minus_y = numpy.array([i[columns.index("w_minus_B_y_rad_s")] for i in impacts])
        w_plus_y = numpy.array([i[columns.index("w_plus_B_y_rad_s")] for i in impacts])
        block = rockfit.Block(*[truth["block"][k] for k in ("b1_m", "b2_m", "h_m")], mass=truth["block"]["mass_kg"]) \
            if trial_id is None else None
        readings = {}
        for label, orientation in (("file", "auto"), ("gyro", "none")):
            recording = rockfit.load_recording(path, trial_id, orientation=orientation)
            readings[label] = rockfit.metrics(recording, block)
        print("%s: OPMF file %.4f gyro %.4f true %.4f; AVRF file %.4f gyro %.4f (%+.2f %%)" % (
            trial, readings["file"].opmf, readings["gyro"].opmf, truth["summary"]["opmf"], readings["file"].avrf,
            readings["gyro"].avrf, 100.0 * (readings["gyro"].avrf / readings["file"].avrf - 1.0)))
        print("  %9s %8s %8s %10s %10s %10s %10s" % ("t true", "w- y", "w+ y", "file-true", "gyro-true",
                                                    "w-(gyro-t)", "anchor g-f"))
        file_by_t = {round(a.t, 2): a for a in readings["file"].impacts}
        dt = 1.0 / readings["file"].rate_hz
        worst = {"file": 0.0, "gyro": 0.0}
        for a in readings["gyro"].impacts:
            k = int(numpy.argmin(numpy.abs(true_t - a.t)))
            f = min(readings["file"].impacts, key=lambda b: abs(b.t - a.t))
            if abs(f.t - a.t) > dt:
                f = None
            gyro_dt = a.t - true_t[k]
            file_dt = f.t - true_t[k] if f is not None else float("nan")
            worst["gyro"] = max(worst["gyro"], abs(w_minus_y[k] * gyro_dt))
            if f is not None:
                worst["file"] = max(worst["file"], abs(w_minus_y[k] * file_dt))
            print("  %9.5f %8.4f %8.4f %+8.3fms %+8.3fms %+8.2e %+8.2e" % (
                true_t[k], w_minus_y[k], w_plus_y[k], 1e3 * file_dt, 1e3 * gyro_dt, w_minus_y[k] * gyro_dt,
                (a.value - f.value) if f is not None else float("nan")))
        print("  largest |ω⁻_y·(anchor time − true time)|: file %.2e rad, gyro %.2e rad" % (worst["file"], worst["gyro"]))
        print("  AVRF peaks (corrected |φ_y|): file", " ".join("%.5f" % v for v in readings["file"].avrf_peak_angles))
        print("                                gyro", " ".join("%.5f" % v for v in readings["gyro"].avrf_peak_angles))


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--rockfit", default=os.path.join(HERE, "build", "tools", "rockfit"))
    parser.add_argument("--manifest", default=os.path.join(HERE, "data-samples", "manifest.toml"))
    parser.add_argument("--variants", nargs=2, metavar=("DIR", "TRIAL"))
    parser.add_argument("--held-out", nargs=2, metavar=("DIR", "N"))
    parser.add_argument("--held-out-seed", type=int, default=29,
                        help="seed of the held-out draw (29: the trials io/README.md reports first)")
    parser.add_argument("--truth", action="store_true",
                        help="with --held-out: also read each trial as an ideal sensor (the AVRF of the true angles)")
    parser.add_argument("--anchors", nargs="+", metavar="TRIAL")
    args = parser.parse_args()
    if args.anchors:
        anchors(args.manifest, args.anchors)
    elif args.held_out:
        held_out(args.rockfit, args.held_out[0], int(args.held_out[1]), args.held_out_seed, args.truth)
    elif args.variants:
        variants(args.rockfit, args.manifest, *args.variants)
    else:
        campaign(args.rockfit, args.manifest)


if __name__ == "__main__":
    main()
