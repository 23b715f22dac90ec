"""Tests of the Python module `slambox` (python/README.md). Run by CTest as
`/usr/bin/python3 -m pytest python/tests/test_slambox.py::NAME`, one test per function."""
import json
import math
import re

import numpy as np
import pytest

import slambox
from example_modules import DeadReckoning

# Timings differ between any two runs; every other metric must be bit-identical.
TIMING_KEYS = {"runtime_s", "realtime_factor", "step_time_median_s", "step_time_p95_s", "step_time_max_s"}
SHORT = {"duration_s": 30}  # 30 s of `loop`: quick, yet ICP, scans and odometry all work


def deterministic(metrics):
    return {k: v for k, v in metrics.items() if k not in TIMING_KEYS}


def test_scenarios_lists_the_builtins():
    s = slambox.scenarios()
    assert "loop" in s and isinstance(s["loop"], str) and s["loop"]


def test_load_scenario_applies_overrides():
    sc = slambox.load_scenario("loop", {"duration_s": 12.5, "sensors.lidar.sigma_range_m": 0.05})
    assert sc.name == "loop" and sc.duration_s == 12.5 and "sigma_range_m: 0.05" in sc.yaml


def test_bad_scenario_raises_input_error_with_file_and_line(tmp_path, cli):
    good = slambox.load_scenario("loop").yaml.splitlines()
    line = next(i for i, l in enumerate(good) if "sigma_range_m" in l)
    good[line] = re.sub(r"sigma_range_m: *[-+0-9.eE]+", "sigma_range_m: -1", good[line])
    bad = tmp_path / "bad.yaml"
    bad.write_text("\n".join(good) + "\n")
    with pytest.raises(slambox.InputError) as e:
        slambox.load_scenario(str(bad))
    assert isinstance(e.value, ValueError)
    assert e.value.file == str(bad) and e.value.line == line + 1
    # The same message the CLI prints.
    r = cli("simulate", bad, "-o", tmp_path / "s.slbx", check=False)
    assert r.returncode != 0 and str(e.value) in r.stderr
    with pytest.raises(slambox.InputError):
        slambox.load_scenario("loop", {"no_such_key": 1})


def test_simulate_is_deterministic_and_arrays_have_the_documented_shapes():
    a = slambox.simulate(slambox.load_scenario("loop", SHORT), seed=4)
    b = slambox.simulate(slambox.load_scenario("loop", SHORT), seed=4)
    c = slambox.simulate(slambox.load_scenario("loop", SHORT), seed=5)
    h = a.header
    assert h["scenario_name"] == "loop" and h["seed"] == 4 and h["duration_s"] == pytest.approx(30.0)
    beams = h["sensors"]["lidar"]["beams"]
    assert a.odometry.shape[1] == 4 and len(a.odometry) == pytest.approx(30 * 50, abs=2)
    assert a.scan_ranges.shape == (len(a.scan_times), beams) and a.scan_valid.dtype == np.bool_
    assert len(a.scan_times) == pytest.approx(30 * 10, abs=2)
    assert a.groundtruth.shape[1] == 4 and np.all(np.diff(a.groundtruth[:, 0]) > 0)
    assert np.all(np.diff(a.odometry[:, 0]) > 0) and np.all(np.diff(a.scan_times) > 0)
    assert a.landmarks.shape == (0, 4) and a.gyro.shape == (0, 2)  # loop has neither sensor
    # invalid beams report range_max_m (never a fake hit)
    assert np.all(a.scan_ranges[~a.scan_valid] == h["sensors"]["lidar"]["range_max_m"])
    assert len(a) == len(a.odometry) + len(a.scan_times)
    for name in ("odometry", "scan_times", "scan_ranges", "scan_valid", "groundtruth"):
        assert np.array_equal(getattr(a, name), getattr(b, name)), name
    assert not np.array_equal(a.scan_ranges, c.scan_ranges)
    assert a.odometry is a.odometry  # built once, cached


