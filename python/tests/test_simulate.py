"""rockfit.simulate: the fields of `rockfit simulate --json`, bit for bit; arrays that own their memory; no leak
over 1000 calls; the GIL released while it runs."""
import gc
import resource
import threading

import numpy as np
import pytest

from conftest import as_plain, requires_optimised_build, run_cli

FIG14 = dict(alpha=0.197, lambda_=2.185, lambda_lat=-2.032, lambda_lon=0.197)
FIG14_CLI = ["--b1", "0.05000453", "--b2", "0.04", "--h", "0.2", "--density", "2692", "--alpha", "0.197",
             "--lambda", "2.185", "--lambda-lat", "-2.032", "--lambda-lon", "0.197"]



def test_simulation_equals_the_program_json_bit_for_bit(rockfit, fig14_block):
    result = rockfit.simulate(fig14_block, **FIG14)
    cli = run_cli("simulate", *FIG14_CLI)
    assert result.end_reason == cli["end_reason"] == "phase4"
    assert result.t_end == cli["t_end"]
    assert result.block == cli["block"] and result.parameters == cli["parameters"]
    assert as_plain(result.impacts) == cli["impacts"]
    for key in ("t", "w_B", "q_WB", "euler_zyx", "mode"):
        assert as_plain(result[key]) == cli["samples"][key], key
    diagnostics = as_plain(result.diagnostics)
    for key in ("num_steps", "num_evaluations", "min_normal_force", "max_friction_ratio", "max_energy_drift_rel",
                "segments"):
        assert diagnostics[key] == cli["diagnostics"][key], key


def test_first_impact_is_the_facet_impact_of_the_readme(rockfit, fig14_block):
    result = rockfit.simulate(fig14_block, **FIG14)
    first = result.impacts[0]
    assert first.kind == "facet" and first.contact_before == "V1V2" and first.contact_after == "V3"
    assert first.t == pytest.approx(0.3875, abs=5e-5)
    assert len(result.impacts) == 25


def test_energy_is_conserved_between_impacts_to_the_integrator_tolerance(rockfit, fig14_block):
    result = rockfit.simulate(fig14_block, **FIG14)
    assert result.diagnostics.max_energy_drift_rel < 1e-8


def test_sample_times_and_stop_options(rockfit, fig14_block):
    times = np.linspace(-0.1, 0.3, 9)
    result = rockfit.simulate(fig14_block, **FIG14, sample_times=times, sample_attitude=False)
    np.testing.assert_array_equal(result.t, times)
    assert result.q_WB.shape == (0, 4) and result.euler_zyx.shape == (0, 3)
    np.testing.assert_array_equal(result.w_B[0], [0, 0, 0])  # held before the release
    rest = rockfit.simulate(fig14_block, **FIG14, stop="rest")
    assert rest.end_reason == "rest" and rest.t_end > result.t[-1]


def test_returned_arrays_own_their_memory(rockfit, fig14_block):
    result = rockfit.simulate(fig14_block, **FIG14)
    w = result.w_B
    expected = w.copy()
    del result
    gc.collect()
    np.testing.assert_array_equal(w, expected)  # the capsule keeps the storage alive
    assert w.shape == (269, 3) and w.flags.c_contiguous


@requires_optimised_build
def test_no_leak_over_1000_simulations(rockfit, fig14_block):
    def rss_kb():
        with open("/proc/self/status") as status:
            for line in status:
                if line.startswith("VmRSS:"):
                    return int(line.split()[1])
        return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss

    for _ in range(100):  # warm up allocators and caches
        rockfit.simulate(fig14_block, **FIG14)
    gc.collect()
    before = rss_kb()
    for _ in range(1000):
        result = rockfit.simulate(fig14_block, **FIG14)
        del result
    gc.collect()
    growth_kb = rss_kb() - before
    # One result holds ~40 kB of arrays and records; a leak of one result per call would grow RSS by ~40 MB.
    assert growth_kb < 2048, f"RSS grew by {growth_kb} kB over 1000 simulations"


def test_simulations_run_in_parallel_threads(rockfit, fig14_block):
    results = [None] * 4

    def work(k):
        results[k] = rockfit.simulate(fig14_block, **FIG14, stop="rest")

    threads = [threading.Thread(target=work, args=(k,)) for k in range(4)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    reference = rockfit.simulate(fig14_block, **FIG14, stop="rest")
    for r in results:
        np.testing.assert_array_equal(r.w_B, reference.w_B)


def test_bad_simulation_arguments_are_value_errors(rockfit, fig14_block):
    with pytest.raises(ValueError, match="stop must be"):
        rockfit.simulate(fig14_block, stop="never")
    with pytest.raises(ValueError, match="facet_tau"):
        rockfit.simulate(fig14_block, facet_tau="spin")
    with pytest.raises(ValueError):
        rockfit.simulate(fig14_block, alpha=-0.1)
    with pytest.raises(ValueError):
        rockfit.simulate(fig14_block, release_edge=(1, 3))


def test_a_failed_run_is_a_status_not_an_exception(rockfit, fig14_block):
    result = rockfit.simulate(fig14_block, **FIG14, stop="rest", max_impacts=3)
    assert result.end_reason == "failed" and "max_impacts" in result.message
