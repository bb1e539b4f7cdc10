#!/usr/bin/env python3
"""Fit the trials of one block and position of the sample campaign, then draw that block's overturning fragility
curve under the campaign's ground motions, with the impact parameters drawn from what the fits say.

    PYTHONPATH=build/python /usr/bin/python3 python/examples/fragility_curve.py [-o fragility.png]

The parameter distribution is the plain mean and sample standard deviation of the fitted values over the trials
(`rockfit fragility --fits` uses the pooled estimates of `rockfit batch` instead, fitting/quake/README.md).
"""
import argparse
import math
import pathlib
import statistics

import matplotlib

matplotlib.use("Agg")  # write a file; no display needed
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import rockfit  # noqa: E402

SAMPLES = pathlib.Path(__file__).resolve().parent.parent.parent / "data-samples"
MANIFEST = SAMPLES / "manifest.toml"
RECORDS = sorted((SAMPLES / "ground-motions").glob("*.AT2"))


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--block", default="block2", help="block id of data-samples/manifest.toml")
    parser.add_argument("--position", default="A", help="position of the trials to fit")
    parser.add_argument("--samples", type=int, default=40, help="samples per intensity level")
    parser.add_argument("-o", "--output", default="fragility.png", help="picture to write (.png, .svg, .pdf)")
    args = parser.parse_args()

    prefix = f"{args.block}-{args.position}-"
    trials = [line.split('"')[1] for line in MANIFEST.read_text().splitlines()
              if line.startswith("id = ") and line.split('"')[1].startswith(prefix)]
    fits = [f for f in rockfit.fit_campaign(str(MANIFEST), trials=trials) if hasattr(f, "values")]
    print(f"fitted {len(fits)} trials of {args.block}/{args.position}")
    spread = {}
    for name in ("lambda", "lambda_lat", "lambda_lon"):
        values = [f.values[name] for f in fits]
        spread[name] = (statistics.fmean(values), statistics.stdev(values) if len(values) > 1 else 0.0)
        print(f"{name:<11} mean {spread[name][0]:+.4f}  sd {spread[name][1]:.4f}")

    block = rockfit.Block.from_manifest(str(MANIFEST), args.block)
    levels = np.linspace(0.1, 1.0, 10)
    study = rockfit.fragility(block, records=RECORDS, pga=list(levels), samples=args.samples, seed=1,
                              lambda_=spread["lambda"][0], lambda_sd=spread["lambda"][1],
                              lambda_lat=spread["lambda_lat"][0], lambda_lat_sd=spread["lambda_lat"][1],
                              lambda_lon=spread["lambda_lon"][0], lambda_lon_sd=spread["lambda_lon"][1])
    curve = study.blocks[0]
    counts = [level["overturning"] for level in curve["levels"]]
    p = np.array([c["probability"] for c in counts])
    low = np.array([c["wilson_95"][0] for c in counts])
    high = np.array([c["wilson_95"][1] for c in counts])
    print(f"{study.samples} responses; P(overturn) by PGA: " +
          ", ".join(f"{x:.1f} g: {y:.2f}" for x, y in zip(levels, p)))

    figure, axes = plt.subplots(figsize=(6, 4))
    axes.fill_between(levels, low, high, alpha=0.25, label="95 % Wilson interval")
    axes.plot(levels, p, "o-", label="overturned fraction")
    lognormal = curve["curves"]["overturning"]
    if lognormal["status"] == "ok":
        x = np.linspace(levels[0], levels[-1], 200)
        y = [0.5 * (1 + math.erf(math.log(v / lognormal["median"]) / (lognormal["beta"] * math.sqrt(2)))) for v in x]
        axes.plot(x, y, "--", label=f"lognormal, median {lognormal['median']:.2f} g, β {lognormal['beta']:.2f}")
    axes.set_xlabel("peak ground acceleration [g]")
    axes.set_ylabel("probability of overturning [–]")
    axes.set_ylim(-0.02, 1.02)
    axes.set_title(f"{args.block}/{args.position}: fitted impact parameters, {len(RECORDS)} records")
    axes.legend(loc="upper left")
    figure.tight_layout()
    figure.savefig(args.output)
    print(f"written {args.output}")


if __name__ == "__main__":
    main()
