"""rockfit.fit, fit_campaign and evaluate: results equal to `rockfit fit --json`, recovery of the known truth of a
synthetic trial, two fits in parallel Python threads faster than one after the other, Ctrl-C."""
import _thread
import json
import threading
import time

import numpy as np
import pytest

from conftest import MANIFEST, SAMPLES, SAMPLE_TRIAL, as_plain, requires_optimised_build, run_cli

pytestmark = requires_optimised_build

OTHER_TRIAL = "block2-A-2"



def assert_equal_to_cli(result, cli):
    """Every key of the program's JSON, bit for bit; wall_s is a measured time."""
    for key, expected in cli.items():
        if key == "wall_s":
            continue
        if key == "uncertainty":  # its wall_s is a measured time too
            expected = {k: v for k, v in expected.items() if k != "wall_s"}
            assert {k: v for k, v in as_plain(result[key]).items() if k != "wall_s"} == expected, key
            continue
        if key == "parameters":
            for name, fields in expected.items():
                for field, value in fields.items():
                    assert result.parameters[name][field] == value, (name, field)
            continue
        assert as_plain(result[key]) == expected, key


@pytest.fixture(scope="module")
def default_fit(rockfit, sample_recording):
    return rockfit.fit(sample_recording)


def test_fit_equals_the_program_json_bit_for_bit(default_fit):
    cli = run_cli("fit", MANIFEST, "--trial", SAMPLE_TRIAL)
    assert_equal_to_cli(default_fit, cli)


def test_fit_with_fix_and_bounds_equals_the_program(rockfit, sample_recording):
    result = rockfit.fit(sample_recording, fix={"lambda_lat": -2.032}, bounds={"lambda": (0.5, 3.5)},
                         method="nelder-mead")
    cli = run_cli("fit", MANIFEST, "--trial", SAMPLE_TRIAL, "--fix", "lambda_lat=-2.032", "--lower", "lambda=0.5",
                  "--upper", "lambda=3.5", "--method", "nelder-mead")
    assert_equal_to_cli(result, cli)
    assert result.parameters["lambda_lat"].fixed and result.values["lambda_lat"] == -2.032


def test_fit_with_a_gyro_scale_equals_the_program(rockfit, sample_recording):
    result = rockfit.fit(sample_recording, estimate_gyro_scale="common", method="nelder-mead", max_evaluations=60,
                         global_stage=False)
    cli = run_cli("fit", MANIFEST, "--trial", SAMPLE_TRIAL, "--estimate-gyro-scale", "common", "--method",
                  "nelder-mead", "--max-evaluations", "60", "--no-global")
    assert_equal_to_cli(result, cli)
    assert cli["gyro_scale"]["mode"] == "common"
    with pytest.raises(ValueError):
        rockfit.fit(sample_recording, estimate_gyro_scale="yes")


def test_fit_with_the_release_roll_equals_the_program(rockfit, sample_recording):
    result = rockfit.fit(sample_recording, fit_release_roll=True, method="nelder-mead", max_evaluations=60,
                         global_stage=False)
    cli = run_cli("fit", MANIFEST, "--trial", SAMPLE_TRIAL, "--fit-release-roll", "--method", "nelder-mead",
                  "--max-evaluations", "60", "--no-global")
    assert_equal_to_cli(result, cli)
    assert not cli["parameters"]["release_roll"]["fixed"]
    assert "release_roll" in result.values


def test_a_fit_without_the_release_roll_does_not_report_it(default_fit):
    assert "release_roll" not in default_fit.parameters and "release_roll" not in default_fit.values


def test_the_release_roll_choice_says_why_a_planar_release_keeps_it_off(default_fit):
    choice = as_plain(default_fit["release_roll_choice"])
    assert choice["mode"] == "auto" and choice["judged"] and not choice["fitted"]
    assert choice["roll_seen_rad"] < 8 * choice["roll_noise_rad"]
    assert choice["start_rad"] is None and "not fitted" in choice["reason"]


def test_a_release_from_rest_is_still_before_its_fitted_t0(default_fit):
    motion = as_plain(default_fit["motion_before_release"])
    assert motion["available"] and not motion["moving"]
    assert motion["t0_s"] == default_fit.values["t0"] and motion["lookback_s"] == pytest.approx(0.1)
    assert motion["turn_deg"] < 0.01  # degrees: noise, against the warning's 0.1
    assert "moving_at_release" not in [w["kind"] for w in as_plain(default_fit["warnings"])]


