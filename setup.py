"""`pip install .`: the module `bleedsim` built by the project's CMake (pyproject.toml says why
setuptools), for the Python that runs pip, with the type stubs beside it."""
import os
import shlex
import shutil
import subprocess
import sys
from pathlib import Path

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

SOURCE = Path(__file__).resolve().parent


class CMakeBuild(build_ext):
    def build_extension(self, ext):
        # BLEEDSIM_BUILD_DIR: a build folder already configured (build/default) is built on, not made anew.
        given = os.environ.get("BLEEDSIM_BUILD_DIR")
        build = Path(given).resolve() if given else Path(self.build_temp).resolve() / "cmake"
        if not given:
            subprocess.run(["cmake", "-S", str(SOURCE), "-B", str(build), "-DCMAKE_BUILD_TYPE=Release",
                            "-DBLEEDSIM_TESTS=OFF", "-DBLEEDSIM_BENCH=OFF", "-DBLEEDSIM_PYTHON=ON",
                            f"-DPython3_EXECUTABLE={sys.executable}", "--log-level=NOTICE",
                            *shlex.split(os.environ.get("CMAKE_ARGS", ""))], check=True)
        subprocess.run(["cmake", "--build", str(build), "--target", "bleedsim_python",
                        "--parallel", str(os.cpu_count() or 1)], check=True)
        module = Path(self.get_ext_fullpath(ext.name))
        module.parent.mkdir(parents=True, exist_ok=True)
        built = build / "python" / module.name
        if not built.exists():
            sys.exit(f"setup.py: CMake built no {built.name} (configuring said why the module was skipped)")
        shutil.copyfile(built, module)
        shutil.copyfile(SOURCE / "python" / "bleedsim.pyi", module.parent / "bleedsim.pyi")


setup(ext_modules=[Extension("bleedsim", sources=[])], cmdclass={"build_ext": CMakeBuild})
