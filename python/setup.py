"""Builds the `actuator` module with the project's CMake build and packages it as a wheel.

The build folder is ACTUATOR_BUILD_DIR when set, else the checkout's build/ (configured and built
here, Release, when it holds no module yet). The wheel holds the module and, in actuator.libs/, the
renderer's GL backends and the optimizers it loads on first use. Nothing is downloaded: CMake finds
Debian's packages.
"""
import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent


def build_dir():
    given = os.environ.get("ACTUATOR_BUILD_DIR")
    return Path(given).resolve() if given else ROOT / "build"


def version():
    match = re.search(r"project\(ActuatorWorkbench VERSION ([0-9.]+)", (ROOT / "CMakeLists.txt").read_text())
    if not match:
        raise RuntimeError("CMakeLists.txt: no project version")
    return match.group(1)


class CMakeBuild(build_ext):
    """The extension is CMake's target actuator_python (and the GL backends); this copies them in."""

    def run(self):
        build = build_dir()
        module = self.built_module(build)
        if module is None:
            print(f"actuator: building the module with CMake in {build}", file=sys.stderr)
            subprocess.run(["cmake", "-S", str(ROOT), "-B", str(build), "-DCMAKE_BUILD_TYPE=Release",
                            f"-DPython_EXECUTABLE={sys.executable}"], check=True)
            jobs = str(os.cpu_count() or 2)
            subprocess.run(["cmake", "--build", str(build), "--parallel", jobs, "--target",
                            "actuator_python", "actuator_render_osmesa", "actuator_render_egl", "actuator_optimizer"], check=True)
            module = self.built_module(build)
            if module is None:
                raise RuntimeError(f"CMake built no module for this Python in {build / 'python'}")
        target = Path(self.get_ext_fullpath("actuator"))
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copy2(module, target)
        libs = target.parent / "actuator.libs"
        libs.mkdir(exist_ok=True)
        for loaded in sorted((build / "lib" / "actuator").glob("libactuator_*.so")):  # the GL backends, the optimizers
            shutil.copy2(loaded, libs / loaded.name)

    def built_module(self, build):
        suffix = self.get_ext_filename("actuator")  # actuator.cpython-311-x86_64-linux-gnu.so for this interpreter
        module = build / "python" / Path(suffix).name
        return module if module.exists() and (build / "lib" / "actuator").is_dir() else None


build_dir().mkdir(parents=True, exist_ok=True)
setup(
    version=version(),
    ext_modules=[Extension("actuator", sources=[])],
    cmdclass={"build_ext": CMakeBuild},
    # setuptools' own build files go under the CMake build, not into the checkout.
    options={"build": {"build_base": str(build_dir() / "python-wheel")}, "egg_info": {"egg_base": str(build_dir())}},
    zip_safe=False,
)
