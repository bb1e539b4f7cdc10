"""Importing the module: an interpreter without numpy is told at import what to do, not at its first array."""
import os
import subprocess
import sys


def test_import_without_numpy_names_the_interpreter_to_use():
    # `sys.modules["numpy"] = None` makes `import numpy` fail as on an interpreter that lacks it.
    code = "import sys; sys.modules['numpy'] = None; import rockfit"
    result = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=dict(os.environ))
    assert result.returncode != 0
    assert "ImportError" in result.stderr
    assert "rockfit needs numpy" in result.stderr
    assert "-DPython3_EXECUTABLE=" in result.stderr
