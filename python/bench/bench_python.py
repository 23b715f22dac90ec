"""Benchmarks of the Python module (python/README.md, "Benchmarks"):
  1. a Python dead-reckoning module replaying `loop` (seed 1): real-time factor
     (stream duration / wall time of slambox.run, replay + scoring) and the module's own
     realtime_factor metric (from its per-event times, as for C++ modules);
  2. a stream file into arrays: Stream.read + every array, against Stream.read alone
     (the C++ reader), on a 10-minute 360-beam `loop` stream.
Usage: PYTHONPATH=build/python /usr/bin/python3 python/bench/bench_python.py [--repeat N]"""
import argparse
import math
import os
import statistics
import sys
import tempfile
import time

import numpy as np

import slambox


class DeadReckoning(slambox.Module):
    name = "py-odometry"

    def start(self, header):
        self.x, self.y, self.th = header["start_pose"]
        self.poses = [(0.0, self.x, self.y, self.th)]

    def on_odometry(self, t_s, dx_m, dy_m, dtheta_rad):
        c, s = math.cos(self.th), math.sin(self.th)
        self.x += c * dx_m - s * dy_m
        self.y += s * dx_m + c * dy_m
        self.th = math.remainder(self.th + dtheta_rad, 2 * math.pi)
        self.poses.append((t_s, self.x, self.y, self.th))

    def finish(self):
        return slambox.Estimate(np.array(self.poses))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--repeat", type=int, default=5)
    args = ap.parse_args()

    stream = slambox.simulate("loop", seed=1)
    walls, module_rtf = [], []
    for _ in range(args.repeat):
        t0 = time.perf_counter()
        r = slambox.run(stream, [DeadReckoning()])["py-odometry"]
        walls.append(time.perf_counter() - t0)
        module_rtf.append(r.metrics.realtime_factor)
    wall = statistics.median(walls)
    print(f"loop seed 1: {stream.duration_s:.1f} s, {len(stream)} events ({len(stream.odometry)} odometry)")
    print(f"python dead reckoning: run() {wall * 1e3:.1f} ms median of {args.repeat} -> "
          f"{stream.duration_s / wall:.0f}x real time (module only: {statistics.median(module_rtf):.0f}x)")

    long = slambox.simulate(slambox.load_scenario("loop", {"duration_s": 600, "robot.laps": 100}), seed=1)
    with tempfile.TemporaryDirectory() as d:
        path = os.path.join(d, "long.slbx")
        long.write(path)
        size_mb = os.path.getsize(path) / 1e6
        read, arrays = [], []
        for _ in range(args.repeat):
            t0 = time.perf_counter()
            s = slambox.Stream.read(path)
            t1 = time.perf_counter()
            _ = (s.odometry, s.scan_times, s.scan_ranges, s.scan_valid, s.groundtruth, s.landmarks, s.header)
            t2 = time.perf_counter()
            read.append(t1 - t0)
            arrays.append(t2 - t0)
        r, a = statistics.median(read), statistics.median(arrays)
        print(f"10-minute stream ({size_mb:.0f} MB, {s.scan_ranges.shape[0]} x {s.scan_ranges.shape[1]} scans): "
              f"Stream.read {r * 1e3:.0f} ms, read + all arrays {a * 1e3:.0f} ms -> {a / r:.2f}x the C++ read")


if __name__ == "__main__":
    sys.exit(main())
