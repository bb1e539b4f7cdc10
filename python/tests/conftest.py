"""Shared fixtures of the rockfit Python tests: the sample campaign, the rockfit program and its --json output.

CTest runs these with PYTHONPATH=build/python, ROCKFIT_BINARY (the program built next to the module) and
ROCKFIT_SOURCE_DIR (the checkout) in the environment.
"""
import json
import os
import pathlib
import subprocess

import numpy as np

import pytest

SOURCE_DIR = pathlib.Path(os.environ.get("ROCKFIT_SOURCE_DIR", pathlib.Path(__file__).resolve().parents[2]))
BINARY = pathlib.Path(os.environ.get("ROCKFIT_BINARY", SOURCE_DIR / "build" / "tools" / "rockfit"))
SAMPLES = SOURCE_DIR / "data-samples"
MANIFEST = SAMPLES / "manifest.toml"

# Whole fits and long loops of simulations run in optimised builds only: in a Debug build the simulator is about
# 150 times slower (tests/support/build_type.hpp does the same for the C++ suites).
OPTIMISED_BUILD = os.environ.get("ROCKFIT_OPTIMISED_BUILD", "1") == "1"
requires_optimised_build = pytest.mark.skipif(
    not OPTIMISED_BUILD, reason="whole fits and 1000-call loops run in optimised builds only (Debug simulates ~150x "
                                "slower); the cheaper tests cover the same code there")

# The sample trial the README fits: block2 (b2 = 3.5 cm), made with the paper's Fig. 14 parameters.
SAMPLE_TRIAL = "block2-A-1"


def run_cli(*args, check=True):
    """Runs the rockfit program with --json and returns the parsed output."""
    result = subprocess.run([str(BINARY), *map(str, args), "--json"], capture_output=True, text=True, check=False)
    if check and result.returncode != 0:
        raise AssertionError(f"rockfit {' '.join(map(str, args))} exited {result.returncode}: {result.stderr}")
    return json.loads(result.stdout)


def run_cli_plain(*args):
    """Runs the rockfit program; returns (exit code, stdout, stderr)."""
    result = subprocess.run([str(BINARY), *map(str, args)], capture_output=True, text=True, check=False)
    return result.returncode, result.stdout, result.stderr


@pytest.fixture(scope="session")
def rockfit():
    import rockfit as module
    return module


@pytest.fixture(scope="session")
def sample_recording(rockfit):
    return rockfit.load_recording(str(MANIFEST), trial=SAMPLE_TRIAL)


@pytest.fixture(scope="session")
def sample_block(rockfit):
    return rockfit.Block.from_manifest(str(MANIFEST), "block2")


@pytest.fixture(scope="session")
def fig14_block(rockfit):
    # The paper's Fig. 14 block: granite, h = 0.20 m, b1 = h·tan 0.245, b2 = 0.04 m.
    return rockfit.Block(0.05000453, 0.04, 0.2, density=2692)


def as_plain(value):
    """A result as plain Python (lists, dicts, numbers) for comparison with the program's JSON."""
    if isinstance(value, np.ndarray):
        return value.tolist()
    if isinstance(value, list):
        return [as_plain(v) for v in value]
    if hasattr(value, "to_dict") or isinstance(value, dict):
        return {k: as_plain(v) for k, v in value.items()}
    return value
