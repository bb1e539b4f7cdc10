#!/usr/bin/env python3
"""Fits of recordings made by other physics: coverage of t0 and α (fitting/README.md, "Recordings made by other
physics").

Makes random recordings with `rockfit_mujoco_synth` (tests/support/mujoco_synth_main.cpp: a granite box released
tilted from rest on a plane, simulated by MuJoCo with a stiff soft contact, measured by rockfit's x-IMU model with
synth's defaults), fits each with `rockfit fit --json --threads 1` (the default `thorough` intervals) and reports
per family:

  * how often the 95 % (and 68 %) interval of t0 and of α holds the truth, and their median widths;
  * ε over the noise floor at rest (the model-error statement) and how often model error is flagged dominant;
  * the same coverage among the fits that are not flagged;
  * the check of α against the tilt at rest: how often it compares (only where the recording rests after the
    rocking: `--duration 6`), z, and the tilt at rest's own error in its σ; with `--push W`, how often it catches
    the push, by its size.

Families (one seed gives the same trials):
  mujoco            roll at release 0–0.01 rad about x (the block stands on one corner of its release edge)
  mujoco-perturbed  the same, plus the centre of mass off the axis by 1–2 % of b2 (either side) and one base
                    corner (random) 0.1 mm proud
  mujoco-planar     no roll, no perturbation (the motion stays in the plane; MuJoCo's contact alone)
  mujoco-lively     as `mujoco` with a springy contact (solref damping ratio LIVELY_DAMPING_RATIO instead of 1):
                    the box rocks for several cycles, so that its AVRF and OPMF can be measured (`--metrics`)

`--push W` gives each release a push: the box leaves its tilt at rest turning at a rate drawn uniformly from
[−W, W] rad/s about body y (> 0 towards the fall), drawn from its own generator so that the trials are otherwise
those of the seed. The truth of α stays the tilt at rest; the study then measures which pushes the check of α
against the tilt at rest catches.

`--solref-time-constant S` makes every family's contact stiffer or softer than the generator's 1 ms (MuJoCo needs
S ≥ 2 × its 1e-4 s timestep): how much of a miss is the contact's softness.

Random ranges: b1 = 0.05000453 m, h = 0.2 m, b2 = 2.5–6 cm, α = 0.5–0.95 θ_c, t0 = 0.8–1.6 s, recording 3 s (`--duration`).

Usage (from the repository root, after building the targets rockfit and rockfit_mujoco_synth):

  nice tools/other_physics_study.py --rockfit build/tools/rockfit --generator build/tests/rockfit_mujoco_synth \\
      --family mujoco --trials 30 --seed 1 --out build/other-physics-mujoco-1

Writes OUT/trials.jsonl and prints the table (also OUT/report.md); `--report-only` re-prints it.

`--metrics` (with or after a run) checks that the fitted model reproduces each recording's OPMF and AVRF (paper
Sect. 3.2, `rockfit metrics`): the recording's are measured as recorded; the model's on a `rockfit synth`
recording of the fitted t0, α, λ, λ_lat, λ_lon with the same measurement model and seed. Targets: AVRF within
2 % (relative), OPMF within 0.003 (absolute). Writes OUT/metrics.jsonl and adds the table to the report, with a
line per OPMF miss: both OPMFs, the largest drift-corrected |φx| of the recording and of the model and how long
after the first impact it comes (`rockfit correct`), and what became of the fit's window.

`--refit-rule opmf|epsilon|lateral` (with --metrics) emulates a candidate rule of the fit outside it: every parameter fitted
again on the last window the window extension tried (`rockfit fit --t-end`), kept where the model's OPMF missed and
the refit's is closer (opmf — a rule that selects on the OPMF itself, so the check is then no prediction) or where
its (28) on that common window is lower than the kept fit's (epsilon), or where its model's ω_x, ω_z miss the
recording's less over the 0.1 s after the first impact (lateral). Writes OUT/refit_RULE.jsonl and the counts
with the rule. With --report-only it reuses the fits of an earlier run.
"""
import argparse
import csv
import json
import math
import os
import random
import statistics
import subprocess
import sys

from coverage_study import widening_args  # the widening options of `rockfit fit`, as the coverage study passes them

