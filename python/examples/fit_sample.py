#!/usr/bin/env python3
"""Fit one trial of the sample campaign and plot measured against simulated angular velocity (the paper's Fig. 14).

    PYTHONPATH=build/python python3 python/examples/fit_sample.py [TRIAL] [-o fit_sample.png]
"""
import argparse
import pathlib

import matplotlib

matplotlib.use("Agg")  # write a file; no display needed
import matplotlib.pyplot as plt  # noqa: E402

import rockfit  # noqa: E402

HERE = pathlib.Path(__file__).resolve().parent
MANIFEST = HERE.parent.parent / "data-samples" / "manifest.toml"


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("trial", nargs="?", default="block2-A-1", help="trial id of data-samples/manifest.toml")
    parser.add_argument("-o", "--output", default="fit_sample.png", help="picture to write (.png, .svg, .pdf)")
    args = parser.parse_args()

    recording = rockfit.load_recording(str(MANIFEST), trial=args.trial)  # carries its block from the manifest
    result = rockfit.fit(recording)
    for name, p in result.parameters.items():
        error = "—" if p.std_error is None else f"{p.std_error:.2g}"
        print(f"{name:<11} {p.value:>10.5g} ± {error:<8} {p.unit}{'  (fixed)' if p.fixed else ''}")
    print(f"ε (28) = {result.epsilon:.4g} rad/s over [{result.t[0]:.3f}, {result.t_end:.3f}] s, "
          f"{result.simulations} simulations in {result.wall_s:.2f} s")

    fig, ax = plt.subplots(figsize=(8, 4.5))
    for axis, colour in zip(range(3), ("tab:red", "tab:blue", "tab:green")):
        label = "xyz"[axis]
        ax.plot(result.t, result.w_B_measured[:, axis], ".", ms=3, color=colour, label=f"ω_{label} measured")
        ax.plot(result.t, result.w_B_simulated[:, axis], "-", lw=1, color=colour, label=f"ω_{label} simulated")
    for t in result.impact_times:
        ax.axvline(t, color="0.85", lw=0.5, zorder=0)
    ax.set_xlabel("time [s]")
    ax.set_ylabel("angular velocity in B [rad/s]")
    ax.set_title(f"{result.trial}: ε = {result.epsilon:.4f} rad/s")
    ax.legend(ncol=3, fontsize=8)
    fig.tight_layout()
    fig.savefig(args.output, dpi=120)
    print(f"written {args.output}")


if __name__ == "__main__":
    main()
