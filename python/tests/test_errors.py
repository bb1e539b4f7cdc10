"""rockfit's errors as Python exceptions with the library's messages: InputError with file, line and column,
OutputError, ValueError for bad arguments; the real x-IMU recordings when they are present beside the checkout."""
import os
import pathlib

import pytest

from conftest import MANIFEST, SOURCE_DIR, run_cli_plain

SHARED = pathlib.Path(os.environ.get("ROCKFIT_SHARED_DIR", SOURCE_DIR.parent / "shared"))
REAL_IMU = SHARED / "real-imu"


def test_misspelt_manifest_key_names_line_and_column(rockfit, tmp_path):
    manifest = tmp_path / "campaign.toml"
    manifest.write_text('[[blocks]]\nid = "b"\nb1 = 0.05\nb2 = 0.03\nhh = 0.2\ndensity = 2692\n')
    with pytest.raises(rockfit.InputError) as info:
        rockfit.Block.from_manifest(str(manifest), "b")
    error = info.value
    assert isinstance(error, ValueError)
    assert error.path == str(manifest) and error.line == 5 and error.column == 1
    code, _, stderr = run_cli_plain("block", "--manifest", manifest, "--block", "b")
    assert code == 2 and str(error) in stderr  # the program's message, unchanged


def test_not_a_rockfit_hdf5_file_is_an_input_error(rockfit, tmp_path):
    fake = tmp_path / "trial.h5"
    fake.write_bytes(b"not hdf5 at all")
    with pytest.raises(rockfit.InputError, match="not an HDF5 file") as info:
        rockfit.load_recording(str(fake))
    assert info.value.path == str(fake) and info.value.line is None


def test_unwritable_output_is_an_output_error(rockfit, tmp_path):
    block = rockfit.Block(0.05000453, 0.035, 0.2, density=2692)
    with pytest.raises(rockfit.OutputError, match="check that the directory exists") as info:
        rockfit.synth(str(tmp_path / "missing" / "trial"), block, alpha=0.1, t0=0.5, duration=1.5)
    assert isinstance(info.value, OSError)


def test_wrong_argument_types_are_type_errors(rockfit):
    with pytest.raises(TypeError):
        rockfit.Block("wide", 0.03, 0.2, mass=1)
    with pytest.raises(TypeError):
        rockfit.metrics("not a recording")


def test_paths_may_be_pathlib_paths(rockfit):
    block = rockfit.Block.from_manifest(MANIFEST, "block2")
    assert block.b1 == rockfit.Block.from_manifest(str(MANIFEST), "block2").b1
    assert len(rockfit.load_recording(MANIFEST, trial="block2-A-1")) > 1000


def test_a_nul_byte_in_a_path_is_a_value_error_naming_the_path(rockfit):
    with pytest.raises(ValueError, match="contains a NUL byte"):
        rockfit.load_recording(str(MANIFEST) + "\0.csv", trial="block2-A-1")
    with pytest.raises(ValueError, match="contains a NUL byte"):
        rockfit.Block.from_manifest(str(MANIFEST) + "\0x", "block2")


def test_a_deep_dotted_manifest_key_or_a_fifo_is_an_input_error_not_a_crash(rockfit, tmp_path):
    manifest = tmp_path / "deep.toml"
    manifest.write_text(".".join(["a"] * 40000) + " = 1\n")
    with pytest.raises(rockfit.InputError, match="more than 64 parts"):
        rockfit.Block.from_manifest(manifest, "b")
    with pytest.raises(rockfit.InputError, match="more than 64 parts"):
        rockfit.load_recording(manifest, trial="t")
    fifo = tmp_path / "fifo.toml"
    os.mkfifo(fifo)
    with pytest.raises(rockfit.InputError, match="FIFO"):
        rockfit.load_recording(fifo, trial="t")


@pytest.mark.skipif(not REAL_IMU.is_dir(), reason="the real x-IMU recordings beside the checkout are not present")
def test_real_ximu_set_without_registers_says_which_rate_to_pass(rockfit):
    prefix = REAL_IMU / "Oscillatory-Motion-Tracking-With-x-IMU" / "LoggedData" / "LoggedData"
    with pytest.raises(rockfit.InputError, match="suggests --rate 256") as info:
        rockfit.load_recording(str(prefix))
    assert info.value.path.endswith("LoggedData_CalInertialAndMag.csv")
    rec = rockfit.load_recording(str(prefix), rate=256)
    assert rec.rate_hz == 256 and rec.rate_source == "option" and len(rec) > 1000


@pytest.mark.skipif(not REAL_IMU.is_dir(), reason="the real x-IMU recordings beside the checkout are not present")
def test_real_ximu3_directory_loads(rockfit):
    rec = rockfit.load_recording(str(REAL_IMU / "x-IMU3-CSV" / "Logged Data"))
    assert rec.format == "ximu3" and rec.rate_source == "timestamps" and rec.w_B.shape[1] == 3


def test_the_module_documents_itself(rockfit):
    assert "Units are SI" in rockfit.__doc__
    for name in ("Block", "Recording", "load_recording", "metrics", "edge_impact", "facet_impact", "simulate",
                 "fit", "evaluate", "fit_campaign", "synth", "InputError", "NumericalError", "OutputError", "Record"):
        assert getattr(rockfit, name).__doc__, name
    assert "[rad/s]" in rockfit.simulate.__doc__ and "KeyboardInterrupt" in rockfit.fit.__doc__
