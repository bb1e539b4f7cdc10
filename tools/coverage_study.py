#!/usr/bin/env python3
"""Coverage study of rockfit's parameter intervals (fitting/README.md, "Intervals").

Makes random synthetic trials with `rockfit synth` (noise, gyro bias, quantisation, ringing after impacts and
attitude drift, all on), fits each with `rockfit fit --json` for every interval method asked for, evaluates (28)
at the true parameters with `rockfit fit --evaluate` over the same window, and reports per method and
parameter:

  * how often the parameter is reported `determined` yes / sign only / no;
  * among the `yes` ones, how often the 68 % and the 95 % interval hold the true value (targets 60–80 % and
    ≥ 90 %) and the median width of each;
  * among the `sign only` ones, how often the sign is right; among the `no` ones, how often the 95 %
    interval (with its open ends) still holds the truth;
  * ε of the fit over ε of the truth: the fraction ≤ 1.02 and every miss with its ε;
  * the cost (simulations and wall time per fit).

Random ranges (one seed gives the same trials): b1 = 5 cm, b2 = 2.5–7 cm (narrow to deep), h = 15–25 cm, tilt
α = 0.5–0.97 θ_c, λ = 0.3–2.5, λ_lon = 0.1–1.4, |λ_lat| of either sign: 0.05–0.5 in one trial in three (weak
lateral motion), 0.5–3 otherwise; t0 = 0.8–1.6 s; a gyro bias of up to 0.3 deg/s per axis.

`--ringing-scale F` multiplies the ringing frequency, gain and decay time of `synth`'s default measurement model
(38 Hz, 0.25, 0.03 s) by F, because real ringing will not match the generator.

`--sensor-family NAME` changes the gyroscope columns of each recording after `synth` wrote it (the truth stays
that of the motion), for sensor errors the measurement model does not make:
  gyro-scale       each axis scaled by 1 ± 1–2 % (random sign and size per axis)
  non-orthogonal   each sensor axis tilted by 0.5° towards another (ω_x += s·ω_y, ω_y += s·ω_z, ω_z += s·ω_x,
                   s = ±sin 0.5°, random signs)
  dropped-samples  0.5 % of the inertial rows removed at random (the x-IMU's files carry no time: a reader that
                   trusts the rate shifts everything after a drop by one sample)
  clock            the sensor's clock off by ±100 ppm and each sample taken with a timing jitter of σ = 0.3 ms
                   (the gyro resampled linearly at the true sample times; the file still says 256 Hz)
  saturation       every gyro axis clipped at a full scale of 0.6–0.9 × the recording's largest |ω| (a gyro
                   whose range is too small for the block)
  ringing-two-mode synth's ringing replaced by two modes per impact: gain 0.15–0.25 at 25–45 Hz decaying in
                   20–40 ms plus gain 0.08–0.18 at 60–110 Hz decaying in 5–15 ms (random phase)
  ringing-hammer   synth's ringing replaced by a hammer-like blow: gain 0.2–0.35 × the jump, a cosine of 20–60 Hz
                   starting at its peak, under a power-law envelope (1 + t/T)^-3, T = 5–15 ms
  The two ringing families locate the impacts in a noiseless run of the same trial (`synth --no-noise`) by the
  jumps of ω and ring with the jump each shows.

Usage (from the repository root, after building):

  nice tools/coverage_study.py --rockfit build/tools/rockfit --trials 100 --seed 1 \\
      --methods fast,thorough --out build/coverage-1 [--ringing-scale 2]

`--synth-rockfit PATH` makes the recordings with another program than the one that fits them (default: the
`--rockfit` given), so that two programs compared with tools/compare_fit_runs.py fit the same files: `synth`'s
output moves with the integrator's round-off from one version to the next.

Writes OUT/trials.jsonl (one line per trial and method: truth, fit JSON, ε of the truth) and prints the tables
(also in OUT/report.md). `--report-only` re-prints the tables from an existing trials.jsonl. Each fit runs
on one thread (`--threads 1`); run one study per core at most.
"""
import argparse
import json
import math
import os
import random
import statistics
import subprocess
import sys
import time

