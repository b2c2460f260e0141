"""Builds the compiled part of the Python module with CMake (pyproject.toml holds the metadata).

The module, the libraries it loads, the assimp plugin and the ``massprops`` command (for
``python -m massprops``) are installed into the package, found relative to one another:
massprops/_core*.so, massprops/_libs/, massprops/_libs/massprops/, massprops/_bin/. The CMake build
is kept in build-pip/, beside build/ (at the same depth, so that ccache, with paths relative to the
checkout, reuses build/'s compilations).
"""

import os
import shutil
import subprocess
import sys
from pathlib import Path

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = Path(__file__).resolve().parent


class CMakeBuild(build_ext):
    """Runs CMake instead of compiling the (placeholder) extension itself."""

    def build_extension(self, ext):
        build = ROOT / "build-pip"  # beside build/, at the same depth: ccache finds the same compilations
        stage = build / "stage"
        env = dict(os.environ)
        env.setdefault("CCACHE_BASEDIR", str(ROOT))
        env.setdefault("CCACHE_NOHASHDIR", "1")
        configure = [
            "cmake", "-S", str(ROOT), "-B", str(build), "-G", "Ninja", "-DCMAKE_BUILD_TYPE=Release",
            "-DMASSPROPS_BUILD_TESTS=OFF", "-DMASSPROPS_BUILD_BENCH=OFF", "-DMASSPROPS_BUILD_APPS=ON",
            "-DMASSPROPS_BUILD_PYTHON=ON", f"-DPython_EXECUTABLE={sys.executable}",
            "-DCMAKE_INSTALL_LIBDIR=massprops/_libs", "-DCMAKE_INSTALL_BINDIR=massprops/_bin",
            "-DMASSPROPS_PYTHON_INSTALL_DIR=.", "-DCMAKE_INSTALL_RPATH=$ORIGIN/../_libs;$ORIGIN",
        ]
        subprocess.run(configure, check=True, env=env, stdout=subprocess.DEVNULL)
        jobs = str(os.cpu_count() or 1)
        subprocess.run(["cmake", "--build", str(build), "-j", jobs], check=True, env=env)
        if stage.exists():
            shutil.rmtree(stage)
        subprocess.run(["cmake", "--install", str(build), "--prefix", str(stage)], check=True, env=env,
                       stdout=subprocess.DEVNULL)
        target = Path(self.build_lib) / "massprops"
        shutil.rmtree(stage / "massprops" / "_libs" / "cmake", ignore_errors=True)
        shutil.copytree(stage / "massprops", target, symlinks=True, dirs_exist_ok=True)


setup(
    ext_modules=[Extension("massprops._core", sources=[])],
    cmdclass={"build_ext": CMakeBuild},
    options={"build": {"build_base": str(Path("build-pip") / "setuptools")}},
)