B1, H, DENSITY = 0.05000453, 0.2, 2692.0
# The damping ratio of MuJoCo's solref in the `mujoco-lively` family: well below critical (1), the contact
# returns part of the impact's energy, and the box rocks for several cycles instead of settling after one.
LIVELY_DAMPING_RATIO = 0.1


def random_trial(rng, index, family):
    b2 = rng.uniform(0.025, 0.06)
    theta_c = math.atan(B1 / H)
    trial = {"index": index, "family": family, "b2": b2, "theta_c": theta_c,
             "alpha": rng.uniform(0.5, 0.95) * theta_c, "t0": round(rng.uniform(0.8, 1.6) * 10240) / 10240,
             "roll": 0.0 if family == "mujoco-planar" else rng.uniform(0.0, 0.01),
             "damping_ratio": LIVELY_DAMPING_RATIO if family == "mujoco-lively" else 1.0,
             "com_offset_y": 0.0, "proud_vertex": 0, "seed": 1000 + index}
    if family == "mujoco-perturbed":
        trial["com_offset_y"] = rng.uniform(0.01, 0.02) * rng.choice([-1.0, 1.0])
        trial["proud_vertex"] = rng.randint(1, 4)
    return trial


def run_trial(args, trial, out_dir):
    prefix = os.path.join(out_dir, "recordings", f"trial{trial['index']:03d}")
    subprocess.run([args.generator, "-o", prefix, "--alpha", repr(trial["alpha"]), "--roll", repr(trial["roll"]),
                    "--t0", repr(trial["t0"]), "--duration", repr(args.duration), "--b2", repr(trial["b2"]),
                    "--com-offset-y", repr(trial["com_offset_y"]), "--proud-vertex", str(trial["proud_vertex"]),
                    "--seed", str(trial["seed"]), "--solref-damping-ratio", repr(trial.get("damping_ratio", 1.0)),
                    "--push", repr(trial.get("push", 0.0))]
                   + (["--solref-time-constant", repr(args.solref_time_constant)] if args.solref_time_constant else []),
                   check=True, capture_output=True)
    fit = subprocess.run([args.rockfit, "fit", prefix, "--rate", "256", "--b1", repr(B1), "--b2", repr(trial["b2"]),
                          "--h", repr(H), "--density", repr(DENSITY), "--threads", "1", "--json"] + widening_args(args)
                         + (["--fit-release-roll"] if args.fit_release_roll else [])
                         + (["--release-roll-mode", args.release_roll_mode] if args.release_roll_mode else []),
                         capture_output=True, text=True)
    trial["exit_code"] = fit.returncode
    trial["fit"] = json.loads(fit.stdout) if fit.stdout.strip() else None
    return trial


def holds(interval, truth):
    if interval is None:
        return False
    lo, hi = interval
    return (lo is None or lo <= truth) and (hi is None or truth <= hi)


def width(interval):
    if interval is None or interval[0] is None or interval[1] is None:
        return math.inf
    return interval[1] - interval[0]


AVRF_RELATIVE_TOLERANCE = 0.02  # the fitted model's AVRF within 2 % of the recording's (the study's target)
OPMF_TOLERANCE = 0.003          # the fitted model's OPMF within 0.003 of the recording's (the study's target)


def metrics_of(args, prefix, b2):
    out = subprocess.run([args.rockfit, "metrics", prefix, "--json", "--b1", repr(B1), "--b2", repr(b2), "--h", repr(H),
                          "--density", repr(DENSITY)], capture_output=True, text=True)
    if not out.stdout.strip():
        return {"status": "error", "message": out.stderr.strip()}
    m = json.loads(out.stdout)
    return {k: m.get(k) for k in ("opmf", "avrf", "status", "opmf_status", "avrf_status")}


def largest_roll_after_first_impact(args, prefix):
    """Time after the first impact [s] and size [rad] of the largest |φx| (drift-corrected, `rockfit correct`): the
    numerator of the OPMF. On the rolled MuJoCo releases it is the first lateral swing after the base impact."""
    csv_path = prefix + "_corrected.csv"
    out = subprocess.run([args.rockfit, "correct", prefix, "-o", csv_path, "--json"], capture_output=True, text=True)
    if out.returncode != 0 or not out.stdout.strip():
        return None
    impacts = json.loads(out.stdout).get("impact_times") or []
    if not impacts:
        return None
    with open(csv_path) as f:
        rows = [(float(r["time_s"]), float(r["phi_x_corrected_rad"])) for r in csv.DictReader(f)]
    after = [r for r in rows if r[0] >= impacts[0]]
    if not after:
        return None
    t_s, phi_x = max(after, key=lambda r: abs(r[1]))
    return {"after_first_impact_s": t_s - impacts[0], "abs_phi_x_rad": abs(phi_x)}