def test_landmark_arrays_are_one_row_per_observation():
    s = slambox.simulate("landmarks" if "landmarks" in slambox.scenarios() else "loop", seed=1)
    if s.header["sensors"].get("landmarks") is None:
        pytest.skip("no built-in landmark scenario")
    lm = s.landmarks
    assert lm.shape[1] == 4 and len(lm) > 0
    assert np.all(np.diff(lm[:, 0]) >= 0)
    assert np.all((lm[:, 2] >= -math.pi) & (lm[:, 2] < math.pi))
    cfg = s.header["sensors"]["landmarks"]  # true range within range_max_m, plus range noise
    assert np.all(lm[:, 1] <= cfg["range_max_m"] + 6 * cfg["sigma_range_m"])
    assert np.all(lm[:, 3] == np.round(lm[:, 3]))


def test_stream_write_is_the_cli_stream_and_reads_back(tmp_path, cli):
    s = slambox.simulate(slambox.load_scenario("loop", SHORT), seed=7)
    s.write(str(tmp_path / "py.slbx"))
    cli("simulate", "loop", "--seed", 7, "--set", "duration_s=30", "-o", tmp_path / "cli.slbx")
    assert (tmp_path / "py.slbx").read_bytes() == (tmp_path / "cli.slbx").read_bytes()
    r = slambox.Stream.read(str(tmp_path / "py.slbx"))
    assert r.header == s.header
    assert np.array_equal(r.scan_ranges, s.scan_ranges) and np.array_equal(r.odometry, s.odometry)
    (tmp_path / "bad.slbx").write_bytes((tmp_path / "py.slbx").read_bytes()[:1000])
    with pytest.raises(slambox.InputError) as e:
        slambox.Stream.read(str(tmp_path / "bad.slbx"))
    assert e.value.file == str(tmp_path / "bad.slbx")


def test_run_gives_the_cli_metrics_bit_for_bit(tmp_path, cli):
    s = slambox.simulate(slambox.load_scenario("loop", SHORT), seed=3)
    s.write(str(tmp_path / "s.slbx"))
    cli("run", tmp_path / "s.slbx", "--algo", "odometry,icp-poseslam", "--no-figures", "-q", "-o", tmp_path / "run")
    doc = json.loads((tmp_path / "run" / "metrics.json").read_text())
    res = slambox.run(s, ["odometry", "icp-poseslam"])
    assert res.names == ["odometry", "icp-poseslam"]
    assert res.header["distance_m"] == doc["distance_m"]
    assert res.header["converted_log"] is False and doc["converted_log"] is False
    for name in res.names:
        r = res[name]
        assert r.status == "ok" == doc["algorithms"][name]["status"]
        assert deterministic(r.metrics.to_dict()) == deterministic(doc["algorithms"][name])
        assert r.metrics.ate_rmse_m == doc["algorithms"][name]["ate_rmse_m"]
    est = res["odometry"].estimate
    assert est.poses.shape[1] == 4 and est.covariances.shape == (len(est), 3, 3)
    assert np.all(np.isfinite(est.covariances[1:]))  # dead reckoning propagates a covariance
    assert res["icp-poseslam"].metrics.landmark_rmse_m is None  # null in metrics.json: no landmarks
    assert res["odometry"].metrics.ate_rmse_m > res["icp-poseslam"].metrics.ate_rmse_m


def test_run_overrides_and_bad_arguments():
    s = slambox.simulate(slambox.load_scenario("loop", {"duration_s": 10}), seed=1)
    a = slambox.run(s, ["odometry"], {"algo.odometry.noise_scale": 4.0})["odometry"].metrics
    b = slambox.run(s, ["odometry"])["odometry"].metrics
    assert a.ate_rmse_m == b.ate_rmse_m and a.anees != b.anees  # same path, 4x covariance
    with pytest.raises(slambox.InputError, match="unknown algorithm"):
        slambox.run(s, ["no-such-slam"])
    with pytest.raises(slambox.InputError, match="not among the algorithms run"):
        slambox.run(s, ["odometry"], {"algo.icp-poseslam.max_iterations": 3})
    with pytest.raises(slambox.InputError, match="scenario keys"):
        slambox.run(s, ["odometry"], {"duration_s": 3})
    with pytest.raises(slambox.InputError, match="lacks a sensor"):
        slambox.run(s, ["ekf-slam"])
    with pytest.raises(TypeError):
        slambox.run(s, [42])
    with pytest.raises(ValueError, match="twice"):
        slambox.run(s, [DeadReckoning(), DeadReckoning()])


