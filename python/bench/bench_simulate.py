#!/usr/bin/env python3
"""Cost of one rockfit.simulate call from Python, against the simulator's own time (not part of the tests).

The C++ reference is build/tests/bench/rockfit_bench_simulate (BM_SimulateFig14, BM_SimulateFig14_NoAttitude):
the same block, parameters and options. Per call this prints the median CPU time of the Python call and the
median of (wall time of the call − the simulator's own wall time, diagnostics.wall_time_s), which is the cost of
the binding: argument conversion, result arrays and records.

    PYTHONPATH=build/python python3 python/bench/bench_simulate.py [--calls 2000]
"""
import argparse
import math
import statistics
import time

import rockfit

FIG14 = dict(alpha=0.197, lambda_=2.185, lambda_lat=-2.032, lambda_lon=0.197)


def measure(block, calls, **options):
    cpu, overhead = [], []
    for _ in range(calls):
        c0, w0 = time.process_time(), time.perf_counter()
        result = rockfit.simulate(block, **FIG14, **options)
        w1, c1 = time.perf_counter(), time.process_time()
        cpu.append(c1 - c0)
        overhead.append((w1 - w0) - result.diagnostics.wall_time_s)
    return statistics.median(cpu), statistics.median(overhead), len(result.impacts), result.t.size


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--calls", type=int, default=2000)
    args = parser.parse_args()
    block = rockfit.Block(0.2 * math.tan(0.245), 0.04, 0.2, density=2692)  # the paper's Fig. 14 block
    for name, options in (("Fig14", {}), ("Fig14_NoAttitude", {"sample_attitude": False})):
        measure(block, 50, **options)  # warm up
        cpu, overhead, impacts, samples = measure(block, args.calls, **options)
        print(f"simulate {name:<17} {impacts} impacts, {samples} samples: CPU per call {cpu * 1e6:8.1f} us, "
              f"binding overhead per call {overhead * 1e6:6.1f} us (median of {args.calls})")


if __name__ == "__main__":
    main()
