#!/usr/bin/env python3
"""Calibration of the intervals under model error (fitting/README.md, "Intervals under model error").

Reads the trials.jsonl of studies made by tools/coverage_study.py and tools/other_physics_study.py with the
widening off (`--model-error-widening 0 --t0-floor-samples 0`), widens every 95 % interval as `rockfit fit`
does (fitting/include/rockfit/fitting/model_error_widening.hpp):

    h' = √((f·h)² + floor²),  f = √(1 + c²·max(0, r² − 1)),  r = ε / ε_noise,  floor = q / rate for t0 only,

clipped to the parameter's bounds, and reports per study how often the 95 % intervals hold the truth (over
every fit, and over the fits where the parameter is `determined` yes after the widening) with the median
widths. The fitted values do not depend on c and q, so one run of each study serves every (c, q).

  tools/widening_calibration.py --c 0.5 --q 0.5 build/study/*/trials.jsonl
  tools/widening_calibration.py --grid build/study/sensor-reference-26/trials.jsonl ...   # the smallest c, q
  tools/widening_calibration.py --compare --c 0.75 --q 0.5 build/study/*/trials.jsonl     # off → (c, q)

`--grid` prints, for each q of a grid, the smallest c (step 0.05) with which the 95 % intervals of t0 and α,
and of the λ's where the study has their truth, hold the truth in at least --target of the fits of every study
given (the calibration: give it the tuning families only).
"""
import argparse
import json
import math
import os
import statistics
import sys

RATE_HZ = 256.0  # the studies' sample rate
PARAMETERS = ["t0", "alpha", "lambda", "lambda_lat", "lambda_lon", "release_roll"]
UNDETERMINED_RANGE_FRACTION = 0.5  # IntervalOptions::undetermined_range_fraction


def load(path):
    """(fit, truth) pairs of one study; truth has t0 and α, the λ's for coverage_study.py's trials and the
    release roll for other_physics_study.py's trials fitted with the roll."""
    pairs = []
    with open(path) as f:
        for line in f:
            row = json.loads(line)
            if not row.get("fit"):
                continue
            truth = row["trial"] if isinstance(row.get("trial"), dict) and "t0" in row["trial"] else row
            if "roll" in truth and "release_roll" in row["fit"]["parameters"]:
                # other_physics_study.py --fit-release-roll: the roll MuJoCo was given is the fitted roll's truth
                truth = dict(truth, release_roll=truth["roll"])
            pairs.append((row["fit"], truth))
    return pairs


def factor(ratio, c):
    if ratio is None or not math.isfinite(ratio) or ratio <= 1.0 or c <= 0.0:
        return 1.0
    return math.sqrt(1.0 + c * c * (ratio * ratio - 1.0))


def widened(p, ratio, c, q, name):
    lo, hi = p["interval_95"]
    v = p["value"]
    f = factor(ratio, c)
    floor = q / RATE_HZ if name == "t0" else 0.0
    side = lambda h: math.hypot(f * h, floor)
    return (None if lo is None else max(p["lower"], v - side(v - lo)),
            None if hi is None else min(p["upper"], v + side(hi - v)))


def holds(interval, x):
    return (interval[0] is None or interval[0] <= x) and (interval[1] is None or x <= interval[1])


def determined_yes(p, interval):
    if p.get("determined") != "yes" or interval[0] is None or interval[1] is None:
        return False
    return interval[1] - interval[0] <= UNDETERMINED_RANGE_FRACTION * (p["upper"] - p["lower"])


def coverage(pairs, c, q, names):
    """name → (held, fits, held among determined yes, determined yes, median width)."""
    out = {}
    for name in names:
        held = total = held_yes = yes = 0
        widths = []
        for fit, truth in pairs:
            if name not in fit["parameters"] or name not in truth:  # the roll: reported only where it was fitted
                continue
            p = fit["parameters"][name]
            if p.get("fixed") or p.get("interval_95") is None:
                continue
            m = fit.get("model_error", {})
            i = widened(p, m.get("ratio") if m.get("available") else None, c, q, name)
            total += 1
            held += holds(i, truth[name])
            if determined_yes(p, i):
                yes += 1
                held_yes += holds(i, truth[name])
            if i[0] is not None and i[1] is not None:
                widths.append(i[1] - i[0])
        out[name] = (held, total, held_yes, yes, statistics.median(widths) if widths else float("nan"))
    return out


