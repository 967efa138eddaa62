"""The Python package ccal as setuptools builds it (pyproject.toml): CMake configures and builds the target
ccal_python (python/CMakeLists.txt), which lays the package out in <cmake tree>/python/ccal (the Python modules,
the compiled ccal._ccal, the type stubs as __init__.pyi and py.typed), and this copies that folder into the
package. The CMake tree is a folder of setuptools' own, or CCAL_CMAKE_BUILD_DIR: an existing build tree of the
project (bash scripts/setup.sh's ./build), which then only brings its module up to date."""

import os
import pathlib
import re
import shutil
import subprocess
import sys

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

SOURCE = pathlib.Path(__file__).resolve().parent
# setup.cfg's folder for setuptools' own files, which egg_info wants to exist.
(SOURCE / "build" / "python-package").mkdir(parents=True, exist_ok=True)


def project_version():
    """The version of CMakeLists.txt's project(), the one home of the version."""
    text = (SOURCE / "CMakeLists.txt").read_text(encoding="utf-8")
    found = re.search(r"project\(ccal VERSION (\d+\.\d+\.\d+)", text)
    if not found:
        sys.exit("setup.py: CMakeLists.txt has no 'project(ccal VERSION x.y.z'")
    return found.group(1)


class CMakePackage(build_ext):
    """Builds ccal._ccal with CMake and copies the package CMake lays out beside it."""

    def build_extension(self, ext):
        tree = os.environ.get("CCAL_CMAKE_BUILD_DIR")
        if tree:
            tree = pathlib.Path(tree).resolve()
        else:
            tree = pathlib.Path(self.build_temp).resolve() / "cmake"
            subprocess.run(["cmake", "-S", str(SOURCE), "-B", str(tree), "-DCMAKE_BUILD_TYPE=Release",
                            "-DCCAL_BUILD_TESTS=OFF", "-DCCAL_BUILD_BENCH=OFF", "-DCCAL_BUILD_PYTHON=ON",
                            f"-DPython_EXECUTABLE={sys.executable}"], check=True)
        jobs = os.environ.get("CMAKE_BUILD_PARALLEL_LEVEL") or str(os.cpu_count() or 1)
        subprocess.run(["cmake", "--build", str(tree), "--target", "ccal_python", "-j", jobs], check=True)
        built = tree / "python" / "ccal"
        if not any(built.glob("_ccal*.so")):
            sys.exit(f"setup.py: CMake built no module into {built} (is pybind11-dev, python3-dev and "
                     "python3-numpy installed? bash scripts/setup.sh installs them)")
        target = pathlib.Path(self.get_ext_fullpath(ext.name)).parent
        target.mkdir(parents=True, exist_ok=True)
        # setuptools keeps its build folder between builds: what an earlier build copied goes first, so that the
        # package holds this build's files only (the Python sources build_py put there stay).
        for item in target.iterdir():
            if item.is_file() and not (SOURCE / "python" / "ccal" / item.name).is_file():
                item.unlink()
        for item in built.iterdir():
            if item.is_file():
                shutil.copy2(item, target / item.name)


setup(
    version=project_version(),
    packages=["ccal"],
    package_dir={"ccal": "python/ccal"},
    ext_modules=[Extension("ccal._ccal", sources=[])],
    cmdclass={"build_ext": CMakePackage},
    zip_safe=False,
)
