"""`pip install .`: the extension _terratin is built by the project's own CMake (the release
settings, the Python module target only) for the interpreter pip runs, then packaged with
python/terratin. pyproject.toml holds the metadata; this file only drives CMake."""

import os
import pathlib
import re
import shutil
import subprocess
import sys

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = pathlib.Path(__file__).resolve().parent


def project_version():
    """The version of CMakeLists.txt's project(), the one the module reports."""
    text = (ROOT / "CMakeLists.txt").read_text()
    return re.search(r"project\(terratin VERSION ([0-9.]+)", text).group(1)


class CMakeExtension(Extension):
    def __init__(self, name):
        super().__init__(name, sources=[])


class CMakeBuild(build_ext):
    def build_extension(self, ext):
        # TERRATIN_CMAKE_BUILD_DIR: a build tree already configured for this interpreter (the
        # test suite's, which has built the libraries once already); else one of pip's own.
        reused = os.environ.get("TERRATIN_CMAKE_BUILD_DIR")
        build_dir = pathlib.Path(reused or pathlib.Path(self.build_temp).resolve() / "cmake")
        if not reused:
            self.configure(build_dir)
        subprocess.run(
            ["cmake", "--build", str(build_dir), "--target", "_terratin", "--parallel"],
            check=True,
        )
        built = next((build_dir / "python" / "terratin").glob("_terratin*.so"))
        target = pathlib.Path(self.get_ext_fullpath(ext.name))
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(built, target)

    @staticmethod
    def configure(build_dir):
        generator = ["-G", "Ninja"] if shutil.which("ninja") else []
        subprocess.run(
            ["cmake", "-S", str(ROOT), "-B", str(build_dir), *generator,
             "-DCMAKE_BUILD_TYPE=Release", "-DTERRATIN_BUILD_TESTS=OFF",
             "-DTERRATIN_BUILD_TOOLS=OFF", "-DTERRATIN_INSTALL=OFF",
             "-DTERRATIN_BUILD_PYTHON=ON", f"-DPython3_EXECUTABLE={sys.executable}"],
            check=True,
        )


setup(
    version=project_version(),
    packages=["terratin"],
    package_dir={"": "python"},
    ext_modules=[CMakeExtension("terratin._terratin")],
    cmdclass={"build_ext": CMakeBuild},
)
