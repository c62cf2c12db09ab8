"""The wheel's compiled parts, from CMake: setuptools (pyproject.toml) packs the Python sources;
this adds tcpmsim/_core (the module), tcpmsim/_bin/tcpmsim (the program, run by the console
script tcpmsim) and tcpmsim/lib/tcpmsim/tcpmsim_fmu.so (what export-fmu packs), built in
TCPMSIM_CMAKE_BUILD_DIR (default build/wheel: a Release tree of its own; give an existing
Release tree to pack what it built)."""
import glob
import os
import shutil
import subprocess
import sys

from setuptools import setup
from setuptools.command.build_py import build_py
from setuptools.dist import Distribution

ROOT = os.path.dirname(os.path.abspath(__file__))


class CMakeBuild(build_py):
    def run(self):
        super().run()
        tree = os.path.abspath(os.environ.get("TCPMSIM_CMAKE_BUILD_DIR",
                                              os.path.join(ROOT, "build", "wheel")))
        if not os.path.exists(os.path.join(tree, "CMakeCache.txt")):
            subprocess.check_call(["cmake", "-S", ROOT, "-B", tree, "-DCMAKE_BUILD_TYPE=Release",
                                   "-DTCPMSIM_BUILD_TESTS=OFF",
                                   f"-DPython3_EXECUTABLE={sys.executable}"])
        subprocess.check_call(["cmake", "--build", tree, "-j", str(os.cpu_count() or 1),
                               "--target", "tcpmsim", "tcpmsim_python", "tcpmsim_fmu"])
        package = os.path.join(self.build_lib, "tcpmsim")
        for core in glob.glob(os.path.join(tree, "python", "tcpmsim", "_core*.so")):
            shutil.copy2(core, package)
        for source, target in ((os.path.join(tree, "tcpmsim"), "_bin/tcpmsim"),
                               (os.path.join(tree, "fmu", "tcpmsim_fmu.so"),
                                "lib/tcpmsim/tcpmsim_fmu.so")):
            os.makedirs(os.path.dirname(os.path.join(package, target)), exist_ok=True)
            shutil.copy2(source, os.path.join(package, target))


class BinaryDistribution(Distribution):
    """A wheel for this platform and Python: it carries compiled code."""

    def has_ext_modules(self):
        return True


os.makedirs(os.path.join(ROOT, "build"), exist_ok=True)  # setuptools' metadata and staging go there
setup(cmdclass={"build_py": CMakeBuild}, distclass=BinaryDistribution,
      options={"build": {"build_base": os.path.join("build", "setuptools")},
               "egg_info": {"egg_base": os.path.join("build")}})
