"""examples/python/: README.md's Python example runs as printed (issue 41). scripts/demo.sh builds
the module and prints the line that runs it; this runs that script with this interpreter (ctest
uses the one the module was built for, Debian's /usr/bin/python3 through scripts/build.sh) and
PYTHONPATH pointing at the built module, and checks its whole output.
"""
import os
import pathlib
import re
import subprocess
import sys

import pytest

import delcert

ROOT = pathlib.Path(__file__).resolve().parents[2]


def test_demo_prints_the_line_that_runs_an_existing_example():
    demo = (ROOT / "scripts" / "demo.sh").read_text()
    lines = re.findall(r'echo "(PYTHONPATH=build/python \S+ (examples/python/\S+\.py))"', demo)
    assert len(lines) == 1, lines
    script = ROOT / lines[0][1]
    assert script.is_file(), script
    assert "delcert_python" in demo  # the demo builds the module's target


def test_readme_python_example_prints_certified():
    pytest.importorskip("gudhi")  # python3-gudhi (scripts/setup.sh)
    script = ROOT / "examples" / "python" / "certify_gudhi.py"
    # PYTHONPATH: the folder of the module this test imported (build/python/ from the demo).
    module_dir = os.path.dirname(os.path.abspath(delcert.__file__))
    result = subprocess.run([sys.executable, str(script)], capture_output=True, text=True, cwd=ROOT,
                            env=dict(os.environ, PYTHONPATH=module_dir, PYTHONNOUSERSITE="1"))
    assert result.returncode == 0, result.stderr
    # GUDHI's complex of this net (80 points, seed 1) is Del_TM(P): every check passes.
    assert result.stdout == "CERTIFIED\n", result.stdout + result.stderr