def test_python_dead_reckoning_matches_the_cpp_one():
    s = slambox.simulate(slambox.load_scenario("loop", SHORT), seed=2)
    res = slambox.run(s, [DeadReckoning(), "odometry"])
    py, cpp = res["py-odometry"], res["odometry"]
    assert py.status == "ok" and len(py.estimate) == len(cpp.estimate)
    assert np.allclose(py.estimate.poses, cpp.estimate.poses, atol=1e-9, rtol=0)
    assert py.metrics.ate_rmse_m == pytest.approx(cpp.metrics.ate_rmse_m, abs=1e-9)
    assert py.metrics.anees is None  # no covariance given: NEES is null, not 0
    assert py.metrics.ate_rmse_m > 0.01  # odometry noise is there
    assert [r.name for r in res] == ["py-odometry", "odometry"] == res.names  # iterating, as python/README.md does


def test_a_python_module_that_raises_fails_alone():
    class Broken(slambox.Module):
        def on_odometry(self, t_s, dx, dy, dth):
            if t_s > 5.0:
                raise ZeroDivisionError("the module broke at 5 s")

        def finish(self):
            return np.zeros((1, 4))

    class NoFinish(slambox.Module):
        pass

    s = slambox.simulate(slambox.load_scenario("loop", {"duration_s": 10}), seed=1)
    alone = slambox.run(s, ["odometry"])["odometry"].metrics
    res = slambox.run(s, ["odometry", Broken(), NoFinish()])
    b = res["Broken"]
    assert b.status == "failed" and b.estimate is None
    assert b.metrics.reason == "ZeroDivisionError: the module broke at 5 s"
    assert res["NoFinish"].status == "failed" and "finish" in res["NoFinish"].metrics.reason
    assert res["odometry"].status == "ok"
    assert deterministic(res["odometry"].metrics.to_dict()) == deterministic(alone.to_dict())


def test_scan_and_start_callbacks_see_the_stream():
    class Counter(slambox.Module):
        def start(self, header):
            self.header = header
            self.scans = []

        def on_scan(self, t_s, ranges_m, valid, angles_rad):
            self.scans.append((t_s, ranges_m.copy(), valid.copy(), angles_rad[0], angles_rad[1] - angles_rad[0]))

        def finish(self):
            return np.array([[0.0] + list(self.header["start_pose"])])

    s = slambox.simulate(slambox.load_scenario("loop", {"duration_s": 5}), seed=1)
    m = Counter()
    slambox.run(s, [m])
    assert m.header == s.header and len(m.scans) == len(s.scan_times)
    t, r, v, a0, da = m.scans[3]
    assert t == s.scan_times[3] and np.array_equal(r, s.scan_ranges[3]) and np.array_equal(v, s.scan_valid[3])
    assert da == pytest.approx(2 * math.pi / s.header["sensors"]["lidar"]["beams"])