def metrics_trial(args, trial, out_dir, model_name=None):
    """OPMF and AVRF of the recording and of the fitted model (synth with the fitted parameters, same seed)."""
    prefix = os.path.join(out_dir, "recordings", f"trial{trial['index']:03d}")
    row = {"index": trial["index"], "recording": metrics_of(args, prefix, trial["b2"])}
    p = trial["fit"]["parameters"]
    model = os.path.join(out_dir, "recordings", model_name or f"model{trial['index']:03d}")
    synth = subprocess.run([args.rockfit, "synth", "-o", model, "--t0", repr(p["t0"]["value"]),
                            "--duration", repr(args.duration),
                            "--alpha", repr(p["alpha"]["value"]), "--lambda", repr(p["lambda"]["value"]),
                            "--lambda-lat", repr(p["lambda_lat"]["value"]), "--lambda-lon", repr(p["lambda_lon"]["value"]),
                            "--b1", repr(B1), "--b2", repr(trial["b2"]), "--h", repr(H), "--density", repr(DENSITY),
                            "--seed", str(trial["seed"]), "--no-rotation-matrix"]
                           + (["--release-roll", repr(p["release_roll"]["value"])] if "release_roll" in p else []),
                           capture_output=True, text=True)
    row["model"] = metrics_of(args, model, trial["b2"]) if synth.returncode == 0 else {"status": "error",
                                                                                      "message": synth.stderr.strip()}
    row["recording"]["largest_roll"] = largest_roll_after_first_impact(args, prefix)
    if synth.returncode == 0:
        row["model"]["largest_roll"] = largest_roll_after_first_impact(args, model)
    return row


def metrics_report(rows, trials=None):
    both = lambda key: [r for r in rows if r["recording"].get(key) is not None and r["model"].get(key) is not None]
    q90 = lambda v: statistics.quantiles(v, n=10)[8] if len(v) > 1 else v[0]
    lines = ["\nOPMF and AVRF of the fitted model against the recording's:"]
    ok = both("avrf")
    if ok:
        avrf = [abs(r["model"]["avrf"] / r["recording"]["avrf"] - 1.0) for r in ok]
        lines.append(f"  AVRF ({len(ok)} of {len(rows)} trials where both have one): within "
                     f"{100 * AVRF_RELATIVE_TOLERANCE:.0f} % in {sum(a <= AVRF_RELATIVE_TOLERANCE for a in avrf)}/{len(avrf)}; "
                     f"relative difference median {statistics.median(avrf):.4f}, 90th percentile {q90(avrf):.4f}, "
                     f"max {max(avrf):.4f}")
    else:
        lines.append(f"  AVRF: none of {len(rows)} trials has one in both (recording: "
                     f"{sum(r['recording'].get('avrf') is not None for r in rows)}, model: "
                     f"{sum(r['model'].get('avrf') is not None for r in rows)})")
    ok = both("opmf")
    if ok:
        opmf = [abs(r["model"]["opmf"] - r["recording"]["opmf"]) for r in ok]
        lines.append(f"  OPMF ({len(ok)} trials): within {OPMF_TOLERANCE} in {sum(o <= OPMF_TOLERANCE for o in opmf)}/"
                     f"{len(opmf)}; difference median {statistics.median(opmf):.4f}, 90th percentile {q90(opmf):.4f}, "
                     f"max {max(opmf):.4f}; the recording's OPMF median "
                     f"{statistics.median(r['recording']['opmf'] for r in ok):.4f}, the model's "
                     f"{statistics.median(r['model']['opmf'] for r in ok):.4f}")
        fits = {t["index"]: t["fit"] for t in trials or [] if t.get("fit")}
        for r in ok:
            if abs(r["model"]["opmf"] - r["recording"]["opmf"]) <= OPMF_TOLERANCE:
                continue
            line = (f"    OPMF miss, trial {r['index']}: recorded {r['recording']['opmf']:.4f}, model "
                    f"{r['model']['opmf']:.4f}")
            where = [r[k].get("largest_roll") for k in ("recording", "model")]
            if all(where):
                line += (f"; largest |φx| {1e3 * where[0]['abs_phi_x_rad']:.2f} / {1e3 * where[1]['abs_phi_x_rad']:.2f} "
                         f"mrad, {1e3 * where[0]['after_first_impact_s']:.0f} / "
                         f"{1e3 * where[1]['after_first_impact_s']:.0f} ms after the first impact (recording / model)")
            window = fits.get(r["index"], {}).get("window")
            if window:
                line += f"; window {window['reason']}, {window['extensions']} of {window['extensions_tried']} extensions kept"
            lines.append(line)
    return lines