PARAMETERS = ["t0", "alpha", "lambda", "lambda_lat", "lambda_lon"]
SYNTH_RINGING = {"--ringing-frequency-hz": 38.0, "--ringing-gain": 0.25, "--ringing-decay-time-s": 0.03}
EPSILON_RATIO_TARGET = 1.02


def random_trial(rng, index):
    b1, b2, h = 0.05, rng.uniform(0.025, 0.07), rng.uniform(0.15, 0.25)
    theta_c = math.atan(b1 / h)
    weak = rng.random() < 1.0 / 3.0
    magnitude = rng.uniform(0.05, 0.5) if weak else rng.uniform(0.5, 3.0)
    return {
        "index": index,
        "b1": b1, "b2": b2, "h": h, "theta_c": theta_c,
        "t0": rng.uniform(0.8, 1.6),
        "alpha": rng.uniform(0.5, 0.97) * theta_c,
        "lambda": rng.uniform(0.3, 2.5),
        "lambda_lat": magnitude * rng.choice([-1.0, 1.0]),
        "lambda_lon": rng.uniform(0.1, 1.4),
        "bias_dps": [rng.uniform(-0.3, 0.3) for _ in range(3)],
        "seed": rng.randrange(1, 2**31),
        "weak_lateral": weak,
    }


def run(cmd):
    r = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    return r.returncode, r.stdout, r.stderr


def block_args(t):
    return ["--b1", repr(t["b1"]), "--b2", repr(t["b2"]), "--h", repr(t["h"]), "--density", "2692"]


SENSOR_FAMILIES = ["gyro-scale", "non-orthogonal", "dropped-samples", "clock", "saturation", "ringing-two-mode",
                   "ringing-hammer"]
RINGING_FAMILIES = ["ringing-two-mode", "ringing-hammer"]
RATE_HZ = 256.0
CLOCK_ERROR = 100e-6          # relative clock-rate error of the `clock` family
JITTER_S = 0.3e-3             # σ of the sample-time jitter of the `clock` family [s]
IMPACT_JUMP_DPS = 2.0        # a jump of ω above this marks an impact in a noiseless run [°/s] (20 × its 1/16 °/s step)


def read_gyro(path):
    with open(path) as f:
        header, *rows = f.read().splitlines()
    columns = [c.strip() for c in header.split(",")]
    gyro = [columns.index(f"Gyroscope {axis} (deg/s)") for axis in "XYZ"]
    return header, rows, gyro


def impacts_from_clean(path):
    """(sample index, jump in °/s per axis) where the noiseless ω of `path` jumps: the step into the sample less
    the mean of the steps either side, at its local maxima in size above IMPACT_JUMP_DPS."""
    _, rows, gyro = read_gyro(path)
    w = [[float(r.split(",")[i]) for i in gyro] for r in rows]
    step = [[w[k][a] - w[k - 1][a] for a in range(3)] for k in range(1, len(w))]  # step[k-1]: into sample k
    jump = {}
    for k in range(2, len(w) - 1):
        j = [step[k - 1][a] - 0.5 * (step[k - 2][a] + step[k][a]) for a in range(3)]
        jump[k] = (math.sqrt(sum(x * x for x in j)), j)
    out = []
    for k, (size, j) in jump.items():
        if size > IMPACT_JUMP_DPS and size >= jump.get(k - 1, (0,))[0] and size >= jump.get(k + 1, (0,))[0]:
            out.append((k, j))
    return out


