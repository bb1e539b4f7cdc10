"""rockfit.metrics: the fields of `rockfit metrics --json`, bit for bit, and the corrected angles as arrays."""
import numpy as np
import pytest

from conftest import MANIFEST, SAMPLE_TRIAL, as_plain, run_cli

TRIAL = "block3-A-1"  # the README's metrics example



def test_metrics_equal_the_program_json_bit_for_bit(rockfit):
    rec = rockfit.load_recording(str(MANIFEST), trial=TRIAL)
    result = rockfit.metrics(rec)
    cli = run_cli("metrics", MANIFEST, "--trial", TRIAL)
    for key, expected in cli.items():
        assert as_plain(result[key]) == expected, key
    assert result.status == "ok"


def test_metrics_with_options_equal_the_program(rockfit):
    rec = rockfit.load_recording(str(MANIFEST), trial=TRIAL)
    result = rockfit.metrics(rec, anchors="sample", uplift="paper", peaks=6)
    cli = run_cli("metrics", MANIFEST, "--trial", TRIAL, "--anchors", "sample", "--uplift", "paper", "--peaks", "6")
    for key, expected in cli.items():
        assert as_plain(result[key]) == expected, key


def test_corrected_angles_are_zero_at_the_detected_impacts(rockfit):
    rec = rockfit.load_recording(str(MANIFEST), trial=TRIAL)
    result = rockfit.metrics(rec)
    assert result.euler_corrected.shape == rec.euler.shape
    # At each φ_y anchor the correction removes the measured value: corrected φ_y interpolates to zero there.
    phi_y = np.interp(result.impact_times, result.t, result.euler_corrected[:, 1])
    assert np.max(np.abs(phi_y)) < 2e-3  # rad; linear interpolation across the landing's kink
    np.testing.assert_array_equal(result.euler_raw, rec.euler)


def test_opmf_is_the_ratio_of_the_maxima(rockfit):
    rec = rockfit.load_recording(str(MANIFEST), trial=TRIAL)
    result = rockfit.metrics(rec)
    assert result.opmf == pytest.approx(result.max_abs_phi_x / result.max_abs_phi_y, rel=1e-15)
    assert result.avrf == pytest.approx(float(np.median(result.avrf_ratios)), rel=1e-15)


def test_metrics_without_a_block_is_a_value_error(rockfit):
    rec = rockfit.load_recording(str(MANIFEST), trial=SAMPLE_TRIAL)
    bare = rockfit.Recording(rec.t, rec.w_B, rec.euler)
    with pytest.raises(ValueError, match="needs the block geometry"):
        rockfit.metrics(bare)
    with pytest.raises(ValueError, match="uplift"):
        rockfit.metrics(rec, uplift="nope")


def test_recording_without_attitude_gets_it_from_the_gyro(rockfit, sample_block):
    rec = rockfit.load_recording(str(MANIFEST), trial=SAMPLE_TRIAL)
    bare = rockfit.Recording(rec.t, rec.w_B)
    result = rockfit.metrics(bare, sample_block)
    with_attitude = rockfit.metrics(rec, sample_block)
    assert result.status == "ok"
    # The required agreement of gyro-only metrics (io/README.md, "Attitude from the gyro").
    assert result.opmf == pytest.approx(with_attitude.opmf, abs=0.003)
    assert result.avrf == pytest.approx(with_attitude.avrf, rel=0.01)