def epsilon_at(args, trial, prefix, parameters, t_end):
    """(28) of the fitted values on the window ending at t_end (`rockfit fit --evaluate`)."""
    cmd = [args.rockfit, "fit", prefix, "--rate", "256", "--b1", repr(B1), "--b2", repr(trial["b2"]), "--h", repr(H),
           "--density", repr(DENSITY), "--evaluate", "--json", "--t-end", repr(t_end)]
    for name, option in (("t0", "--t0"), ("alpha", "--alpha"), ("lambda", "--lambda"), ("lambda_lat", "--lambda-lat"),
                         ("lambda_lon", "--lambda-lon"), ("release_roll", "--release-roll")):
        if name in parameters:
            cmd += [option, repr(parameters[name]["value"])]
    out = subprocess.run(cmd, capture_output=True, text=True)
    return json.loads(out.stdout).get("epsilon") if out.stdout.strip() else None


LATERAL_SPAN_S = 0.1  # the lateral criterion's span after the first impact: the first lateral swing (fitting/README.md)


def lateral_misfit_after_first_impact(recording_prefix, model_prefix):
    """Σ (ω_x² + ω_z²) of the recording minus the model over the LATERAL_SPAN_S after the recording's first impact,
    from the files `rockfit correct` wrote for largest_roll_after_first_impact (same sample times: same rate and
    duration). None when a file is missing."""
    def read(prefix):
        path = prefix + "_corrected.csv"
        if not os.path.exists(path):
            return None
        with open(path) as f:
            return [(float(r["time_s"]), float(r["w_x_rad_s"]), float(r["w_z_rad_s"]), r["impact_y"] == "1")
                    for r in csv.DictReader(f)]
    recording, model = read(recording_prefix), read(model_prefix)
    if recording is None or model is None:
        return None
    impacts = [r[0] for r in recording if r[3]]
    if not impacts:
        return None
    return sum((a[1] - b[1]) ** 2 + (a[2] - b[2]) ** 2 for a, b in zip(recording, model)
               if impacts[0] <= a[0] < impacts[0] + LATERAL_SPAN_S)


