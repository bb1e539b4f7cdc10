"""The examples in python/examples run and write their pictures."""
import os
import pathlib
import subprocess
import sys

from conftest import SOURCE_DIR, requires_optimised_build


@requires_optimised_build
def test_fit_sample_example_writes_a_png(rockfit, tmp_path):
    picture = tmp_path / "fit.png"
    module_dir = str(pathlib.Path(rockfit.__file__).resolve().parent)  # the module under test, wherever it is
    env = dict(os.environ, MPLBACKEND="Agg", MPLCONFIGDIR=str(tmp_path),
               PYTHONPATH=os.pathsep.join([module_dir, os.environ.get("PYTHONPATH", "")]))
    result = subprocess.run([sys.executable, str(SOURCE_DIR / "python" / "examples" / "fit_sample.py"), "-o",
                             str(picture)], capture_output=True, text=True, env=env, cwd=tmp_path, check=False)
    assert result.returncode == 0, result.stderr
    assert picture.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert "ε (28)" in result.stdout and "alpha" in result.stdout


@requires_optimised_build
def test_fragility_curve_example_fits_the_campaign_and_draws_a_png(rockfit, tmp_path):
    picture = tmp_path / "fragility.png"
    module_dir = str(pathlib.Path(rockfit.__file__).resolve().parent)
    env = dict(os.environ, MPLBACKEND="Agg", MPLCONFIGDIR=str(tmp_path),
               PYTHONPATH=os.pathsep.join([module_dir, os.environ.get("PYTHONPATH", "")]))
    result = subprocess.run([sys.executable, str(SOURCE_DIR / "python" / "examples" / "fragility_curve.py"),
                             "--samples", "10", "-o", str(picture)], capture_output=True, text=True, env=env,
                            cwd=tmp_path, check=False)
    assert result.returncode == 0, result.stderr
    assert picture.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert "fitted 2 trials of block2/A" in result.stdout and "P(overturn) by PGA" in result.stdout
