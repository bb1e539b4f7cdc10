"""CSV recordings as labs bring them (data-samples/csv/): phyphox, Sensor Logger, a microcontroller log and a quoted
spreadsheet export, read from their campaign manifest, with the attitude integrated from the gyro for the metrics,
equal to what the program prints."""
import pytest

from conftest import MANIFEST, SAMPLES, as_plain, requires_optimised_build, run_cli

CSV_MANIFEST = SAMPLES / "csv" / "manifest.toml"
TRIALS = ["block1-A-1", "block1-B-1", "block2-A-1", "block3-A-1"]


@pytest.mark.parametrize("trial", TRIALS)
def test_each_csv_trial_is_read_with_its_column_map(rockfit, trial):
    rec = rockfit.load_recording(str(CSV_MANIFEST), trial=trial)
    original = rockfit.load_recording(str(MANIFEST), trial=trial)
    assert rec.format == "generic-csv"
    assert rec.rate_hz == pytest.approx(256.0, rel=1e-4)
    assert len(rec.t) == len(original.t)


@pytest.mark.parametrize("trial", TRIALS)
def test_metrics_of_a_csv_trial_equal_the_program(rockfit, trial):
    result = rockfit.metrics(rockfit.load_recording(str(CSV_MANIFEST), trial=trial))
    cli = run_cli("metrics", CSV_MANIFEST, "--trial", trial)
    for key, expected in cli.items():
        assert as_plain(result[key]) == expected, key
    assert result.status == "ok"


def expect_fit_like_the_program_near_its_truth(rockfit, trial, alpha_true, lambda_lat_true):
    """Python's fit of a CSV manifest trial gives the program's ε, and α and λ_lat near the synthetic truth: α within
    2e-3 rad and λ_lat within 10 %, the bounds test_fit.py holds the x-IMU files of the same trials to."""
    result = rockfit.fit(rockfit.load_recording(str(CSV_MANIFEST), trial=trial))
    cli = run_cli("fit", CSV_MANIFEST, "--trial", trial)
    assert result.epsilon == cli["epsilon"]
    assert abs(result.values["alpha"] - alpha_true) < 2e-3
    assert abs(result.values["lambda_lat"] - lambda_lat_true) < 0.1 * abs(lambda_lat_true)


@requires_optimised_build
def test_a_phyphox_trial_fits_like_the_program(rockfit):
    # The truth of the synthetic trial (data-samples/README.md): the paper's Fig. 14 parameters.
    expect_fit_like_the_program_near_its_truth(rockfit, "block2-A-1", 0.197, -2.032)


def test_a_sensor_logger_trial_carries_the_total_acceleration_beside_its_gyroscope(rockfit):
    rec = rockfit.load_recording(str(CSV_MANIFEST), trial="block1-A-1")
    assert rec.accel_B.shape == rec.w_B.shape
    assert any(c.startswith("TotalAcceleration.csv: ") for c in rec.columns)
    # At rest before the release the specific force is g (9.81 m/s², the synthetic model's) within the noise.
    assert abs(float((rec.accel_B[:100] ** 2).sum(axis=1).mean()) ** 0.5 - 9.81) < 0.05


@requires_optimised_build
def test_a_sensor_logger_trial_fits_like_the_program(rockfit):
    # The truth of the synthetic trial (tools/make_samples.sh: α = 0.21, λ_lat = −4.2).
    expect_fit_like_the_program_near_its_truth(rockfit, "block1-A-1", 0.21, -4.2)


def test_orientation_none_holds_for_a_manifest_trial_as_in_the_program(rockfit):
    rec = rockfit.load_recording(str(MANIFEST), trial="block3-A-1", orientation="none")
    assert rec.euler.shape == (0, 3)
    result = rockfit.metrics(rec)
    cli = run_cli("metrics", MANIFEST, "--trial", "block3-A-1", "--orientation", "none")
    assert result.opmf == cli["opmf"]
    assert result.avrf == cli["avrf"]
