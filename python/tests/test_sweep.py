"""Tests of slambox.sweep / read_results / register (python/README.md): the CLI's sweep code
driven from Python, with Python modules in forked runs."""
import json
import math
import os

import numpy as np
import pytest

import slambox
from example_modules import DeadReckoning, Raising

# Run times differ between any two runs; results.csv holds only deterministic metrics.
SPEC = {
    "scenarios": ["loop", "landmarks"],
    "algorithms": ["odometry", "ekf-slam"],
    "seeds": 2,
    "set": {"duration_s": 15},
    "grid": {"sensors.landmarks.sigma_range_m": [0.05, 0.1]},
}


def test_sweep_of_a_dict_writes_the_cli_sweep_folder(tmp_path, cli):
    spec = dict(SPEC, scenarios=["landmarks"])
    rows = slambox.sweep(spec, out=str(tmp_path / "py"), jobs=2)
    # The same spec as a sweep file through the CLI: the same results.csv and summary.md, byte for byte.
    (tmp_path / "s.yaml").write_text(json.dumps(spec))
    cli("sweep", tmp_path / "s.yaml", "-j", 2, "--no-figures", "-o", tmp_path / "cli")
    for name in ("results.csv", "summary.md"):
        assert (tmp_path / "py" / name).read_bytes() == (tmp_path / "cli" / name).read_bytes(), name
    assert len(rows) == 2 * 2 * 2  # grid points x seeds x algorithms
    assert {r["algorithm"] for r in rows} == {"odometry", "ekf-slam"} and all(r["status"] == "ok" for r in rows)
    assert rows == slambox.read_results(str(tmp_path / "py" / "results.csv"))
    ekf = [r for r in rows if r["algorithm"] == "ekf-slam"]
    assert all(r["landmark_rmse_m"] is not None and r["ate_rmse_m"] < 0.5 for r in ekf)
    assert all(r["landmark_rmse_m"] is None for r in rows if r["algorithm"] == "odometry")  # null stays None


def test_a_python_module_in_a_forked_sweep_equals_the_cpp_one(tmp_path):
    out = str(tmp_path / "s")
    spec = {"scenarios": ["loop"], "algorithms": ["odometry", DeadReckoning], "seeds": [0, 3, 5],
            "set": {"duration_s": 20}}
    rows = slambox.sweep(spec, out=out, jobs=2)
    assert len(rows) == 6 and all(r["status"] == "ok" for r in rows)
    # Every metric but the consistency ones (the C++ module also propagates a covariance).
    metrics = [k for k in rows[0] if k not in ("run_id", "algorithm", "status") and "nees" not in k]
    for seed in (0, 3, 5):
        cpp, py = (next(r for r in rows if r["seed"] == seed and r["algorithm"] == a) for a in ("odometry", "py-odometry"))
        assert cpp["ate_rmse_m"] > 0.01
        assert {k: cpp[k] for k in metrics} == {k: py[k] for k in metrics}, seed
    # Resumable: a second call refuses the folder, with resume=True it runs nothing again.
    stamps = {p: os.stat(os.path.join(out, "runs", p, "metrics.json")).st_mtime_ns for p in os.listdir(out + "/runs")}
    with pytest.raises(slambox.InputError, match="already holds results"):
        slambox.sweep(spec, out=out, jobs=2)
    assert slambox.sweep(spec, out=out, jobs=2, resume=True) == rows
    assert stamps == {p: os.stat(os.path.join(out, "runs", p, "metrics.json")).st_mtime_ns for p in stamps}


def test_a_raising_python_module_fails_alone_in_a_sweep(tmp_path):
    rows = slambox.sweep({"scenarios": ["loop"], "algorithms": ["odometry", Raising], "seeds": 1,
                          "set": {"duration_s": 10}}, out=str(tmp_path / "s"), jobs=1)
    by = {r["algorithm"]: r for r in rows}
    assert by["odometry"]["status"] == "ok" and by["odometry"]["ate_rmse_m"] is not None
    assert by["py-raising"]["status"] == "failed" and by["py-raising"]["ate_rmse_m"] is None
    run = json.loads(open(os.path.join(tmp_path, "s", "runs", rows[0]["run_id"], "metrics.json")).read())
    assert run["algorithms"]["py-raising"]["reason"].endswith("ZeroDivisionError: planted at event 100")


def test_a_sweep_file_names_registered_python_modules(tmp_path):
    f = tmp_path / "sweep.yaml"
    f.write_text("scenarios: [loop]\nalgorithms: [py-odometry]\nseeds: 2\nset: {duration_s: 10}\n"
                 "grid:\n  sensors.lidar.sigma_range_m: [0.01, 0.05]\n")
    a = slambox.sweep(str(f), out=str(tmp_path / "s"), jobs=2, modules=[DeadReckoning], as_array=True)
    assert isinstance(a, np.ndarray) and a.shape == (4,) and a.dtype["sensors.lidar.sigma_range_m"] == np.float64
    assert sorted(a["sensors.lidar.sigma_range_m"]) == [0.01, 0.01, 0.05, 0.05]
    assert set(a["algorithm"]) == {"py-odometry"} and np.all(a["ate_rmse_m"] > 0) and np.all(np.isnan(a["anees"]))  # no covariance: NaN
    assert (tmp_path / "s" / "sweep.yaml").read_text() == f.read_text()  # what `sweep --merge` reads back
    assert any(m["name"] == "py-odometry" and m["origin"].startswith("Python class") for m in slambox.algorithms())
    named_only = {m["name"] for m in slambox.algorithms() if not m["in_all"]}  # ModuleInfo::in_all
    assert "py-odometry" not in named_only and named_only <= {"mrpt-graphslam"}, named_only


def test_bad_sweeps_raise_before_any_run(tmp_path):
    out = tmp_path / "s"
    with pytest.raises(slambox.InputError, match="unknown key|seedz"):
        slambox.sweep({"scenarios": ["loop"], "algorithms": ["odometry"], "seedz": 2}, out=str(out))
    with pytest.raises(slambox.InputError, match="no-such-module"):
        slambox.sweep({"scenarios": ["loop"], "algorithms": ["no-such-module"], "seeds": 1}, out=str(out))
    with pytest.raises(slambox.InputError, match="has no options"):
        slambox.sweep({"scenarios": ["loop"], "algorithms": [DeadReckoning], "seeds": 1,
                       "set": {"algo.py-odometry.alpha": 1}}, out=str(out))
    with pytest.raises(TypeError, match="subclass of slambox.Module"):
        slambox.register(DeadReckoning())
    assert not out.exists() or not any((out / "runs").glob("*/metrics.json"))