def refit_on_longest_window(args, trials, rows, out_dir, criterion):
    """Candidate rules, emulated (fitting/README.md, "OPMF and AVRF on MuJoCo recordings"): fit again with every
    parameter free (the release too) on the last window the extension tried, and keep that fit
      criterion "opmf":    where the fitted model's OPMF misses the recording's, when the refit's is closer — a rule
                           that selects on the OPMF itself (on the trials it changes the check is no prediction);
      criterion "epsilon": on every fit whose window extension was tried, when its (28) on that common window is
                           lower than the kept fit's there;
      criterion "lateral": on the same fits, when its model's out-of-plane rates (ω_x, ω_z of its `synth`
                           recording) miss the recording's less over the LATERAL_SPAN_S after the first impact."""
    by_row = {r["index"]: r for r in rows}
    out = []
    for trial in trials:
        r = by_row.get(trial["index"])
        if r is None or r["recording"].get("opmf") is None or r["model"].get("opmf") is None:
            continue
        window = trial["fit"].get("window") or {}
        if criterion == "opmf":
            if abs(r["model"]["opmf"] - r["recording"]["opmf"]) <= OPMF_TOLERANCE:
                continue
        elif not window.get("extensions_tried"):
            continue
        t_end = (window.get("tried_t_end") or [window.get("t_end")])[-1]
        if t_end is None or t_end <= window.get("first_t_end", 0.0):
            out.append({"index": trial["index"], "refit_model": None, "reason": "no later window"})
            continue
        prefix = os.path.join(out_dir, "recordings", f"trial{trial['index']:03d}")
        fit = subprocess.run([args.rockfit, "fit", prefix, "--rate", "256", "--b1", repr(B1), "--b2", repr(trial["b2"]),
                              "--h", repr(H), "--density", repr(DENSITY), "--threads", "1", "--json", "--t-end",
                              repr(t_end)] + widening_args(args), capture_output=True, text=True)
        if not fit.stdout.strip():
            out.append({"index": trial["index"], "refit_model": None, "reason": fit.stderr.strip()})
            continue
        refit = dict(trial, fit=json.loads(fit.stdout))
        m = metrics_trial(args, refit, out_dir, model_name=f"refit{trial['index']:03d}")
        entry = {"index": trial["index"], "t_end": t_end, "recording": r["recording"], "model": r["model"],
                 "refit_model": m["model"], "t0_error": refit["fit"]["parameters"]["t0"]["value"] - trial["t0"],
                 "alpha_error": refit["fit"]["parameters"]["alpha"]["value"] - trial["alpha"],
                 "refit_epsilon": refit["fit"]["epsilon"],
                 "refit_interval_95": {name: refit["fit"]["parameters"][name]["interval_95"]
                                       for name in ("t0", "alpha", "release_roll")
                                       if name in refit["fit"]["parameters"]},
                 "kept_epsilon": epsilon_at(args, trial, prefix, trial["fit"]["parameters"], t_end)}
        if m["model"].get("opmf") is None:
            entry["keep"] = False
        elif criterion == "opmf":
            entry["keep"] = (abs(m["model"]["opmf"] - r["recording"]["opmf"]) <
                             abs(r["model"]["opmf"] - r["recording"]["opmf"]))
        elif criterion == "lateral":
            recordings = os.path.join(out_dir, "recordings")
            kept = lateral_misfit_after_first_impact(prefix, os.path.join(recordings, f"model{trial['index']:03d}"))
            again = lateral_misfit_after_first_impact(prefix, os.path.join(recordings, f"refit{trial['index']:03d}"))
            entry["kept_lateral"], entry["refit_lateral"] = kept, again
            entry["keep"] = kept is not None and again is not None and again < kept
        else:
            entry["keep"] = entry["kept_epsilon"] is not None and entry["refit_epsilon"] < entry["kept_epsilon"]
        out.append(entry)
    return out


def refit_report(refits, rows, criterion, trials=()):
    lines = [f"\nCandidate rule, emulated: every parameter refitted on the last window the extension tried, kept "
             + {"opmf": "where the model's OPMF missed and the refit's is closer (selects on the OPMF):",
                "epsilon": "where its (28) on that window is lower than the kept fit's:",
                "lateral": f"where its model's ω_x, ω_z miss the recording's less over the {LATERAL_SPAN_S} s after the "
                           "first impact:"}[criterion]]
    model = {r["index"]: r["model"] for r in rows}
    for e in refits:
        if e.get("refit_model") is None:
            lines.append(f"  trial {e['index']}: not refitted ({e.get('reason', '')[:80]})")
            continue
        if e["keep"]:
            model[e["index"]] = e["refit_model"]
        rec = e["recording"]
        lines.append(f"  trial {e['index']}: window to {e['t_end']:.4f} s: ε {e['kept_epsilon']:.5f} → "
                     f"{e['refit_epsilon']:.5f}; model OPMF {e['model']['opmf']:.4f} → "
                     f"{e['refit_model'].get('opmf') or float('nan'):.4f} (recorded {rec['opmf']:.4f}); AVRF "
                     f"{e['model'].get('avrf') or float('nan'):.4f} → {e['refit_model'].get('avrf') or float('nan'):.4f}"
                     f" (recorded {rec.get('avrf') or float('nan'):.4f}); {'kept' if e['keep'] else 'not kept'}; "
                     f"t0 error {1e3 * e['t0_error']:+.1f} ms, α error {1e3 * e['alpha_error']:+.2f} mrad")
    kept = [e for e in refits if e.get("refit_model") is not None and e["keep"] and "refit_interval_95" in e]
    if kept:  # the release's 95 % intervals of the kept refits (all parameters free on the longer window)
        by_index = {t["index"]: t for t in trials}
        for name, truth_key in (("t0", "t0"), ("alpha", "alpha"), ("release_roll", "roll")):
            with_it = [e for e in kept if name in e["refit_interval_95"]]
            before = sum(holds(by_index[e["index"]]["fit"]["parameters"][name]["interval_95"], by_index[e["index"]][truth_key])
                         for e in with_it if name in by_index[e["index"]]["fit"]["parameters"])
            after = sum(holds(e["refit_interval_95"][name], by_index[e["index"]][truth_key]) for e in with_it)
            lines.append(f"  {name}: the 95 % interval holds the truth in {before} → {after} of the {len(with_it)} "
                         "refits kept (the kept fit's → the refit's own)")
    after = [dict(r, model=model[r["index"]]) for r in rows]
    lines += [line.replace("OPMF and AVRF of the fitted model", "With the rule, OPMF and AVRF of the fitted model")
              for line in metrics_report(after) if not line.startswith("    OPMF miss")]
    return lines


