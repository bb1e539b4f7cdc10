"""rockfit.load_recording and rockfit.Recording: the readers' samples and metadata, views without copies."""
import gc

import numpy as np
import pytest

from conftest import MANIFEST, SAMPLE_TRIAL, SAMPLES, run_cli


def test_manifest_trial_matches_the_program_inspect(rockfit, sample_recording):
    cli = run_cli("inspect", SAMPLES / "recordings" / SAMPLE_TRIAL)
    rec = sample_recording
    assert rec.trial == SAMPLE_TRIAL
    assert len(rec) == cli["samples"] == 1536
    assert rec.format == cli["format"] == "ximu-gui"
    assert rec.rate_hz == cli["rate_hz"] == 256
    assert rec.duration_s == cli["duration_s"]
    assert rec.orientation_rate_hz == cli["orientation_rate_hz"]
    assert rec.columns == cli["columns"]
    assert rec.warnings == cli["warnings"]
    assert rec.gaps == [] and cli["gaps"] == []


def test_arrays_have_the_documented_shapes_and_units(sample_recording):
    rec = sample_recording
    assert rec.t.shape == (1536,) and rec.t.dtype == np.float64
    assert rec.w_B.shape == (1536, 3)
    assert rec.euler.shape == (1536, 3)
    np.testing.assert_allclose(np.diff(rec.t), 1 / 256, rtol=1e-9)
    # Released about V1V2, falling back: w_B ≈ (0, +ω, 0) with |ω| ≲ 2 rad/s for this block.
    assert 0.5 < np.max(np.abs(rec.w_B[:, 1])) < 3.0


def test_manifest_trial_carries_its_block(rockfit, sample_recording):
    assert sample_recording.block is not None
    assert sample_recording.block.b2 == 0.035
    assert sample_recording.block_id == "block2" and sample_recording.position == "A"


def test_arrays_are_views_of_the_recording_and_keep_it_alive(rockfit):
    rec = rockfit.load_recording(str(MANIFEST), trial=SAMPLE_TRIAL)
    w = rec.w_B
    assert not w.flags.owndata and w.base is not None
    w[0, 0] = 123.0  # in place: the next view sees it
    assert rec.w_B[0, 0] == 123.0
    t = rec.t
    expected_last = float(t[-1])
    del rec
    gc.collect()
    assert t[-1] == expected_last  # the view keeps the recording alive


def test_recording_from_arrays_copies_once_and_estimates_the_rate(rockfit):
    t = np.arange(512) / 256.0
    w = np.zeros((512, 3))
    w[:, 1] = np.sin(t)
    rec = rockfit.Recording(t, w, np.zeros((512, 3)))
    assert rec.rate_hz == pytest.approx(256.0, rel=1e-12)
    w[0, 1] = 99.0
    assert rec.w_B[0, 1] == 0.0
    assert rec.format == "python"


def test_recording_from_arrays_of_different_lengths_is_a_value_error(rockfit):
    with pytest.raises(ValueError, match="one row per sample"):
        rockfit.Recording(np.arange(10.0), np.zeros((9, 3)))
    with pytest.raises(ValueError, match=r"w_B must be an \(N, 3\) array"):
        rockfit.Recording(np.arange(10.0), np.zeros((10, 2)))
    with pytest.raises(ValueError, match="strictly increasing"):
        rockfit.Recording(np.array([0.0, 1.0, 1.0]), np.zeros((3, 3)))


def test_missing_file_is_an_input_error_with_the_path(rockfit, tmp_path):
    missing = tmp_path / "nothing.csv"
    with pytest.raises(rockfit.InputError) as info:
        rockfit.load_recording(str(missing))
    assert str(missing) in str(info.value)
    assert info.value.path is not None and str(missing) in info.value.path


def test_bad_cell_is_an_input_error_with_file_line_and_column(rockfit, tmp_path):
    csv = tmp_path / "trial.csv"
    rows = ["time_s,gx,gy,gz"] + [f"{k / 100},0,0.5,0" for k in range(20)]
    rows[7] = "0.06,0,abc,0"
    csv.write_text("\n".join(rows) + "\n")
    with pytest.raises(rockfit.InputError) as info:
        rockfit.load_recording(str(csv), columns="time=time_s@s;gyro=gx,gy,gz@rad/s")
    assert info.value.path == str(csv)
    assert info.value.line == 8
    assert info.value.column is not None
    assert "abc" in str(info.value)


def test_manifest_without_trial_is_a_value_error_listing_the_trials(rockfit):
    with pytest.raises(ValueError, match="block1-A-1"):
        rockfit.load_recording(str(MANIFEST))


def test_options_that_do_not_fit_are_value_errors(rockfit):
    with pytest.raises(ValueError, match="--format"):
        rockfit.load_recording(str(MANIFEST), trial=SAMPLE_TRIAL, format="nope")
    with pytest.raises(ValueError, match="rate"):
        rockfit.load_recording(str(SAMPLES / "recordings" / SAMPLE_TRIAL), rate=-1)
