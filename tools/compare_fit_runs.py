#!/usr/bin/env python3
"""Compares two programs' fits of the same trials: ε trial by trial, and the coverage of the intervals.

For a change that must keep the fits (a faster search, say): run the reference program and the changed one on the
same trials and give both outputs here. Each input is either a coverage study's output directory (its
trials.jsonl; `tools/coverage_study.py`, same --seed and --trials for both) or a `rockfit batch --json` document
(the same manifest for both). Prints every trial whose ε rose by more than --max-rise (relative), the largest
rise (noting where a study's two fits end their windows at different times, whose ε are then means over
different windows), and for a coverage study the share of the determined values whose 68 % and 95 % intervals
hold the truth and the share of fits with ε ≤ 1.02 × ε(truth), for both; for two batch documents whose HDF5 files (their
"output") are still there, the largest change of each fitted value over the trials (read with h5py; it does not
change the exit status). Exit status 1 when a trial's ε rose by more than
--max-rise, a fit of the reference is missing from the other, or a coverage share of the other is lower.

Usage (from the repository root):

  nice tools/coverage_study.py --rockfit OLD/rockfit --synth-rockfit build/tools/rockfit --trials 100 --seed 1 \\
      --methods thorough --out build/study/old-1   # both fit the recordings of one `synth`
  nice tools/coverage_study.py --rockfit build/tools/rockfit --trials 100 --seed 1 --methods thorough --out build/study/new-1
  tools/compare_fit_runs.py build/study/old-1 build/study/new-1
  OLD/rockfit batch data-samples/manifest.toml -o /tmp/old.h5 --json > /tmp/old.json   # likewise new.json
  tools/compare_fit_runs.py /tmp/old.json /tmp/new.json
"""
import argparse
import json
import os
import sys

PARAMETERS = ["t0", "alpha", "lambda", "lambda_lat", "lambda_lon"]
EPSILON_RATIO_TARGET = 1.02  # as tools/coverage_study.py counts ε of the fit against ε of the truth


def load(path):
    """{key: row} with row = {"epsilon", and for a study: "fit", "trial", "epsilon_truth"}; and the kind."""
    if os.path.isdir(path):
        rows = {}
        with open(os.path.join(path, "trials.jsonl")) as f:
            for line in f:
                r = json.loads(line)
                if "fit" in r:
                    rows[(r["trial"]["index"], r["method"])] = {"epsilon": r["fit"]["epsilon"], **r}
        return rows, "study"
    with open(path) as f:
        doc = json.load(f)
    return {t["trial"]: {"epsilon": t["epsilon"]} for t in doc["trials"] if t.get("epsilon") is not None}, "batch"


def fitted_values(batch_json):
    """{trial: {parameter: (value, unit)}} of the free parameters in the HDF5 file a `rockfit batch --json` document
    names as its output; None when the file or h5py is missing."""
    with open(batch_json) as f:
        output = json.load(f).get("output")
    try:
        import h5py
    except ImportError:
        return None
    if not output or not os.path.exists(output):
        return None
    text = lambda x: x.decode() if isinstance(x, bytes) else str(x)
    values = {}
    with h5py.File(output, "r") as h5:
        for trial, group in h5.get("fits", {}).items():
            p = group["parameters"]
            values[trial] = {text(n): (float(v), text(u)) for n, v, u, fixed in
                             zip(p["name"][:], p["value"][:], p["unit"][:], p["fixed"][:]) if not fixed}
    return values


def largest_value_changes(ref, other):
    """[(parameter, largest |Δ|, its trial, unit)] over the trials and free parameters both fitted."""
    largest = {}
    for trial in sorted(set(ref) & set(other)):
        for name, (value, unit) in ref[trial].items():
            if name in other[trial]:
                delta = abs(other[trial][name][0] - value)
                if name not in largest or delta > largest[name][0]:
                    largest[name] = (delta, trial, unit)
    return [(name, *largest[name]) for name in largest]