def ringing_shape(family, rng):
    """A function of (time since the impact [s]) → gain, the ringing of `family` per unit jump."""
    if family == "ringing-two-mode":
        g1, f1, t1 = rng.uniform(0.15, 0.25), rng.uniform(25, 45), rng.uniform(0.02, 0.04)
        g2, f2, t2, phase = rng.uniform(0.08, 0.18), rng.uniform(60, 110), rng.uniform(0.005, 0.015), rng.uniform(0, 2 * math.pi)
        return lambda dt: (g1 * math.exp(-dt / t1) * math.sin(2 * math.pi * f1 * dt)
                           + g2 * math.exp(-dt / t2) * math.sin(2 * math.pi * f2 * dt + phase))
    g, f, t = rng.uniform(0.2, 0.35), rng.uniform(20, 60), rng.uniform(0.005, 0.015)
    return lambda dt: g * (1.0 + dt / t) ** -3 * math.cos(2 * math.pi * f * dt)


def gyro_scale_draw(rng):
    """The gyro-scale family's scale per axis: 1 ± 1–2 %, random sign and size (the first draws of the trial's rng)."""
    return [1.0 + rng.uniform(0.01, 0.02) * rng.choice([-1.0, 1.0]) for _ in range(3)]


def perturb_gyro(prefix, family, rng, impacts=None):
    """Rewrites <prefix>_CalInertialAndMag.csv with the sensor error of `family` (see the module's help)."""
    path = prefix + "_CalInertialAndMag.csv"
    header, rows, gyro = read_gyro(path)
    if family == "dropped-samples":
        rows = [r for r in rows if rng.random() >= 0.005]
    elif family in ("clock", "saturation") or family in RINGING_FAMILIES:
        cells = [r.split(",") for r in rows]
        w = [[float(c[i]) for i in gyro] for c in cells]
        n = len(w)
        if family == "clock":
            rate_error = CLOCK_ERROR * rng.choice([-1.0, 1.0])
            new = []
            for k in range(n):
                x = k * (1.0 - rate_error) + rng.gauss(0.0, JITTER_S * RATE_HZ)  # true time in samples
                x = min(max(x, 0.0), n - 1.0)
                j = min(int(x), n - 2)
                f = x - j
                new.append([(1 - f) * w[j][a] + f * w[j + 1][a] for a in range(3)])
            w = new
        elif family == "saturation":
            full_scale = rng.uniform(0.6, 0.9) * max(abs(v) for row in w for v in row)
            w = [[min(max(v, -full_scale), full_scale) for v in row] for row in w]
        else:
            shape = ringing_shape(family, rng)
            for k0, jump in impacts or []:
                for k in range(k0, min(n, k0 + int(0.3 * RATE_HZ))):
                    g = shape((k - k0) / RATE_HZ)
                    for a in range(3):
                        w[k][a] += g * jump[a]
        for c, row in zip(cells, w):
            for a, i in enumerate(gyro):
                c[i] = repr(round(row[a] * 16.0) / 16.0 if family in RINGING_FAMILIES else row[a])
        rows = [",".join(c) for c in cells]
    else:
        if family == "gyro-scale":
            scale = gyro_scale_draw(rng)
            mix = [[scale[0], 0, 0], [0, scale[1], 0], [0, 0, scale[2]]]
        elif family == "non-orthogonal":
            s = [math.sin(math.radians(0.5)) * rng.choice([-1.0, 1.0]) for _ in range(3)]
            mix = [[1, s[0], 0], [0, 1, s[1]], [s[2], 0, 1]]
        else:
            raise ValueError(f"unknown sensor family {family}")
        out = []
        for r in rows:
            cells = r.split(",")
            w = [float(cells[i]) for i in gyro]
            for k, i in enumerate(gyro):
                cells[i] = repr(sum(mix[k][j] * w[j] for j in range(3)))
            out.append(",".join(cells))
        rows = out
    with open(path, "w") as f:
        f.write("\n".join([header] + rows) + "\n")


def remove_file_set(prefix):
    """Deletes the files synth wrote for one trial (those that exist)."""
    for suffix in ["_CalInertialAndMag.csv", "_EulerAngles.csv", "_Quaternion.csv", "_Registers.csv",
                   "_DateTime.csv", "_CalBattAndTherm.csv", "_truth.json"]:
        try:
            os.remove(prefix + suffix)
        except OSError:
            pass


