#!/usr/bin/env python3
"""Minimum overturning acceleration of a rocking block under a one-sine acceleration pulse, with `rockfit respond`.

For each ω_p/p the pulse a_x(t) = a_p sin(ω_p t), 0 ≤ t ≤ 2π/ω_p (400 samples a period), acts along the block's x
axis; λ = λ_lon = 1 and λ_lat = 0 make the facet impact Housner's rule (3), r = 1 − 1.5 sin²θ_c for a square base.
The amplitude a_p/(g tan θ_c) is raised in steps of --step from 1 until the block first overturns, and that
crossing is then bisected to --tol: the first (smallest) amplitude that overturns, not merely a boundary, up to
windows of safety narrower than the step. p = √(3g/(4R)), R the half-diagonal of the block's section.

  tools/overturning_spectrum.py --rockfit build/tools/rockfit --alpha 0.25 --ratios 1,2,3,4,6 --overturn side

Prints one line per ω_p/p: the amplitude and whether the block landed (a facet impact) before it overturned.
The pulse starts at zero; a block at rest moves with the table until a_x reaches g tan θ_c, so this is the same
motion as a pulse sin(ω_p t + ψ) that starts at the uplift (ψ = asin(g tan θ_c / a_p)).
"""
import argparse
import json
import math
import os
import subprocess
import sys
import tempfile

G = 9.81  # the simulation's gravity (rockfit's default); the record is written in m/s²


def write_pulse(path, omega_p, samples_per_period=400):
    period = 2.0 * math.pi / omega_p
    dt = period / samples_per_period
    with open(path, "w") as f:
        f.write("time_s,a_x\n")
        for k in range(samples_per_period + 1):
            t = k * dt
            f.write(f"{t:.17g},{math.sin(omega_p * t):.17g}\n")
    return period


def run(rockfit, block_args, record, amplitude_m_s2, tail_s, overturn):
    args = [rockfit, "respond", *block_args, "--lambda", "1", "--lambda-lat", "0", "--lambda-lon", "1",
            "--record", record, "--units", "m/s2", "--scale", f"{amplitude_m_s2:.17g}", "--tail", f"{tail_s:.17g}",
            "--rate", "10", "--overturn", overturn, "--json"]
    out = subprocess.run(args, capture_output=True, text=True)
    if out.returncode != 0:
        sys.exit(f"overturning_spectrum.py: {' '.join(args)} failed with {out.returncode}: {out.stderr.strip()}")
    j = json.loads(out.stdout)
    landed = any(i["kind"] == "facet" for i in j["impacts"])
    return j["summary"]["overturned"], landed


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--rockfit", default=os.path.join(os.path.dirname(__file__), "..", "build", "tools", "rockfit"))
    parser.add_argument("--alpha", type=float, default=0.25, help="slenderness θ_c = atan(b/h) [rad]")
    parser.add_argument("--R", type=float, default=1.0, help="half-diagonal of the section [m]")
    parser.add_argument("--ratios", default="1,1.5,2,3,4,5,6", help="ω_p/p values, comma-separated")
    parser.add_argument("--overturn", choices=["support", "side"], default="side")
    parser.add_argument("--step", type=float, default=0.02, help="scan step of a_p/(g tan θ_c)")
    parser.add_argument("--tol", type=float, default=1e-3, help="bisection tolerance of a_p/(g tan θ_c)")
    parser.add_argument("--max", type=float, default=20.0, help="largest a_p/(g tan θ_c) tried")
    a = parser.parse_args()

    b = a.R * math.sin(a.alpha)
    h = a.R * math.cos(a.alpha)
    p = math.sqrt(3.0 * G / (4.0 * a.R))
    block_args = ["--b1", f"{b:.17g}", "--b2", f"{b:.17g}", "--h", f"{h:.17g}", "--density", "2500"]
    unit = G * math.tan(a.alpha)
    print(f"# θ_c = {a.alpha} rad, R = {a.R} m, p = {p:.6g} rad/s, r = {1 - 1.5 * math.sin(a.alpha) ** 2:.6f} "
          f"(Housner), overturn = {a.overturn}")
    print("# ω_p/p  a_p/(g tan θ_c)  landed before overturning")
    with tempfile.TemporaryDirectory() as tmp:
        for ratio in (float(x) for x in a.ratios.split(",")):
            record = os.path.join(tmp, f"pulse_{ratio}.csv")
            period = write_pulse(record, ratio * p)
            tail = 8.0 / p
            lo, hi, hi_landed = 1.0, None, False
            x = 1.0
            while x <= a.max:
                over, landed = run(a.rockfit, block_args, record, x * unit, tail, a.overturn)
                if over:
                    hi, hi_landed = x, landed
                    break
                lo = x
                x += a.step
            if hi is None:
                print(f"{ratio:7.3g}  > {a.max}")
                continue
            while hi - lo > a.tol:
                mid = 0.5 * (lo + hi)
                over, landed = run(a.rockfit, block_args, record, mid * unit, tail, a.overturn)
                if over:
                    hi, hi_landed = mid, landed
                else:
                    lo = mid
            print(f"{ratio:7.3g}  {hi:.4f}  {'yes' if hi_landed else 'no'}", flush=True)


if __name__ == "__main__":
    main()
