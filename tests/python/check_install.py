"""The package as pip installs it (pyproject.toml, setup.py): into a fresh virtual environment (Debian's NumPy
from the system's site packages; no network, no build isolation), then imported from outside the source and build
trees.
    check_install.py SOURCE_DIR BUILD_DIR WORK_DIR
installs from this build tree's CMake build (CCAL_CMAKE_BUILD_DIR); also the wheel: its platform tag and its files.
    check_install.py --clean-clone SOURCE_DIR BUILD_DIR WORK_DIR
installs from a `git clone` of SOURCE_DIR (its committed files only) without CCAL_CMAKE_BUILD_DIR, so that
setup.py configures and builds with CMake itself, as `pip install .` of a fresh checkout does; through ccache
(CMAKE_CXX_COMPILER_LAUNCHER, which CMake reads from the environment) when it is installed, with the clone as
CCACHE_BASEDIR, so that a second run compiles nothing. It prints how long the install took.
Exit 77 (skipped) when Debian's venv or pip is missing (python3-venv, python3-pip), or git for --clean-clone."""

import os
import re
import shutil
import subprocess
import sys
import time
import zipfile


def run(*args, env=None, cwd=None):
    r = subprocess.run(list(args), capture_output=True, text=True, env=env, cwd=cwd)
    if r.returncode != 0:
        sys.exit(f"failed ({r.returncode}): {' '.join(args)}\n{r.stdout[-3000:]}\n{r.stderr[-3000:]}")
    return r.stdout


def clean_clone_environment(source, work, env):
    """A clone of SOURCE's committed files in WORK/clone, and the environment of a build by setup.py's own CMake
    configure: no CCAL_CMAKE_BUILD_DIR; ccache and Ninja when they are installed."""
    clone = os.path.join(work, "clone")
    run("git", "clone", "--quiet", source, clone, cwd=work)
    env.pop("CCAL_CMAKE_BUILD_DIR", None)
    if shutil.which("ccache"):
        # Paths below the clone hashed relative to it: a clone in another folder finds the same cache entries.
        env.update(CMAKE_CXX_COMPILER_LAUNCHER="ccache", CCACHE_BASEDIR=clone)
    if shutil.which("ninja"):
        env["CMAKE_GENERATOR"] = "Ninja"
    return clone


def main(source, build, work, clean_clone=False):
    python = "/usr/bin/python3"
    for module in ("venv", "pip", "setuptools", "wheel"):
        if subprocess.run([python, "-c", f"import {module}"], capture_output=True).returncode != 0:
            print(f"skipped: Debian's {python} has no {module} (python3-venv, python3-pip, python3-wheel)")
            return 77
    if clean_clone and not shutil.which("git"):
        print("skipped: no git to clone the sources with")
        return 77
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    venv = os.path.join(work, "venv")
    run(python, "-m", "venv", "--system-site-packages", venv)
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "PYTHONHOME")}
    env.update(CCAL_CMAKE_BUILD_DIR=build, CMAKE_BUILD_PARALLEL_LEVEL="2", PIP_NO_INDEX="1")
    pip = os.path.join(venv, "bin", "pip")
    if clean_clone:
        source = clean_clone_environment(source, work, env)
    start = time.monotonic()
    run(pip, "install", "--no-build-isolation", "--no-deps", source, env=env, cwd=work)
    print(f"pip install took {time.monotonic() - start:.0f} s")
    wheels = os.path.join(work, "wheels")
    if not clean_clone:
        run(pip, "wheel", "--no-build-isolation", "--no-deps", "-w", wheels, source, env=env, cwd=work)

    problems = []
    version = re.search(r"project\(ccal VERSION (\d+\.\d+\.\d+)",
                        open(os.path.join(source, "CMakeLists.txt"), encoding="utf-8").read()).group(1)
    # Imported from the virtual environment, not from the source or the build tree.
    probe = ("import ccal, importlib.metadata, os, json\n"
             "b = ccal.budget(ccal.bundled_example())\n"
             "print(json.dumps({'file': ccal.__file__, 'version': importlib.metadata.version('ccal'),\n"
             "  'files': sorted(os.listdir(os.path.dirname(ccal.__file__))),\n"
             "  'budget': json.loads(b.to_json())['coefficients']}))\n")
    import json
    installed = json.loads(run(os.path.join(venv, "bin", "python"), "-c", probe, env=env, cwd=work))
    if not installed["file"].startswith(os.path.realpath(venv)) and not installed["file"].startswith(venv):
        problems.append(f"ccal imported from {installed['file']}, not from the virtual environment")
    if installed["version"] != version:
        problems.append(f"installed version {installed['version']}, the project's is {version}")
    for needed in ("__init__.py", "__init__.pyi", "py.typed", "_results.py"):
        if needed not in installed["files"]:
            problems.append(f"the installed package has no {needed}: {installed['files']}")
    if not any(f.startswith("_ccal.") and f.endswith(".so") for f in installed["files"]):
        problems.append(f"the installed package has no compiled module: {installed['files']}")
    # The same numbers as the build tree's module (the same compiled code: equal to the last bit).
    tree_env = dict(env, PYTHONPATH=os.path.join(build, "python"))
    in_tree = json.loads(run(python, "-c", probe, env=tree_env, cwd=work))
    if installed["budget"] != in_tree["budget"]:
        problems.append("the installed module's budget differs from the build tree's")
    if clean_clone:  # setup.py's own CMake tree, in the clone's build folder (setup.cfg)
        if not any("CMakeCache.txt" in files for _, _, files in os.walk(os.path.join(source, "build", "python-package"))):
            problems.append("setup.py configured no CMake tree of its own in the clone's build/python-package")
        return report(problems, installed)
    # The wheel: for this interpreter and platform (it holds compiled code), with the module and the stubs.
    built = os.listdir(wheels)
    tag = f"cp{sys.version_info.major}{sys.version_info.minor}"
    if len(built) != 1 or not re.fullmatch(rf"ccal-{re.escape(version)}-{tag}-{tag}-linux_\w+\.whl", built[0]):
        problems.append(f"the wheel is {built}, expected ccal-{version}-{tag}-{tag}-linux_<arch>.whl")
    else:
        names = zipfile.ZipFile(os.path.join(wheels, built[0])).namelist()
        for needed in ("ccal/__init__.py", "ccal/__init__.pyi", "ccal/py.typed"):
            if needed not in names:
                problems.append(f"the wheel has no {needed}")
        if not any(re.fullmatch(r"ccal/_ccal\..*\.so", n) for n in names):
            problems.append("the wheel has no compiled module")
        if not any(n.endswith(".dist-info/METADATA") for n in names):
            problems.append("the wheel has no METADATA")
    # Nothing left in the source tree (setuptools' folders are in the build tree).
    for stray in ("ccal.egg-info", "python/ccal.egg-info"):
        if os.path.exists(os.path.join(source, stray)):
            problems.append(f"the build left {stray} in the source tree")
    return report(problems, installed)


def report(problems, installed):
    for p in problems:
        print(p, file=sys.stderr)
    print(f"installed {installed['file']}, {len(problems)} problems")
    return 1 if problems else 0


if __name__ == "__main__":
    arguments = sys.argv[1:]
    clean = arguments[:1] == ["--clean-clone"]
    if len(arguments) != 3 + clean:
        sys.exit("usage: check_install.py [--clean-clone] SOURCE_DIR BUILD_DIR WORK_DIR")
    sys.exit(main(*[os.path.abspath(a) for a in arguments[clean:]], clean_clone=clean))