def label(path):
    return os.path.basename(os.path.dirname(os.path.abspath(path)))


def names_of(pairs):
    return [n for n in PARAMETERS if any(n in truth for _, truth in pairs)]


def table(paths, c, q):
    lines = [f"c = {c:g}, t0 floor q = {q:g} samples",
             "| study | fits | " + " | ".join(PARAMETERS) + " | median 95 % widths t0 / α / λ / λ_lat / λ_lon / roll |",
             "|---|---|" + "---|" * len(PARAMETERS) + "---|"]
    for path in paths:
        pairs = load(path)
        cov = coverage(pairs, c, q, names_of(pairs))
        cells, widths = [], []
        for name in PARAMETERS:
            if name not in cov:
                cells.append("—")
                widths.append("—")
                continue
            held, total, held_yes, yes, w = cov[name]
            cells.append(f"{100 * held / total:.0f} % ({100 * held_yes / yes:.0f} % of {yes})" if yes else
                         f"{100 * held / total:.0f} %")
            widths.append(f"{w * 1e3:.3g} ms" if name == "t0" else f"{w * 1e3:.3g} mrad" if name in ("alpha", "release_roll") else f"{w:.2g}")
        lines.append(f"| {label(path)} | {len(pairs)} | " + " | ".join(cells) + " | " + " / ".join(widths) + " |")
    return "\n".join(lines)


def compare(paths, c, q):
    """One row per study: coverage over every fit and median width, widening off → (c, q)."""
    lines = [f"widening off → c = {c:g}, q = {q:g}",
             "| study | fits | " + " | ".join(PARAMETERS) + " | median 95 % widths t0 / α / λ / λ_lat / λ_lon / roll |",
             "|---|---|" + "---|" * len(PARAMETERS) + "---|"]
    fmt_w = lambda name, w: (f"{w * 1e3:.3g} ms" if name == "t0" else f"{w * 1e3:.3g} mrad" if name in ("alpha", "release_roll")
                             else f"{w:.2g}")
    for path in paths:
        pairs = load(path)
        names = names_of(pairs)
        before, after = coverage(pairs, 0.0, 0.0, names), coverage(pairs, c, q, names)
        cells, widths = [], []
        for name in PARAMETERS:
            if name not in names:
                cells.append("—")
                continue
            (h0, n0, _, _, w0), (h1, n1, _, _, w1) = before[name], after[name]
            cells.append(f"{100 * h0 / n0:.0f} → {100 * h1 / n1:.0f} %")
            widths.append(f"{fmt_w(name, w0)} → {fmt_w(name, w1)}")
        lines.append(f"| {label(path)} | {len(pairs)} | " + " | ".join(cells) + " | " + "; ".join(widths) + " |")
    return "\n".join(lines)


def smallest_c(paths, q, target):
    studies = [load(p) for p in paths]
    for k in range(0, 101):
        c = 0.05 * k
        if all(held >= target * total
               for pairs in studies
               for name, (held, total, _, _, _) in coverage(pairs, c, q, names_of(pairs)).items() if total):
            return c
    return None


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("studies", nargs="+", help="trials.jsonl files")
    parser.add_argument("--c", type=float, default=0.0, help="the model-error coefficient c")
    parser.add_argument("--q", type=float, default=0.0, help="t0's floor in sample periods")
    parser.add_argument("--grid", action="store_true", help="the smallest c for each q of 0, 0.25, …, 1.5")
    parser.add_argument("--target", type=float, default=0.9)
    parser.add_argument("--compare", action="store_true", help="coverage and widths with the widening off → (c, q)")
    args = parser.parse_args()
    if args.grid:
        for i in range(7):
            q = 0.25 * i
            c = smallest_c(args.studies, q, args.target)
            print(f"q = {q:g}: smallest c = {'none ≤ 5' if c is None else f'{c:.2f}'}")
        return 0
    print(compare(args.studies, args.c, args.q) if args.compare else table(args.studies, args.c, args.q))
    return 0


if __name__ == "__main__":
    sys.exit(main())
