#!/usr/bin/python3
"""Misbehaving exec children for tests/app/exec_module_test.cpp: `child.py MODE`.

crash: dies by SIGSEGV after 100 events; exit3: exits with status 3 before done;
hang: reads the header, then sleeps; garbage: answers a line that is not JSON;
nan: a NaN pose (Python's json writes a bare NaN); flood: 8 MiB of stderr before each
of the first answers, then valid dead reckoning (no deadlock); quiet-exit: exits 0 before done;
params: valid dead reckoning if the header's params are those the test sets, else exit 5.
"""
import json
import math
import os
import signal
import sys
import time

mode = sys.argv[1]
count = 0
x = y = theta = 0.0
for line in sys.stdin:
    ev = json.loads(line)
    count += 1
    if ev["type"] == "header":
        sys.stderr.write("child %s: started\n" % mode)
        sys.stderr.flush()
        if mode == "hang":
            time.sleep(3600)
        if mode == "params":
            expected = {"gain": 2.5, "n": 7, "on": True, "mode": "exact"}
            if ev["params"] != expected:
                sys.exit("child params: got %r, expected %r" % (ev["params"], expected))
            mode = "flood-free"
        x, y, theta = ev["start_pose"]
        print(json.dumps({"type": "pose", "t_s": 0.0, "x_m": x, "y_m": y, "theta_rad": theta}))
        continue
    if count == 100:
        if mode == "crash":
            sys.stderr.write("child crash: about to segfault\n")
            sys.stderr.flush()
            os.kill(os.getpid(), signal.SIGSEGV)
        if mode == "exit3":
            sys.stderr.write("child exit3: giving up\n")
            sys.exit(3)
        if mode == "quiet-exit":
            sys.exit(0)
        if mode == "garbage":
            print("hello, I am not JSON", flush=True)
        if mode == "nan":
            print(json.dumps({"type": "pose", "t_s": ev["t_s"], "x_m": float("nan"), "y_m": 0.0, "theta_rad": 0.0}),
                  flush=True)
    if mode == "flood" and count < 5:
        sys.stderr.write("x" * (8 << 20) + "\n")
    if mode in ("flood", "flood-free") and ev["type"] == "odometry":
        c, s = math.cos(theta), math.sin(theta)
        x, y = x + c * ev["dx_m"] - s * ev["dy_m"], y + s * ev["dx_m"] + c * ev["dy_m"]
        theta = math.remainder(theta + ev["dtheta_rad"], 2 * math.pi)
        print(json.dumps({"type": "pose", "t_s": ev["t_s"], "x_m": x, "y_m": y, "theta_rad": theta}))
    if ev["type"] == "finish":
        print('{"type":"done"}', flush=True)
        break
