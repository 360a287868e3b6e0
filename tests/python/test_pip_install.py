# `pip install .` from the tree installs the module and its stubs where pip is told, and it imports
# from there alone. The build folder under test is built on (BLEEDSIM_BUILD_DIR), so this takes
# seconds; a fresh configure and build, what a user's `pip install .` does, takes minutes on two
# cores and was run by hand (docs/python.md).
import os
import subprocess
import sys
import tomllib

from conftest import SOURCE


def test_pip_installs_the_module_and_its_stubs(tmp_path):
    target = tmp_path / "site"
    # setuptools' own build folder in the test's, not the tree's build/, where an earlier install's
    # files would be installed again.
    (tmp_path / "setuptools.cfg").write_text(f"[build]\nbuild_base = {tmp_path / 'setuptools-build'}\n")
    environment = {**os.environ, "BLEEDSIM_BUILD_DIR": os.environ["BLEEDSIM_BINARY_DIR"], "PIP_NO_CACHE_DIR": "1",
                   "DIST_EXTRA_CONFIG": str(tmp_path / "setuptools.cfg")}
    environment.pop("PYTHONPATH")
    installed = subprocess.run([sys.executable, "-m", "pip", "install", "--no-build-isolation", "--no-deps",
                                "--no-index", "--target", str(target), str(SOURCE)],
                               env=environment, capture_output=True, text=True, timeout=600)
    assert installed.returncode == 0, installed.stdout + installed.stderr
    assert (target / "bleedsim.pyi").read_text() == (SOURCE / "python" / "bleedsim.pyi").read_text()
    imported = subprocess.run([sys.executable, "-c", "import bleedsim; print(bleedsim.__file__, bleedsim.__version__)"],
                              env={**environment, "PYTHONPATH": str(target)}, cwd=tmp_path, capture_output=True,
                              text=True, timeout=60)
    assert imported.returncode == 0, imported.stderr
    path, version = imported.stdout.split()
    assert path.startswith(str(target))
    assert version == tomllib.loads((SOURCE / "pyproject.toml").read_text())["project"]["version"]
