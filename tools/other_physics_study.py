#!/usr/bin/env python3
"""Fits of recordings made by other physics: coverage of t0 and α (fitting/README.md, "Recordings made by other
physics").

Makes random recordings with `rockfit_mujoco_synth` (tests/support/mujoco_synth_main.cpp: a granite box released
tilted from rest on a plane, simulated by MuJoCo with a stiff soft contact, measured by rockfit's x-IMU model with
synth's defaults), fits each with `rockfit fit --json --threads 1` (the default `thorough` intervals) and reports
per family:

  * how often the 95 % (and 68 %) interval of t0 and of α holds the truth, and their median widths;
  * ε over the noise floor at rest (the model-error statement) and how often model error is flagged dominant;
  * the same coverage among the fits that are not flagged.

Families (one seed gives the same trials):
  mujoco            roll at release 0–0.01 rad about x (the block stands on one corner of its release edge)
  mujoco-perturbed  the same, plus the centre of mass off the axis by 1–2 % of b2 (either side) and one base
                    corner (random) 0.1 mm proud
  mujoco-planar     no roll, no perturbation (the motion stays in the plane; MuJoCo's contact alone)

Random ranges: b1 = 0.05000453 m, h = 0.2 m, b2 = 2.5–6 cm, α = 0.5–0.95 θ_c, t0 = 0.8–1.6 s, recording 3 s.

Usage (from the repository root, after building the targets rockfit and rockfit_mujoco_synth):

  nice tools/other_physics_study.py --rockfit build/tools/rockfit --generator build/tests/rockfit_mujoco_synth \\
      --family mujoco --trials 30 --seed 1 --out build/other-physics-mujoco-1

Writes OUT/trials.jsonl and prints the table (also OUT/report.md); `--report-only` re-prints it.
"""
import argparse
import json
import math
import os
import random
import statistics
import subprocess
import sys

B1, H, DENSITY = 0.05000453, 0.2, 2692.0


def random_trial(rng, index, family):
    b2 = rng.uniform(0.025, 0.06)
    theta_c = math.atan(B1 / H)
    trial = {"index": index, "family": family, "b2": b2, "theta_c": theta_c,
             "alpha": rng.uniform(0.5, 0.95) * theta_c, "t0": round(rng.uniform(0.8, 1.6) * 10240) / 10240,
             "roll": 0.0 if family == "mujoco-planar" else rng.uniform(0.0, 0.01),
             "com_offset_y": 0.0, "proud_vertex": 0, "seed": 1000 + index}
    if family == "mujoco-perturbed":
        trial["com_offset_y"] = rng.uniform(0.01, 0.02) * rng.choice([-1.0, 1.0])
        trial["proud_vertex"] = rng.randint(1, 4)
    return trial


def run_trial(args, trial, out_dir):
    prefix = os.path.join(out_dir, "recordings", f"trial{trial['index']:03d}")
    subprocess.run([args.generator, "-o", prefix, "--alpha", repr(trial["alpha"]), "--roll", repr(trial["roll"]),
                    "--t0", repr(trial["t0"]), "--duration", "3", "--b2", repr(trial["b2"]),
                    "--com-offset-y", repr(trial["com_offset_y"]), "--proud-vertex", str(trial["proud_vertex"]),
                    "--seed", str(trial["seed"])], check=True, capture_output=True)
    fit = subprocess.run([args.rockfit, "fit", prefix, "--rate", "256", "--b1", repr(B1), "--b2", repr(trial["b2"]),
                          "--h", repr(H), "--density", repr(DENSITY), "--threads", "1", "--json",
                          "--model-error-widening", repr(args.model_error_widening)],
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


def report(trials):
    fitted = [t for t in trials if t.get("fit")]
    lines = [f"{len(fitted)} of {len(trials)} trials fitted"]
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
    parser.add_argument("--family", default="mujoco", choices=["mujoco", "mujoco-perturbed", "mujoco-planar"])
    parser.add_argument("--trials", type=int, default=30)
    parser.add_argument("--model-error-widening", type=float, default=0.0,
                        help="rockfit fit --model-error-widening K (0: off, the default)")
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--out", required=True)
    parser.add_argument("--report-only", action="store_true")
    args = parser.parse_args()
    path = os.path.join(args.out, "trials.jsonl")
    if not args.report_only:
        os.makedirs(os.path.join(args.out, "recordings"), exist_ok=True)
        rng = random.Random(args.seed)
        with open(path, "w") as f:
            for i in range(args.trials):
                trial = run_trial(args, random_trial(rng, i, args.family), args.out)
                f.write(json.dumps(trial) + "\n")
                f.flush()
                print(f"[{i + 1}/{args.trials}]", file=sys.stderr)
    trials = [json.loads(line) for line in open(path)]
    text = f"family {args.family}, seed {args.seed}, model-error widening {args.model_error_widening:g}\n" + report(trials)
    open(os.path.join(args.out, "report.md"), "w").write(text + "\n")
    print(text)


if __name__ == "__main__":
    main()
