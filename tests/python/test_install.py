"""cmake --install puts an importable package under the prefix."""

import glob
import os
import subprocess
import sys

from conftest import BINARY_DIR


def test_installed_package_imports_and_runs(tmp_path):
    prefix = str(tmp_path / "prefix")
    subprocess.run(["cmake", "--install", BINARY_DIR, "--prefix", prefix],
                   check=True, capture_output=True)
    found = glob.glob(os.path.join(prefix, "lib", "python3*", "*-packages",
                                   "mrsim", "__init__.py"))
    assert len(found) == 1, found
    site = os.path.dirname(os.path.dirname(found[0]))
    assert glob.glob(os.path.join(site, "mrsim", "_core*.so"))
    assert os.path.exists(os.path.join(site, "mrsim", "_core.pyi"))
    env = dict(os.environ, PYTHONPATH=site)
    out = subprocess.run(
        [sys.executable, "-c",
         "import mrsim, os; assert mrsim.__file__.startswith(%r); "
         "s = mrsim.Simulation(mrsim.Scenario.chain(modules=3)); s.step(5); "
         "print(s.time)" % site],
        env=env, capture_output=True, text=True, check=True).stdout
    assert float(out) > 0