def release_tilt_lines(fitted):
    """The check of the fitted α against the tilt at rest (fitting/README.md, "The tilt at rest"): how often it
    compares, z and the warnings, and how far the tilt at rest is from MuJoCo's α in its own σ."""
    checks = [(t, t["fit"]["release_tilt"]) for t in fitted if t["fit"].get("release_tilt")]
    compared = [(t, c) for t, c in checks if c["available"]]
    if not checks:
        return []
    out = [f"\nα against the tilt at rest: compared in {len(compared)} of {len(checks)}"]
    if compared:
        z = [c["z"] for _, c in compared]
        rest_z = [(c["rest_rad"] - t["alpha"]) / c["rest_std_error_rad"] for t, c in compared]
        def rms(v):
            return math.sqrt(sum(x * x for x in v) / len(v))
        out.append(f"  z RMS {rms(z):.2f}, max |z| {max(abs(x) for x in z):.2f}, disagree (|z| > 4) in "
                   f"{sum(not c['consistent'] for _, c in compared)}; the tilt at rest off the truth by {rms(rest_z):.2f} "
                   f"σ_rest RMS (σ_rest {1e3 * min(c['rest_std_error_rad'] for _, c in compared):.2f}–"
                   f"{1e3 * max(c['rest_std_error_rad'] for _, c in compared):.2f} mrad)")
    pushed = [(t, c) for t, c in checks if t.get("push")]
    if pushed:  # which pushes are caught, by size (toward the fall: push > 0)
        out.append(f"  pushed releases: {len(pushed)}; compared in {sum(c['available'] for _, c in pushed)}")
        edges = [0.0, 0.05, 0.1, 0.2, math.inf]
        for lo, hi in zip(edges, edges[1:]):
            for sign, label in ((1, "toward the fall"), (-1, "away from it")):
                group = [(t, c) for t, c in pushed if lo <= sign * t["push"] < hi]
                if not group:
                    continue
                available = [(t, c) for t, c in group if c["available"]]
                caught = sum(not c["consistent"] for _, c in available)
                shift = [1e3 * (c["fitted_rad"] - t["alpha"]) for t, c in available]
                out.append(f"    |push| {lo:g}–{hi:g} rad/s {label}: {len(group)} trials, compared {len(available)}, "
                           f"caught (|z| > 4) {caught}"
                           + (f"; fitted α − true α {min(shift):+.1f} to {max(shift):+.1f} mrad, |z| up to "
                              f"{max(abs(c['z']) for _, c in available):.1f}" if available else ""))
    return out