def test_fit_recovers_the_truth_of_the_synthetic_trial(default_fit):
    truth = json.loads((SAMPLES / "recordings" / f"{SAMPLE_TRIAL}_truth.json").read_text())
    assert truth["command"].find("--alpha 0.197") > 0  # made with the paper's Fig. 14 values, t0 = 2.33 s
    v = default_fit.values
    assert abs(v["t0"] - 2.33) < 2e-3          # s
    assert abs(v["alpha"] - 0.197) < 2e-3      # rad
    assert abs(v["lambda"] - 2.185) < 0.1
    assert abs(v["lambda_lat"] - -2.032) < 0.2032
    assert abs(v["lambda_lon"] - 0.197) < 0.03
    assert default_fit.feasible and default_fit.epsilon < 0.02


def test_fit_result_exposes_the_whole_summary(default_fit):
    alpha = default_fit.parameters["alpha"]
    for field in ("value", "lower", "upper", "fixed", "std_error", "identifiable", "at_bound", "start", "unit"):
        assert field in alpha, field
    assert alpha.unit == "rad" and alpha.std_error > 0
    assert default_fit.parameters["tau_edge"].std_error is None  # fixed: no standard error
    assert default_fit.stages and default_fit.notes and "ε (28)" in default_fit.report
    assert default_fit.w_B_simulated.shape == default_fit.w_B_measured.shape == (default_fit.t.size, 3)
    assert default_fit.t[0] == default_fit.values["t0"] and default_fit.t[-1] == default_fit.t_end
    text = repr(default_fit)
    assert text.startswith("FitResult(trial='block2-A-1'") and "epsilon=" in text
    assert "alpha" in dir(alpha) or "value" in dir(alpha)


def test_evaluate_equals_the_program(rockfit, sample_recording):
    result = rockfit.evaluate(sample_recording, t0=2.33, alpha=0.197, lambda_=2.185, lambda_lat=-2.032,
                              lambda_lon=0.197)
    cli = run_cli("fit", MANIFEST, "--trial", SAMPLE_TRIAL, "--evaluate", "--t0", 2.33, "--alpha", 0.197,
                  "--lambda", 2.185, "--lambda-lat", -2.032, "--lambda-lon", 0.197)
    assert as_plain(result.to_dict()) == cli


def test_fit_campaign_equals_single_fits(rockfit):
    results = rockfit.fit_campaign(str(MANIFEST), trials=[SAMPLE_TRIAL, OTHER_TRIAL], jobs=2)
    assert [r.trial for r in results] == [SAMPLE_TRIAL, OTHER_TRIAL]
    single = rockfit.fit(rockfit.load_recording(str(MANIFEST), trial=OTHER_TRIAL), threads=1)
    assert results[1].values == single.values and results[1].epsilon == single.epsilon


def test_fit_campaign_reports_an_unreadable_trial(rockfit, tmp_path):
    manifest = tmp_path / "campaign.toml"
    manifest.write_text(MANIFEST.read_text().replace('files = "recordings/block1-A-1"', 'files = "nowhere/x"')
                        .replace('"recordings/', f'"{SAMPLES}/recordings/'))
    results = rockfit.fit_campaign(str(manifest), trials=["block1-A-1"])
    assert results[0].type_name == "FitFailure" and results[0].error == "InputError"


def test_a_fit_releases_the_gil_while_it_runs(rockfit, sample_recording):
    done = threading.Event()
    worker = threading.Thread(target=lambda: (rockfit.fit(sample_recording, threads=1), done.set()))
    worker.start()
    python_steps = 0
    while not done.is_set() and worker.is_alive():
        python_steps += 1  # this thread runs Python code only while the fit does not hold the GIL
        time.sleep(0.001)
    worker.join()
    assert python_steps > 50, f"the main thread ran {python_steps} steps during the fit"


def test_ctrl_c_interrupts_a_running_fit(rockfit, sample_recording):
    # A fit of 20000 evaluations runs for seconds; it can only end in KeyboardInterrupt if Ctrl-C stops it
    # (no wall time is asserted: the machine may be shared).
    timer = threading.Timer(0.15, _thread.interrupt_main)
    timer.start()
    with pytest.raises(KeyboardInterrupt):
        rockfit.fit(sample_recording, threads=1, max_evaluations=20000)
    timer.join()
    # The module is usable afterwards.
    assert rockfit.evaluate(sample_recording).feasible


def test_bad_fit_arguments_are_value_errors_with_the_program_messages(rockfit, sample_recording):
    with pytest.raises(ValueError, match="lambda_x"):
        rockfit.fit(sample_recording, fix="lambda_x")
    with pytest.raises(ValueError, match="outside the bounds"):
        rockfit.fit(sample_recording, fix={"alpha": 0.5})
    with pytest.raises(ValueError, match="method"):
        rockfit.fit(sample_recording, method="newton")
    with pytest.raises(ValueError, match="bounds"):
        rockfit.fit(sample_recording, bounds=3)
