"""rockfit.synth: the same files as `rockfit synth` for the same inputs, and the truth it returns."""
import json

import numpy as np
import pytest

from conftest import run_cli

ARGS = dict(alpha=0.197, lambda_=2.185, lambda_lat=-2.032, lambda_lon=0.197, t0=1.0, duration=3.0, seed=7)
CLI = ["--b1", "0.05000453", "--b2", "0.035", "--h", "0.2", "--density", "2692", "--alpha", "0.197", "--lambda",
       "2.185", "--lambda-lat", "-2.032", "--lambda-lon", "0.197", "--t0", "1", "--duration", "3", "--seed", "7"]


@pytest.fixture(scope="module")
def block(rockfit):
    return rockfit.Block(0.05000453, 0.035, 0.2, density=2692)


def test_synth_writes_the_same_files_as_the_program(rockfit, block, tmp_path):
    (tmp_path / "py").mkdir()
    (tmp_path / "cli").mkdir()
    truth = rockfit.synth(str(tmp_path / "py" / "trial"), block, **ARGS)
    cli = run_cli("synth", *CLI, "-o", tmp_path / "cli" / "trial")
    for key in ("samples", "rate_hz", "duration_s", "t0_s", "seed", "impacts", "first_impact_s", "phase4_end_s",
                "rest_s"):
        assert truth[key] == cli[key], key
    assert [f.split("/")[-1] for f in truth.files] == [f.split("/")[-1] for f in cli["files"]]
    for name in sorted(p.name for p in (tmp_path / "cli").iterdir()):
        mine = (tmp_path / "py" / name).read_bytes()
        theirs = (tmp_path / "cli" / name).read_bytes()
        if name.endswith("_truth.json"):  # identical but for the command that made it
            a, b = json.loads(mine), json.loads(theirs)
            a.pop("command"), b.pop("command")
            assert a == b
        else:
            assert mine == theirs, name


def test_a_rolled_release_writes_the_same_files_as_the_program(rockfit, block, tmp_path):
    (tmp_path / "py").mkdir()
    (tmp_path / "cli").mkdir()
    truth = rockfit.synth(str(tmp_path / "py" / "trial"), block, release_roll=0.005, **ARGS)
    run_cli("synth", *CLI, "--release-roll", "0.005", "-o", tmp_path / "cli" / "trial")
    name = "trial_CalInertialAndMag.csv"
    assert (tmp_path / "py" / name).read_bytes() == (tmp_path / "cli" / name).read_bytes()
    assert truth.parameters["release_roll"] == 0.005 == truth.truth["parameters"]["release_roll_rad"]
    w_x = np.abs(truth.w_B_true[:, 0])
    assert w_x.max() > 0.01  # the premise: the roll rocks the block about x from the release on


def test_synth_returns_the_truth_and_the_true_motion(rockfit, block, tmp_path):
    truth = rockfit.synth(str(tmp_path / "trial"), block, **ARGS)
    assert truth.parameters["alpha"] == 0.197 and truth.parameters["t0"] == 1.0
    assert truth.t.shape == (768,) and truth.w_B_true.shape == (768, 3)
    released = truth.t >= 1.0
    assert np.all(truth.w_B_true[~released] == 0)  # at rest before the release
    assert truth.first_impact_s > 1.0 and truth.truth["format"] == "rockfit synthetic recording truth"
    rec = rockfit.load_recording(str(tmp_path / "trial"))
    assert len(rec) == truth.samples
    # The gyro measures the true motion plus noise (0.1 deg/s), ringing and bias (quantised to 1/16 deg/s).
    residual = rec.w_B[released] - truth.w_B_true[released]
    assert np.median(np.abs(residual)) < np.deg2rad(0.5)


def test_ideal_sensor_reproduces_the_simulation(rockfit, block, tmp_path):
    truth = rockfit.synth(str(tmp_path / "ideal"), block, **ARGS, noise=False)
    rec = rockfit.load_recording(str(tmp_path / "ideal"))
    np.testing.assert_allclose(rec.w_B, truth.w_B_true, atol=1e-5)  # single precision in the files


def test_bad_synth_arguments(rockfit, block, tmp_path):
    with pytest.raises(ValueError, match="noise=False"):
        rockfit.synth(str(tmp_path / "x"), block, noise=False, ringing_gain=0.1)
    with pytest.raises(ValueError, match="facet_tau"):
        rockfit.synth(str(tmp_path / "x"), block, facet_tau="x")
    with pytest.raises(rockfit.NumericalError):
        rockfit.synth(str(tmp_path / "x"), block, alpha=0.6, t0=0.5, duration=2)  # beyond the critical tilt: overturns
