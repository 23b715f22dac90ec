"""`cmake --install` of the Python module: installed to a temporary prefix, imported from
there by Debian's /usr/bin/python3 (not from the build tree), and working with the
installed lib/slambox (renderer, MRPT plugin)."""
import os
import subprocess
import sys

import pytest

CHECK = r"""
import os, sys, slambox
prefix = sys.argv[1]
assert slambox.__file__.startswith(prefix + "/lib/python3/dist-packages/"), slambox.__file__
stream = slambox.simulate(slambox.load_scenario("loop", {"duration_s": 5}), seed=2)
r = slambox.run(stream, ["odometry"])
assert r["odometry"].status == "ok" and r["odometry"].metrics.ate_rmse_m > 0
mrpt = [m for m in slambox.algorithms() if m["name"] == "mrpt-icp-slam"]
assert mrpt and mrpt[0]["unavailable"] is None, mrpt      # PREFIX/lib/slambox/plugins found
rows = slambox.sweep({"scenarios": ["loop"], "algorithms": ["odometry"], "seeds": 1, "set": {"duration_s": 5}},
                     out=sys.argv[2], figures=True)
assert rows[0]["status"] == "ok" and os.path.exists(sys.argv[2] + "/report.html")  # PREFIX/lib/slambox renderer
print("installed module ok")
"""


def test_cmake_install_gives_an_importable_module(tmp_path):
    build = os.environ.get("SLAMBOX_BUILD_DIR")
    cmake = os.environ.get("SLAMBOX_CMAKE", "cmake")
    if not build:
        pytest.skip("SLAMBOX_BUILD_DIR is not set (CTest sets it)")
    prefix = tmp_path / "prefix"
    subprocess.run([cmake, "--install", build, "--prefix", str(prefix)], check=True, capture_output=True, text=True)
    assert (prefix / "lib/python3/dist-packages").is_dir()
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "SLAMBOX_BINARY")}
    env["PYTHONPATH"] = str(prefix / "lib/python3/dist-packages")
    r = subprocess.run(["/usr/bin/python3", "-c", CHECK, str(prefix), str(tmp_path / "sweep")], cwd=tmp_path, env=env,
                       capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    assert "installed module ok" in r.stdout