def widening_args(args):
    """The widening options of `rockfit fit` that were given (none: rockfit's calibrated defaults)."""
    out = []
    if args.model_error_widening is not None:
        out += ["--model-error-widening", repr(args.model_error_widening)]
    if args.t0_floor_samples is not None:
        out += ["--t0-floor-samples", repr(args.t0_floor_samples)]
    return out + gyro_scale_args(args)


def gyro_scale_args(args):
    """`rockfit fit --estimate-gyro-scale MODE` when given (the fit and the truth's ε both of the scaled model)."""
    return ["--estimate-gyro-scale", args.estimate_gyro_scale] if args.estimate_gyro_scale else []


def study_trial(args, t, workdir):
    prefix = os.path.join(workdir, f"trial{t['index']:03d}")
    synth = [args.synth_rockfit or args.rockfit, "synth", "-o", prefix, "--t0", repr(t["t0"]), "--duration", repr(t["t0"] + 2.5),
             "--alpha", repr(t["alpha"]), "--lambda", repr(t["lambda"]), "--lambda-lat", repr(t["lambda_lat"]),
             "--lambda-lon", repr(t["lambda_lon"]), "--seed", str(t["seed"]), "--no-rotation-matrix",
             "--gyro-bias-dps=" + ",".join(repr(b) for b in t["bias_dps"])] + block_args(t)
    if args.ringing_scale != 1.0:
        for option, value in SYNTH_RINGING.items():
            synth += [option, repr(value * args.ringing_scale)]
    impacts = None
    if args.sensor_family in RINGING_FAMILIES:
        clean = prefix + "_clean"
        code, _, err = run([c if c != prefix else clean for c in synth if not c.startswith("--gyro-bias-dps")]
                           + ["--no-noise"])
        if code != 0:
            return [{"trial": t, "error": "synth --no-noise: " + err.strip()}]
        impacts = impacts_from_clean(clean + "_CalInertialAndMag.csv")
        remove_file_set(clean)
        synth += ["--no-ringing"]
    code, _, err = run(synth)
    if code != 0:
        return [{"trial": t, "error": "synth: " + err.strip()}]
    if args.sensor_family:
        perturb_gyro(prefix, args.sensor_family, random.Random(t["seed"]), impacts)
    rows = []
    for method in args.methods:
        started = time.time()
        code, out, err = run([args.rockfit, "fit", prefix, "--json", "--threads", "1", "--intervals", method] + widening_args(args)
                             + block_args(t))
        wall = time.time() - started
        if code != 0:
            rows.append({"trial": t, "method": method, "error": f"fit exit {code}: {err.strip()}"})
            continue
        fit = json.loads(out)
        code, out, err = run([args.rockfit, "fit", prefix, "--json", "--evaluate", "--t-end", repr(fit["t_end"]),
                              "--t0", repr(t["t0"]), "--alpha", repr(t["alpha"]), "--lambda", repr(t["lambda"]),
                              "--lambda-lat", repr(t["lambda_lat"]), "--lambda-lon", repr(t["lambda_lon"])]
                             + gyro_scale_args(args) + block_args(t))
        truth_eps = json.loads(out)["epsilon"] if code == 0 else None
        row = {"trial": t, "method": method, "fit": fit, "epsilon_truth": truth_eps, "process_wall_s": wall}
        if args.sensor_family == "gyro-scale":
            row["gyro_scale_truth"] = gyro_scale_draw(random.Random(t["seed"]))
        rows.append(row)
    remove_file_set(prefix)
    return rows


def contains(interval, value):
    lo, hi = interval
    return (lo is None or lo <= value) and (hi is None or value <= hi)


def width(interval):
    lo, hi = interval
    return None if lo is None or hi is None else hi - lo


def pooled_coverage_68(rows, method):
    """(held, total): the 68 % intervals over every determined parameter value of every trial of `method`."""
    held = total = 0
    for r in rows:
        if r.get("method") != method or "fit" not in r:
            continue
        for name in PARAMETERS:
            p = r["fit"]["parameters"][name]
            if p.get("determined") == "yes":
                total += 1
                held += contains(p["interval_68"], r["trial"][name])
    return held, total


