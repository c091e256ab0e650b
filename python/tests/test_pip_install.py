"""`pip install .` as docs/python.md tells a Debian user without internet to run it: a venv
that sees the system's packages (NumPy), pip without build isolation. The extension is built
in the suite's own build tree (TERRATIN_CMAKE_BUILD_DIR), which the suite has compiled once
already; everything else is what a user's install does."""

import os
import pathlib
import subprocess
import sys

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]


@pytest.mark.skipif(
    not os.environ.get("TERRATIN_CMAKE_BUILD_DIR"), reason="run by ctest, which names the build"
)
def test_pip_install_in_a_system_site_packages_venv_gives_an_importable_module(tmp_path):
    venv = tmp_path / "venv"
    subprocess.run([sys.executable, "-m", "venv", "--system-site-packages", str(venv)], check=True)
    python = venv / "bin" / "python"
    environment = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    installed = subprocess.run(
        [str(python), "-m", "pip", "install", "--no-build-isolation", "--no-index", "-q", str(ROOT)],
        env=environment, capture_output=True, text=True,
    )
    assert installed.returncode == 0, installed.stdout + installed.stderr
    # Imported from elsewhere, the module is the venv's, and it works.
    script = (
        "import numpy, terratin; "
        "v, t = terratin.triangulate(numpy.random.default_rng(1).random((100, 2))); "
        "print(terratin.__file__, terratin.__version__, len(t))"
    )
    run = subprocess.run(
        [str(python), "-c", script], cwd=tmp_path, env=environment, capture_output=True, text=True
    )
    assert run.returncode == 0, run.stderr
    module_file, version, triangles = run.stdout.split()
    assert pathlib.Path(module_file).is_relative_to(venv)
    cmake = (ROOT / "CMakeLists.txt").read_text()
    assert f"project(terratin VERSION {version} " in cmake
    assert int(triangles) > 150