def report(trials):
    fitted = [t for t in trials if t.get("fit")]
    lines = [f"{len(fitted)} of {len(trials)} trials fitted"]
    choices = [t["fit"]["release_roll_choice"] for t in fitted if "release_roll_choice" in t["fit"]]
    if choices:  # rockfit's choice of the release roll (--release-roll-mode)
        lines.append(f"release roll fitted in {sum(bool(c['fitted']) for c in choices)} of {len(choices)} "
                     f"(mode {choices[0]['mode']})")
    if not fitted:
        return "\n".join(lines)
    def table(subset, label):
        out = [f"\n{label}: {len(subset)} trials"]
        if not subset:
            return out
        for name, truth_key, unit, scale in (("t0", "t0", "ms", 1e3), ("alpha", "alpha", "mrad", 1e3)):
            p = [t["fit"]["parameters"][name] for t in subset]
            truth = [t[truth_key] for t in subset]
            c95 = sum(holds(q["interval_95"], x) for q, x in zip(p, truth))
            c68 = sum(holds(q["interval_68"], x) for q, x in zip(p, truth))
            w95 = statistics.median(width(q["interval_95"]) for q in p) * scale
            err = statistics.median(abs(q["value"] - x) for q, x in zip(p, truth)) * scale
            out.append(f"  {name:6} 95 % holds {c95}/{len(subset)} ({100 * c95 / len(subset):.0f} %), 68 % holds "
                       f"{c68}/{len(subset)}; median 95 % width {w95:.3g} {unit}; median |error| {err:.3g} {unit}")
        rolled = [t for t in subset if "release_roll" in t["fit"]["parameters"]]
        if rolled:  # fitted with the release roll: the roll MuJoCo was given is its truth
            p = [t["fit"]["parameters"]["release_roll"] for t in rolled]
            c95 = sum(holds(q["interval_95"], t["roll"]) for q, t in zip(p, rolled))
            err = statistics.median(abs(q["value"] - t["roll"]) for q, t in zip(p, rolled)) * 1e3
            w95 = statistics.median(width(q["interval_95"]) for q in p) * 1e3
            out.append(f"  roll   95 % holds {c95}/{len(rolled)} ({100 * c95 / len(rolled):.0f} %); median 95 % width "
                       f"{w95:.3g} mrad; median |error| {err:.3g} mrad")
        ratios = [t["fit"]["model_error"]["ratio"] for t in subset if t["fit"]["model_error"]["available"]]
        flagged = sum(bool(t["fit"]["model_error"]["dominates"]) for t in subset)
        if ratios:
            q = statistics.quantiles(ratios, n=4) if len(ratios) > 1 else [ratios[0]] * 3
            out.append(f"  ε / noise floor: median {statistics.median(ratios):.2f} (quartiles {q[0]:.2f}–{q[2]:.2f}, "
                       f"max {max(ratios):.1f}); model error flagged dominant in {flagged}/{len(subset)}; "
                       f"ε > 2 × floor in {sum(r > 2 for r in ratios)}")
        return out
    lines += table(fitted, "all")
    lines += table([t for t in fitted if not t["fit"]["model_error"]["dominates"]], "not flagged")
    lines += table([t for t in fitted if t["fit"]["model_error"]["dominates"]], "flagged (model error dominates)")
    lines += release_tilt_lines(fitted)
    misses = [t for t in fitted if not (holds(t["fit"]["parameters"]["t0"]["interval_95"], t["t0"]) and
                                        holds(t["fit"]["parameters"]["alpha"]["interval_95"], t["alpha"]))]
    lines.append(f"\nmisses of t0 or α at 95 % ({len(misses)}):")
    for t in misses:
        p = t["fit"]["parameters"]
        lines.append(f"  trial {t['index']}: roll {t['roll']:.4f}, α/θc {t['alpha'] / t['theta_c']:.2f}, b2 {t['b2']:.3f}: "
                     f"t0 {1e3 * (p['t0']['value'] - t['t0']):+.1f} ms, α {1e3 * (p['alpha']['value'] - t['alpha']):+.2f} "
                     f"mrad, ε/floor {t['fit']['model_error']['ratio']:.1f}, flagged {t['fit']['model_error']['dominates']}")
    return "\n".join(lines)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--rockfit", default="build/tools/rockfit")
    parser.add_argument("--generator", default="build/tests/rockfit_mujoco_synth")
    parser.add_argument("--family", default="mujoco", choices=["mujoco", "mujoco-perturbed", "mujoco-planar", "mujoco-lively"])
    parser.add_argument("--trials", type=int, default=30)
    parser.add_argument("--model-error-widening", type=float, default=None,
                        help="rockfit fit --model-error-widening C (default: rockfit's; 0: off)")
    parser.add_argument("--t0-floor-samples", type=float, default=None,
                        help="rockfit fit --t0-floor-samples Q (default: rockfit's; 0: off)")
    parser.add_argument("--estimate-gyro-scale", default=None, choices=["off", "common", "per-axis"],
                        help="rockfit fit --estimate-gyro-scale MODE (default: not given, rockfit's off); the widening "
                             "options above share coverage_study's helper, which reads it")
    parser.add_argument("--fit-release-roll", action="store_true",
                        help="rockfit fit --fit-release-roll: estimate the release roll (and synthesise the fitted "
                             "model's metrics with it)")
    parser.add_argument("--release-roll-mode", default=None, choices=["off", "auto", "on"],
                        help="rockfit fit --release-roll-mode MODE (default: not given, rockfit's auto: the roll fitted "
                             "when the fall shows one); off gives the fits of the program before the choice")
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--duration", type=float, default=3.0,
                        help="length of each recording [s] (default 3: the block still rocks at the end, so the "
                             "mounting's turn about y and the tilt at rest are not fixed and α is not compared with "
                             "it; 6 lets it come to rest)")
    parser.add_argument("--push", type=float, default=0.0,
                        help="push at each release: the box's rate about body y drawn uniformly from [−W, W] rad/s "
                             "(> 0 towards the fall; default 0: released from rest)")
    parser.add_argument("--solref-time-constant", type=float, default=None,
                        help="MuJoCo's contact time constant [s] (default: the generator's 0.001)")
    parser.add_argument("--first", type=int, default=0,
                        help="run only trials FIRST..TRIALS-1 of the seed (the earlier ones are drawn, not run): "
                             "a study split over several processes or continued later")
    parser.add_argument("--out", required=True)
    parser.add_argument("--report-only", action="store_true")
    parser.add_argument("--metrics", action="store_true",
                        help="also compare the OPMF and AVRF of the fitted model with the recording's (OUT/metrics.jsonl)")
    parser.add_argument("--refit-rule", default=None, choices=["opmf", "epsilon", "lateral"],
                        help="with --metrics: emulate a candidate rule — every parameter fitted again on the last "
                             "window the extension tried, kept where the model's OPMF missed and the refit's is closer "
                             "(opmf: selects on the OPMF itself), where its (28) on that window is lower (epsilon), or "
                             "where its ω_x, ω_z miss the recording's less just after the first impact (lateral); "
                             "OUT/refit_RULE.jsonl")
    args = parser.parse_args()
    path = os.path.join(args.out, "trials.jsonl")
    if not args.report_only:
        os.makedirs(os.path.join(args.out, "recordings"), exist_ok=True)
        rng = random.Random(args.seed)
        push_rng = random.Random(args.seed + 1000003)  # its own stream: the trials stay those of the seed
        with open(path, "w") as f:
            for i in range(args.trials):
                trial = random_trial(rng, i, args.family)
                if args.push:
                    trial["push"] = push_rng.uniform(-args.push, args.push)
                if i < args.first:
                    continue
                trial = run_trial(args, trial, args.out)
                f.write(json.dumps(trial) + "\n")
                f.flush()
                print(f"[{i + 1}/{args.trials}]", file=sys.stderr)
    trials = [json.loads(line) for line in open(path)]
    text = (f"family {args.family}, seed {args.seed}, push ±{args.push} rad/s, duration {args.duration} s, widening "
            f"{args.model_error_widening}, t0 floor {args.t0_floor_samples} (None: rockfit's defaults), release roll fitted: "
            f"{'on' if args.fit_release_roll else args.release_roll_mode or 'auto (rockfit default)'}\n"
            + report(trials))
    if args.metrics:
        metrics_path = os.path.join(args.out, "metrics.jsonl")
        if not os.path.exists(metrics_path):
            with open(metrics_path, "w") as f:
                for t in trials:
                    if t.get("fit"):
                        f.write(json.dumps(metrics_trial(args, t, args.out)) + "\n")
                        f.flush()
        rows = [json.loads(line) for line in open(metrics_path)]
        text += "\n".join(metrics_report(rows, trials))
        if args.refit_rule:
            refit_path = os.path.join(args.out, f"refit_{args.refit_rule}.jsonl")
            if not os.path.exists(refit_path):
                with open(refit_path, "w") as f:
                    for e in refit_on_longest_window(args, trials, rows, args.out, args.refit_rule):
                        f.write(json.dumps(e) + "\n")
            text += "\n" + "\n".join(refit_report([json.loads(line) for line in open(refit_path)], rows,
                                                   args.refit_rule, trials))
    open(os.path.join(args.out, "report.md"), "w").write(text + "\n")
    print(text)


if __name__ == "__main__":
    main()