def window_note(ref_row, other_row):
    """For study rows whose fits end their windows at different times (the window extension of one program, say):
    a note that the two ε are means over different windows, so the rise is no comparison; else ""."""
    ends = [r.get("fit", {}).get("t_end") for r in (ref_row, other_row)]
    if None in ends or ends[0] == ends[1]:
        return ""
    return f" — the windows differ (t_end {ends[0]:.6g} → {ends[1]:.6g} s): compare them over one window"


def contains(interval, value):
    lo, hi = interval
    return (lo is None or lo <= value) and (hi is None or value <= hi)


def coverage(rows):
    """(held 68, held 95, determined values, fits with ε ≤ 1.02 ε(truth), fits with ε of the truth)."""
    h68 = h95 = n = ok = n_eps = 0
    for r in rows.values():
        for name in PARAMETERS:
            p = r["fit"]["parameters"][name]
            if p.get("determined") == "yes":
                n += 1
                h68 += contains(p["interval_68"], r["trial"][name])
                h95 += contains(p["interval_95"], r["trial"][name])
        if r.get("epsilon_truth"):
            n_eps += 1
            ok += r["epsilon"] <= EPSILON_RATIO_TARGET * r["epsilon_truth"]
    return h68, h95, n, ok, n_eps


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("reference", help="the reference program's study directory or batch JSON")
    ap.add_argument("other", help="the changed program's, of the same trials")
    ap.add_argument("--max-rise", type=float, default=1e-3, help="largest allowed relative rise of ε (default 0.001)")
    args = ap.parse_args()
    ref, kind = load(args.reference)
    other, other_kind = load(args.other)
    if kind != other_kind:
        sys.exit("compare_fit_runs: give two study directories or two batch JSON documents")
    bad = False
    missing = [k for k in ref if k not in other]
    for k in missing:
        print(f"missing in the other: {k}")
    bad |= bool(missing)
    rises = []
    for k in ref:
        if k in other:
            rise = other[k]["epsilon"] / ref[k]["epsilon"] - 1.0
            rises.append((rise, k))
            if rise > args.max_rise:
                print(f"ε rose: {k}: {ref[k]['epsilon']:.7g} → {other[k]['epsilon']:.7g} rad/s ({100 * rise:+.3f} %)"
                      + window_note(ref[k], other[k]))
                bad = True
    rises.sort()
    if rises:
        same = sum(r == 0.0 for r, _ in rises)
        print(f"{len(rises)} trials: ε the same in {same}, largest rise {100 * rises[-1][0]:+.4f} % ({rises[-1][1]}), "
              f"largest fall {100 * rises[0][0]:+.4f} % ({rises[0][1]})")
    if kind == "batch":
        ref_values, other_values = fitted_values(args.reference), fitted_values(args.other)
        if ref_values is not None and other_values is not None:
            changes = largest_value_changes(ref_values, other_values)
            print("largest |Δ| of the fitted values: " + ", ".join(
                f"{name} {delta:.3g} {unit} ({trial})" for name, delta, trial, unit in changes))
    if kind == "study":
        common = [k for k in ref if k in other]  # the shares over the trials both fitted
        c_ref = coverage({k: ref[k] for k in common})
        c_other = coverage({k: other[k] for k in common})
        for label, c in (("reference", c_ref), ("other", c_other)):
            h68, h95, n, ok, n_eps = c
            print(f"{label:9s}: 68 % holds {h68}/{n}, 95 % holds {h95}/{n}, ε ≤ {EPSILON_RATIO_TARGET} × ε(truth) in "
                  f"{ok}/{n_eps}")
        share = lambda k, n: k / n if n else 1.0
        if (share(c_other[0], c_other[2]) < share(c_ref[0], c_ref[2]) or
                share(c_other[1], c_other[2]) < share(c_ref[1], c_ref[2]) or
                share(c_other[3], c_other[4]) < share(c_ref[3], c_ref[4])):
            print("a coverage share of the other is lower")
            bad = True
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
