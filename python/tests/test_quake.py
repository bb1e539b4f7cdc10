"""The earthquake side in Python (rockfit.read_ground_motion, generate_ground_motion, respond, fragility): the
program's numbers bit for bit (`ground-motion inspect`, `respond --json`, `fragility --json`), thread-independent
fragility outcomes, arrays with units, and bad arguments as ValueError naming what to give."""
import numpy as np
import pytest

from conftest import SAMPLES, as_plain, run_cli

RECORD = SAMPLES / "ground-motions" / "cp-seed1-0.30g.AT2"
BLOCK_CLI = ["--b1", "0.05", "--b2", "0.1", "--h", "0.2", "--density", "2692"]


@pytest.fixture(scope="module")
def block(rockfit):
    return rockfit.Block(0.05, 0.1, 0.2, density=2692)


def test_read_ground_motion_equals_the_program_inspection(rockfit):
    g = rockfit.read_ground_motion(RECORD)
    cli = run_cli("ground-motion", "inspect", RECORD)
    record = cli["records"][0] if "records" in cli else cli
    assert g.npts == record["npts"]
    assert g.dt_s == record["dt_s"]
    assert g.a_g_W.shape == (g.npts, 3) and g.t.shape == (g.npts,)
    assert np.max(np.abs(g.a_g_W[:, 0])) / 9.80665 == pytest.approx(record["pga_g"], rel=1e-12)


def test_generated_record_has_the_requested_peak(rockfit):
    g = rockfit.generate_ground_motion(7, duration=10.0, dt=0.01, pga=0.25)
    assert g.npts == 1001
    assert np.max(np.hypot(g.a_g_W[:, 0], g.a_g_W[:, 1])) == pytest.approx(0.25 * 9.80665, rel=1e-12)


def test_respond_equals_the_program_json_bit_for_bit(rockfit, block):
    result = rockfit.respond(block, record=RECORD, pga=0.35, lambda_=0.95, lambda_lat=0.1, lambda_lon=0.9,
                             facet_tau="fixed")
    cli = run_cli("respond", *BLOCK_CLI, "--record", RECORD, "--pga", "0.35", "--lambda", "0.95", "--lambda-lat",
                  "0.1", "--lambda-lon", "0.9", "--facet-tau", "fixed")
    summary = as_plain(result.summary)
    summary.pop("wall_time_s")
    cli["summary"].pop("wall_time_s")
    assert summary == cli["summary"]
    assert result.parameters == cli["parameters"] and result.parameters["facet_tau"] == "fixed"
    assert as_plain(result.impacts) == cli["impacts"]
    assert as_plain(result.ground_motion) == cli["ground_motion"]
    for key in ("t", "a_g_W", "w_B", "q_WB", "tilt", "mode"):
        assert as_plain(result.samples[key]) == cli["samples"][key], key
    assert result.samples.w_B.shape[1] == 3 and result.samples.q_WB.shape[1] == 4


def test_respond_takes_parameters_from_a_fit_file_as_the_program_does(rockfit, block, tmp_path):
    fits = tmp_path / "fits.h5"
    run_cli("fit", SAMPLES / "manifest.toml", "--trial", "block2-A-1", "--intervals", "none", "-o", fits)
    result = rockfit.respond(block, record=RECORD, fits=fits, trial="block2-A-1")
    cli = run_cli("respond", *BLOCK_CLI, "--record", RECORD, "--fits", fits, "--trial", "block2-A-1")
    assert result.parameters == cli["parameters"]
    assert result.summary.num_impacts == cli["summary"]["num_impacts"]


def test_fragility_equals_the_program_json_and_does_not_depend_on_threads(rockfit, block, tmp_path):
    common = dict(records=[RECORD], pga=[0.2, 0.5], samples=6, lambda_=0.95, lambda_sd=0.05, seed=3, tail=2.0)
    one = rockfit.fragility(block, threads=1, **common)
    two = rockfit.fragility(block, threads=2, **common)
    cli = run_cli("fragility", *BLOCK_CLI, "--record", RECORD, "--pga", "0.2,0.5", "--samples", "6", "--lambda",
                  "0.95", "--lambda-sd", "0.05", "--seed", "3", "--tail", "2", "-j", "1", "-o", tmp_path / "f.h5")
    assert as_plain(one.blocks) == cli["blocks"] == as_plain(two.blocks)
    assert one.settings_hash == cli["settings_hash"]
    assert one.samples == cli["samples"] == 12
    for key in ("peak_tilt_rad", "overturned", "lambda"):
        assert np.array_equal(one.sample_outcomes[key], two.sample_outcomes[key]), key


@pytest.mark.parametrize("kwargs, message", [
    (dict(record=RECORD, facet_tau="bogus"), "facet-τ rule"),
    (dict(record=RECORD, start="sideways"), "flat or tilted"),
    (dict(record=RECORD, fits=None, trial="x"), "need --fits"),
    (dict(), "give"),
])
def test_bad_respond_arguments_are_value_errors_that_say_what_to_give(rockfit, block, kwargs, message):
    with pytest.raises(ValueError, match=message):
        rockfit.respond(block, **kwargs)


def test_a_missing_record_names_the_file(rockfit, tmp_path):
    with pytest.raises((ValueError, OSError), match="nope.AT2"):
        rockfit.read_ground_motion(tmp_path / "nope.AT2")