def test_evaluate_closed_forms():
    t = np.arange(0.0, 20.0, 0.1)
    gt = np.column_stack([t, t, np.zeros_like(t), np.zeros_like(t)])  # 1 m/s along x
    est = gt.copy()
    est[:, 2] += 0.5  # constant 0.5 m offset in y
    m = slambox.evaluate(gt, est)
    assert m.ate_rmse_m == pytest.approx(0.5, abs=1e-12) and m.ate_max_m == pytest.approx(0.5, abs=1e-12)
    assert m.rpe_trans_rmse_m == pytest.approx(0.0, abs=1e-9)  # a rigid offset has no relative error
    assert slambox.evaluate(gt, est, align="se2").ate_rmse_m == pytest.approx(0.0, abs=1e-9)
    assert slambox.evaluate(gt, est, align="origin").ate_rmse_m == pytest.approx(0.0, abs=1e-9)
    # heading error across +-pi wraps: 0.02 rad, not 2 pi - 0.02
    gt2, est2 = gt.copy(), gt.copy()
    gt2[:, 3], est2[:, 3] = math.pi - 0.01, -math.pi + 0.01
    assert slambox.evaluate(gt2, est2).heading_rmse_deg == pytest.approx(math.degrees(0.02), abs=1e-9)
    with pytest.raises(slambox.InputError, match="unknown alignment"):
        slambox.evaluate(gt, est, align="sim3")
    with pytest.raises(slambox.InputError, match="integer"):
        slambox.evaluate(gt, est, delta=1.5, delta_unit="f")
    with pytest.raises(ValueError, match="shape"):
        slambox.evaluate(gt, est[:, :3])
    with pytest.raises(slambox.InputError, match="no timestamp matches"):
        slambox.evaluate(gt, est + np.array([100.0, 0, 0, 0]))


def test_evaluate_on_tum_files_gives_the_cli_numbers(tmp_path, cli):
    cli("run", "loop", "--seed", 1, "--set", "duration_s=30", "--algo", "odometry", "--no-figures", "-q",
        "-o", tmp_path)
    gt, est = tmp_path / "groundtruth.tum", tmp_path / "odometry.tum"
    for kwargs, flags in [({}, []), ({"align": "se2", "delta": 10, "delta_unit": "f"},
                                     ["--align", "se2", "--delta", "10", "--delta-unit", "f"])]:
        want = json.loads(cli("eval", "--gt", gt, "--est", est, "--json", *flags).stdout)
        got = slambox.evaluate(str(gt), str(est), **kwargs).to_dict()
        assert got == want
    arrays = slambox.evaluate(slambox.read_tum(str(gt)), slambox.read_tum(str(est)))
    assert arrays.ate_rmse_m == slambox.evaluate(str(gt), str(est)).ate_rmse_m


def test_evaluate_and_cli_eval_refuse_the_same_options_with_the_same_message(tmp_path, cli):
    cli("run", "loop", "--seed", 1, "--set", "duration_s=10", "--algo", "odometry", "--no-figures", "-q",
        "-o", tmp_path)
    gt, est = str(tmp_path / "groundtruth.tum"), str(tmp_path / "odometry.tum")
    # One check (app/eval_options) for both: the problem is the same text, the option and
    # the fix are spelled as each caller writes them.
    cases = [({"align": "sim3"}, ["--align", "sim3"], "unknown alignment 'sim3'", "--align", "align"),
             ({"delta_unit": "x"}, ["--delta-unit", "x"], "unknown delta unit 'x'", "--delta-unit", "delta_unit"),
             ({"delta": -1.0}, ["--delta", "-1"], "delta must be positive", "--delta 1", "delta=1"),
             ({"delta": 2.5, "delta_unit": "f"}, ["--delta", "2.5", "--delta-unit", "f"],
              "a delta in frames must be an integer", "--delta-unit f", "delta_unit='f'"),
             ({"delta": 200.0, "delta_unit": "d"}, ["--delta", "200", "--delta-unit", "d"],
              "a delta in degrees must be within (0, 180]", "--delta 90", "delta=90"),
             ({"t_max_diff_s": -1.0}, ["--t-max-diff", "-1"], "must be >= 0", "--t-max-diff", "t_max_diff_s")]
    for kwargs, flags, problem, cli_spelling, py_spelling in cases:
        r = cli("eval", "--gt", gt, "--est", est, *flags, check=False)
        assert r.returncode != 0 and problem in r.stderr and cli_spelling in r.stderr, (flags, r.stderr)
        with pytest.raises(slambox.InputError) as e:
            slambox.evaluate(gt, est, **kwargs)
        assert problem in str(e.value) and py_spelling in str(e.value) and "--" not in str(e.value), kwargs
