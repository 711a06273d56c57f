"""Builds the extension stepzip._stepzip with the project's CMake build (the
library and python/_stepzip.cpp), so that pip and CMake compile the same way.
Metadata is in pyproject.toml. Environment: STEPZIP_CMAKE_ARGS adds CMake
arguments; ccache is used when it is installed."""
import os
import shutil
import subprocess
import sys
from pathlib import Path

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = Path(__file__).resolve().parent


class CMakeBuild(build_ext):
    def build_extension(self, ext):
        build_dir = Path(self.build_temp).resolve() / "cmake"
        package_dir = build_dir / "package"
        args = [
            "cmake", "-S", str(ROOT), "-B", str(build_dir),
            "-DCMAKE_BUILD_TYPE=Release",
            "-DSTEPZIP_BUILD_PYTHON=ON", "-DSTEPZIP_BUILD_TESTS=OFF", "-DSTEPZIP_BUILD_BENCH=OFF",
            "-DSTEPZIP_BUILD_CLI=OFF", "-DSTEPZIP_BUILD_EXAMPLES=OFF",
            f"-DSTEPZIP_PYTHON3={sys.executable}", f"-DPYTHON_EXECUTABLE={sys.executable}",
            f"-DSTEPZIP_PYTHON_PACKAGE_DIR={package_dir}",
        ]
        if shutil.which("ccache"):
            args += ["-DCMAKE_CXX_COMPILER_LAUNCHER=ccache", "-DCMAKE_C_COMPILER_LAUNCHER=ccache"]
        args += os.environ.get("STEPZIP_CMAKE_ARGS", "").split()
        subprocess.check_call(args)
        jobs = str(min(os.cpu_count() or 1, 4))
        subprocess.check_call(["cmake", "--build", str(build_dir), "--target", "stepzip_python",
                               "-j", jobs])
        built = sorted((package_dir / "stepzip").glob("_stepzip*.so"))
        if len(built) != 1:
            raise RuntimeError(f"expected one _stepzip module in {package_dir / 'stepzip'}, found {built}")
        target = Path(self.get_ext_fullpath(ext.name))
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(built[0], target)


setup(
    ext_modules=[Extension("stepzip._stepzip", sources=[])],
    cmdclass={"build_ext": CMakeBuild},
    options={"build": {"build_base": "build-python"}},
)
