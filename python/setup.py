"""pip install ./python (or pip wheel ./python) from a kcreep source tree:
builds libkcreep.so with CMake from the tree around this folder and puts
it inside the package, so that `import kcreep` needs no setting. The
system libraries it links (OpenBLAS/LAPACK, FFTW, the gfortran runtime,
OpenMP) are the ones scripts/setup.sh installs."""
import glob
import os
import shutil
import subprocess

from setuptools import setup
from setuptools.command.build_py import build_py
from setuptools.dist import Distribution

SOURCE = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


class BuildWithLibrary(build_py):
    """The Python files, then libkcreep.so built in the build folder."""

    def run(self):
        super().run()
        if not os.path.exists(os.path.join(SOURCE, "CMakeLists.txt")):
            raise RuntimeError(f"kcreep: no CMakeLists.txt in {SOURCE}: install from a kcreep source tree")
        build = os.path.join(os.path.abspath(self.get_finalized_command("build").build_temp), "libkcreep")
        for cmd in (["cmake", "-S", SOURCE, "-B", build, "-DCMAKE_BUILD_TYPE=Release", "-DBUILD_TESTING=OFF"],
                    ["cmake", "--build", build, "--target", "kcreep_shared", "-j", str(os.cpu_count() or 1)]):
            subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
        library = sorted(glob.glob(os.path.join(build, "libkcreep.so.*.*")))[-1]   # the file, not its links
        shutil.copyfile(library, os.path.join(self.build_lib, "kcreep", "libkcreep.so"))


class BinaryDistribution(Distribution):
    """A wheel for this platform: it carries a compiled library."""

    def has_ext_modules(self):
        return True


setup(cmdclass={"build_py": BuildWithLibrary}, distclass=BinaryDistribution)