def coverage_failures(rows, min_coverage_95, min_epsilon_fraction, band_68=None):
    """Reasons why the study misses the given thresholds (for the CTest version); empty when it passes."""
    failures = []
    if band_68 is not None:
        for method in sorted({r["method"] for r in rows if "method" in r}):
            held, total = pooled_coverage_68(rows, method)
            if total and not band_68[0] * total <= held <= band_68[1] * total:
                failures.append(f"{method}: the 68 % intervals hold the truth in {held}/{total} parameter values, "
                                f"outside [{band_68[0]:g}, {band_68[1]:g}]")
    for method in sorted({r["method"] for r in rows if "method" in r}):
        mine = [r for r in rows if r.get("method") == method and "fit" in r]
        if len(mine) < len([r for r in rows if r.get("method") == method]):
            failures.append(f"{method}: some fits failed")
        for name in PARAMETERS:
            yes = [r for r in mine if r["fit"]["parameters"][name].get("determined") == "yes"]
            held = sum(contains(r["fit"]["parameters"][name]["interval_95"], r["trial"][name]) for r in yes)
            if yes and held < min_coverage_95 * len(yes):
                failures.append(f"{method}: the 95 % interval of {name} holds the truth in {held}/{len(yes)}")
            for r in mine:
                p = r["fit"]["parameters"][name]
                if p.get("determined") == "sign only" and p["value"] * r["trial"][name] <= 0:
                    failures.append(f"{method}: {name} of trial {r['trial']['index']} has the wrong sign")
        ratios = [r["fit"]["epsilon"] / r["epsilon_truth"] for r in mine if r.get("epsilon_truth")]
        ok = sum(q <= EPSILON_RATIO_TARGET for q in ratios)
        if ratios and ok < min_epsilon_fraction * len(ratios):
            failures.append(f"{method}: ε ≤ {EPSILON_RATIO_TARGET} × ε(truth) in only {ok}/{len(ratios)}")
    return failures


def gyro_scale_lines(mine):
    """The estimated gyro scale per axis (`--estimate-gyro-scale`): median, how often the 95 % interval holds the
    truth (1, or the gyro-scale family's drawn scale) and the median width, over the fits that estimated it, and
    the 95 % quantile of |error| / half-width (1 for an interval exactly as wide as 95 % coverage needs)."""
    est = [r for r in mine if (r["fit"].get("gyro_scale") or {}).get("available")]
    if not est:
        return []
    lines = ["", f"gyro scale ({est[0]['fit']['gyro_scale']['mode']}), {len(est)} fits: axis, median estimate, "
                 "95 % holds the truth, median 95 % width, median |error|, 95 % quantile of |error| / half-width"]
    for a, axis in enumerate("xyz"):
        cells = []
        for r in est:
            g = r["fit"]["gyro_scale"]
            truth = r.get("gyro_scale_truth", [1.0, 1.0, 1.0])[a]
            i = g["interval_95"][a]
            cells.append((g["value"][a], truth, i))
        closed = [c for c in cells if c[2] is not None]
        held = sum(c[2][0] <= c[1] <= c[2][1] for c in closed)
        widths = [c[2][1] - c[2][0] for c in closed]
        relative = sorted(abs(c[0] - c[1]) / (0.5 * (c[2][1] - c[2][0])) for c in closed if c[2][1] > c[2][0])
        # the nearest-rank 95 % quantile
        q95 = relative[min(len(relative) - 1, math.ceil(0.95 * len(relative)) - 1)] if relative else float("nan")
        lines.append(f"  s_{axis}: {statistics.median(c[0] for c in cells):.4f}, {held}/{len(closed)} "
                     f"({100.0 * held / len(closed) if closed else 0:.0f} %), "
                     f"{statistics.median(widths) if widths else float('nan'):.4f}, "
                     f"{statistics.median(abs(c[0] - c[1]) for c in cells):.4f}, {q95:.2f}")
    return lines


