"""Builds the raps package with libraps.so inside it.

The metadata is in pyproject.toml; this file adds what setuptools cannot say there: libraps is
compiled with CMake (a Release build of the library alone) and copied into the package as
raps/libraps.so, which raps/__init__.py loads before looking anywhere else. The sources come
from the repository this folder sits in (../..), or, in an sdist, from native/, where the sdist
command below copies them. The wheel is tagged for this platform (py3-none-linux_x86_64 and the
like): it holds a native library, but no Python extension, so any Python 3 can load it.

RAPS_SOURCE_DIR names the repository when this folder was copied elsewhere; RAPS_CMAKE_ARGS
adds arguments to the CMake configure step (for example a compiler launcher);
CMAKE_BUILD_PARALLEL_LEVEL sets the number of compile jobs (default: the processor count).
"""

import os
import re
import shlex
import shutil
import subprocess

from setuptools import Distribution, setup
from setuptools.command.build_py import build_py
from setuptools.command.sdist import sdist
from wheel.bdist_wheel import bdist_wheel

HERE = os.path.dirname(os.path.abspath(__file__))
# What a build of the library alone reads: the top-level CMakeLists.txt, its cmake/ templates,
# the public header and the library's sources.
NATIVE_PARTS = ["CMakeLists.txt", "cmake", "include", "src"]
BUNDLED_NAME = "libraps.so"


def native_sources():
    """The folder holding the library's CMake project: native/ in an sdist, else the checkout
    (RAPS_SOURCE_DIR, for a copy of this folder made elsewhere; else two folders up)."""
    checkout = os.environ.get("RAPS_SOURCE_DIR") or os.path.join(HERE, "..", "..")
    for root in (os.path.join(HERE, "native"), os.path.normpath(checkout)):
        if all(os.path.exists(os.path.join(root, part)) for part in NATIVE_PARTS):
            return root
    raise RuntimeError("raps: the library's sources are neither in native/ (an sdist) nor in "
                       "%s (a repository checkout); set RAPS_SOURCE_DIR to the raps repository"
                       % os.path.normpath(checkout))


def version():
    """raps.h's version, as the generated declarations carry it."""
    with open(os.path.join(HERE, "raps", "_native.py")) as stream:
        text = stream.read()
    parts = [re.search(r"^RAPS_VERSION_%s = (\d+)$" % p, text, re.M).group(1)
             for p in ("MAJOR", "MINOR", "PATCH")]
    return ".".join(parts)


class BuildWithLibrary(build_py):
    """Copies the Python files, then compiles libraps and puts it beside them."""

    def run(self):
        super().run()
        build_dir = os.path.join(os.path.abspath(self.get_finalized_command("build").build_temp),
                                 "libraps")
        configure = ["cmake", "-S", native_sources(), "-B", build_dir,
                     "-DCMAKE_BUILD_TYPE=Release", "-DBUILD_SHARED_LIBS=ON",
                     "-DRAPS_BUILD_TESTS=OFF", "-DRAPS_BUILD_SAMPLES=OFF",
                     "-DRAPS_BUILD_BENCH=OFF", "-DRAPS_BUILD_GLTF=OFF"]
        configure += shlex.split(os.environ.get("RAPS_CMAKE_ARGS", ""))
        jobs = os.environ.get("CMAKE_BUILD_PARALLEL_LEVEL") or str(os.cpu_count() or 1)
        self.spawn(configure)
        self.spawn(["cmake", "--build", build_dir, "--target", "raps", "--parallel", jobs])
        built = os.path.realpath(os.path.join(build_dir, "src", BUNDLED_NAME))
        target = os.path.join(self.build_lib, "raps", BUNDLED_NAME)
        self.mkpath(os.path.dirname(target))
        shutil.copyfile(built, target)


class SdistWithSources(sdist):
    """Adds the library's sources under native/, so that the sdist builds on its own."""

    def make_release_tree(self, base_dir, files):
        super().make_release_tree(base_dir, files)
        root = native_sources()
        for part in NATIVE_PARTS:
            source = os.path.join(root, part)
            target = os.path.join(base_dir, "native", part)
            if os.path.isdir(source):
                shutil.copytree(source, target,
                                ignore=shutil.ignore_patterns("__pycache__", "*.pyc"))
            else:
                self.mkpath(os.path.dirname(target))
                shutil.copyfile(source, target)


class PlatformWheel(bdist_wheel):
    """A platform wheel that any Python 3 can use: the library is loaded through ctypes."""

    def finalize_options(self):
        super().finalize_options()
        self.root_is_pure = False

    def get_tag(self):
        _, _, platform = super().get_tag()
        return "py3", "none", platform


class BinaryDistribution(Distribution):
    """Holds a native library, so installs go to platlib and the wheel is not 'any'."""

    def has_ext_modules(self):
        return True


setup(
    version=version(),
    distclass=BinaryDistribution,
    cmdclass={"build_py": BuildWithLibrary, "sdist": SdistWithSources,
              "bdist_wheel": PlatformWheel},
    package_data={"raps": [BUNDLED_NAME]},
)
