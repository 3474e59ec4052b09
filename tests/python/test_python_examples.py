"""The examples run as users run them: the notebook executed by nbconvert, the parameter-study
script as a program. Each reports its runs' energy budget, which must close (a residual far below
the 1e-4 that the budget tests of the command line allow for these runs' length)."""
import os
import re
import shutil
import subprocess
import sys

import pytest

from conftest import ROOT

EXAMPLES = os.path.join(ROOT, "examples")


def environment():
    import grainflow  # the package these tests import, for the kernel and the script as well
    env = dict(os.environ)
    env["GRAINFLOW_ROOT"] = ROOT
    package = os.path.dirname(os.path.dirname(os.path.abspath(grainflow.__file__)))
    env["PYTHONPATH"] = os.pathsep.join([package] + [p for p in env.get("PYTHONPATH", "").split(os.pathsep) if p])
    return env


def residuals(text):
    return [float(x) for x in re.findall(r"residual\s+([-+0-9.e]+)", text)]


def test_notebook_executes(tmp_path):
    if shutil.which("jupyter") is None:
        pytest.skip("jupyter-nbconvert is not installed (tools/install_deps.sh installs it)")
    shutil.copy(os.path.join(EXAMPLES, "chute_friction.ipynb"), tmp_path)
    env = environment()
    # The kernel's connection files and caches in the test's folder: HOME may not be writable.
    for name, folder in (("JUPYTER_RUNTIME_DIR", "runtime"), ("IPYTHONDIR", "ipython"), ("MPLCONFIGDIR", "mpl")):
        env[name] = str(tmp_path / folder)
    subprocess.run(["jupyter", "nbconvert", "--to", "notebook", "--execute", "chute_friction.ipynb",
                    "--output", "executed.ipynb", "--ExecutePreprocessor.timeout=600"],
                   cwd=tmp_path, env=env, check=True, capture_output=True, text=True)
    assert (tmp_path / "chute_profile.png").stat().st_size > 0
    import nbformat
    notebook = nbformat.read(str(tmp_path / "executed.ipynb"), as_version=4)
    printed = "".join(o.get("text", "") for c in notebook.cells if c.cell_type == "code" for o in c.outputs)
    found = residuals(printed)
    assert len(found) == 2 and all(abs(r) < 1e-6 for r in found), printed
    speeds = [float(x) for x in re.findall(r"mean speed down the slope ([-0-9.]+)", printed)]
    assert len(speeds) == 4 and all(s > 0.0 for s in speeds)   # 26 degrees: the grains flow


def test_parameter_study_script(tmp_path):
    result = subprocess.run([sys.executable, os.path.join(EXAMPLES, "friction_study.py"), "--duration", "10",
                             "--output", str(tmp_path)], env=environment(), check=True, capture_output=True, text=True)
    rows = [line.split() for line in result.stdout.splitlines()[1:] if line.strip()]
    assert [float(r[0]) for r in rows] == [0.3, 0.5, 0.8]
    assert all(abs(float(r[3])) < 1e-5 for r in rows), result.stdout
    for friction in ("0.3", "0.5", "0.8"):
        assert (tmp_path / f"mu_{friction}" / "summary.json").exists()