def report(rows, ringing_scale):
    lines = []
    methods = sorted({r["method"] for r in rows if "method" in r})
    n_trials = len({r["trial"]["index"] for r in rows})
    lines.append(f"{n_trials} trials, ringing scale {ringing_scale:g}")
    for method in methods:
        mine = [r for r in rows if r.get("method") == method and "fit" in r]
        failed = [r for r in rows if r.get("method") == method and "error" in r]
        lines.append("")
        lines.append(f"### --intervals {method}: {len(mine)} fits, {len(failed)} failed")
        lines.append("")
        lines.append("| parameter | yes | 68 % holds | 95 % holds | median width 68 % | median width 95 % "
                     "| sign only (sign right) | no (95 % holds) |")
        lines.append("|---|---|---|---|---|---|---|---|")
        for name in PARAMETERS:
            yes, sign, no = [], [], []
            for r in mine:
                p = r["fit"]["parameters"][name]
                d = p.get("determined")
                (yes if d == "yes" else sign if d == "sign only" else no).append(r)
            truth = lambda r: r["trial"][name]
            in68 = sum(contains(r["fit"]["parameters"][name]["interval_68"], truth(r)) for r in yes)
            in95 = sum(contains(r["fit"]["parameters"][name]["interval_95"], truth(r)) for r in yes)
            w68 = [width(r["fit"]["parameters"][name]["interval_68"]) for r in yes]
            w95 = [width(r["fit"]["parameters"][name]["interval_95"]) for r in yes]
            sign_right = sum(r["fit"]["parameters"][name]["value"] * truth(r) > 0 for r in sign)
            no_holds = sum(contains(r["fit"]["parameters"][name]["interval_95"] or [None, None], truth(r)) for r in no)
            pct = lambda k, n: f"{k}/{n} ({100.0 * k / n:.0f} %)" if n else "—"
            med = lambda w: f"{statistics.median([x for x in w if x is not None]):.3g}" if any(
                x is not None for x in w) else "—"
            lines.append(f"| {name} | {len(yes)} | {pct(in68, len(yes))} | {pct(in95, len(yes))} | {med(w68)} | "
                         f"{med(w95)} | {len(sign)} ({sign_right}) | {len(no)} ({no_holds}) |")
        held, total = pooled_coverage_68(rows, method)
        if total:
            lines.append(f"| all (68 % pooled) | {total} | {held}/{total} ({100.0 * held / total:.0f} %) | | | | | |")
        statements = [r["fit"]["model_error"] for r in mine if r["fit"].get("model_error", {}).get("available")]
        if statements:
            ratios = [m["ratio"] for m in statements]
            lines.append("")
            lines.append(f"ε / noise floor at rest: median {statistics.median(ratios):.2f} (range {min(ratios):.2f}–"
                         f"{max(ratios):.2f}); model error flagged dominant in "
                         f"{sum(bool(m['dominates']) for m in statements)}/{len(statements)}, ε > 2 × floor in "
                         f"{sum(q > 2 for q in ratios)}")
        ratios = [(r["fit"]["epsilon"] / r["epsilon_truth"], r) for r in mine if r.get("epsilon_truth")]
        ok = sum(q <= EPSILON_RATIO_TARGET for q, _ in ratios)
        lines.append("")
        lines.append(f"ε ≤ {EPSILON_RATIO_TARGET} × ε(truth): {ok}/{len(ratios)}"
                     + (f" ({100.0 * ok / len(ratios):.1f} %)" if ratios else ""))
        for q, r in sorted(ratios, key=lambda x: -x[0]):
            if q > EPSILON_RATIO_TARGET:
                t = r["trial"]
                lines.append(f"  miss: trial {t['index']} ε = {r['fit']['epsilon']:.5g} rad/s, truth {r['epsilon_truth']:.5g} "
                             f"(ratio {q:.3f}); α/θc = {t['alpha'] / t['theta_c']:.3f}, λ_lat = {t['lambda_lat']:.3f}, "
                             f"λ = {t['lambda']:.3f}, b2 = {t['b2']:.3f}")
        lines += gyro_scale_lines(mine)
        sims = [r["fit"]["simulations"] for r in mine]
        unc_sims = [r["fit"].get("uncertainty", {}).get("simulations", 0) for r in mine]
        walls = [r["fit"]["wall_s"] for r in mine]
        unc_walls = [r["fit"].get("uncertainty", {}).get("wall_s", 0.0) for r in mine]
        if mine:
            lines.append(f"cost per fit (median): {statistics.median(sims):.0f} simulations, {statistics.median(walls):.2f} s; "
                         f"of which intervals {statistics.median(unc_sims):.0f} simulations, "
                         f"{statistics.median(unc_walls):.2f} s")
            moved = sum(any(w["kind"] == "moved_by_intervals" for w in r["fit"]["warnings"]) for r in mine)
            lines.append(f"fits moved to a lower (28) by the profiles: {moved}")
    return "\n".join(lines)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--rockfit", default="build/tools/rockfit")
    parser.add_argument("--synth-rockfit", default=None,
                        help="the program whose `synth` makes the recordings (default: --rockfit)")
    parser.add_argument("--trials", type=int, default=100)
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--first", type=int, default=0,
                        help="run only trials FIRST..TRIALS-1 of the seed (the earlier ones are drawn, not run): "
                             "a study split over several processes or continued later")
    parser.add_argument("--methods", default="fast,thorough")
    parser.add_argument("--ringing-scale", type=float, default=1.0)
    parser.add_argument("--model-error-widening", type=float, default=None,
                        help="rockfit fit --model-error-widening C (default: rockfit's; 0: off)")
    parser.add_argument("--t0-floor-samples", type=float, default=None,
                        help="rockfit fit --t0-floor-samples Q (default: rockfit's; 0: off)")
    parser.add_argument("--estimate-gyro-scale", default=None, choices=["off", "common", "per-axis"],
                        help="rockfit fit --estimate-gyro-scale MODE (default: rockfit's, off)")
    parser.add_argument("--sensor-family", default=None, choices=SENSOR_FAMILIES)
    parser.add_argument("--out", required=True)
    parser.add_argument("--report-only", action="store_true")
    parser.add_argument("--check-coverage-95", type=float, default=None,
                        help="exit 1 unless every parameter's 95 %% interval holds the truth in at least this "
                             "fraction of the trials where it is determined (and every 'sign only' sign is right)")
    parser.add_argument("--check-coverage-68", default=None, metavar="LO,HI",
                        help="with --check-coverage-95: also require the 68 %% intervals, pooled over every "
                             "determined parameter value, to hold the truth in a fraction within [LO, HI]")
    parser.add_argument("--check-epsilon-fraction", type=float, default=0.0,
                        help="with --check-coverage-95: also require ε ≤ 1.02 ε(truth) in this fraction")
    args = parser.parse_args()
    args.methods = [m for m in args.methods.split(",") if m]
    os.makedirs(args.out, exist_ok=True)
    path = os.path.join(args.out, "trials.jsonl")
    if not args.report_only:
        rng = random.Random(args.seed)
        trials = [random_trial(rng, i) for i in range(args.trials)][args.first:]
        with open(path, "w") as out:
            for t in trials:
                for row in study_trial(args, t, args.out):
                    out.write(json.dumps(row) + "\n")
                    out.flush()
    with open(path) as f:
        rows = [json.loads(line) for line in f if line.strip()]
    text = (f"sensor family {args.sensor_family}\n" if args.sensor_family else "") + report(rows, args.ringing_scale)
    with open(os.path.join(args.out, "report.md"), "w") as f:
        f.write(text + "\n")
    print(text)
    if args.check_coverage_95 is not None:
        band_68 = [float(x) for x in args.check_coverage_68.split(",")] if args.check_coverage_68 else None
        failures = coverage_failures(rows, args.check_coverage_95, args.check_epsilon_fraction, band_68)
        for f in failures:
            print("FAILED: " + f)
        return 1 if failures else 0
    return 0


if __name__ == "__main__":
    sys.exit(main())
