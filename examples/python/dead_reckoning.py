#!/usr/bin/python3
"""Dead reckoning as an slambox `exec` module (docs/exec_protocol.md), stdlib only.

Reads the stream's JSON Lines on stdin and answers one pose per odometry event with the
covariance of Thrun's odometry motion model (Probabilistic Robotics, Table 5.6):
P' = G P G^T + V M V^T. Every operation is done in the same order as slambox's built-in
`odometry` module (slam/dead_reckoning.cpp, core/odometry_model.cpp), so the metrics are
bit for bit the same.
"""
import ctypes
import json
import math
import sys

# glibc's hypot, as C++'s std::hypot: Python's math.hypot is a different (also accurate)
# algorithm whose last bit differs on ~0.2 % of inputs.
_libm = ctypes.CDLL("libm.so.6")
_libm.hypot.restype = ctypes.c_double
_libm.hypot.argtypes = [ctypes.c_double, ctypes.c_double]
hypot = _libm.hypot


def normalize_angle(a):
    """Wraps to [-pi, pi) (core/se2.hpp NormalizeAngle)."""
    two_pi = 2.0 * math.pi
    return a - two_pi * math.floor((a + math.pi) / two_pi)


def decompose(dx, dy, dtheta):
    """(rot1, trans, rot2) with |rot1| <= pi/2 (core/odometry_model.cpp Decompose)."""
    trans = hypot(dx, dy)
    rot1 = 0.0 if trans < 1e-9 else math.atan2(dy, dx)
    if abs(rot1) > math.pi / 2:
        rot1 = normalize_angle(rot1 + math.pi)
        trans = -trans
    rot2 = normalize_angle(dtheta - rot1)
    return rot1, trans, rot2


def matmul(a, b):
    return [[a[i][0] * b[0][j] + a[i][1] * b[1][j] + a[i][2] * b[2][j] for j in range(3)] for i in range(3)]


def transpose(a):
    return [[a[j][i] for j in range(3)] for i in range(3)]


def main():
    out = sys.stdout
    x = y = theta = 0.0
    P = [[0.0] * 3 for _ in range(3)]
    alpha = [0.0] * 4
    noise_scale = 1.0

    def pose_line(t):
        cov = ",".join(repr(P[i][j]) for i in range(3) for j in range(3))
        out.write('{"type":"pose","t_s":%r,"x_m":%r,"y_m":%r,"theta_rad":%r,"covariance":[%s]}\n'
                  % (t, x, y, theta, cov))

    for line in sys.stdin:
        ev = json.loads(line)
        kind = ev["type"]
        if kind == "header":
            if ev["version"] != 1:
                sys.exit("dead_reckoning.py: protocol version %r, expected 1" % ev["version"])
            x, y, theta = ev["start_pose"]
            alpha = ev["sensors"].get("odometry", {}).get("alpha", [0.0] * 4)
            noise_scale = ev["params"].get("noise_scale", 1.0)
            pose_line(0.0)
        elif kind == "odometry":
            rot1, trans, rot2 = decompose(ev["dx_m"], ev["dy_m"], ev["dtheta_rad"])
            heading = theta + rot1
            c, s = math.cos(heading), math.sin(heading)
            G = [[1.0, 0.0, -trans * s], [0.0, 1.0, trans * c], [0.0, 0.0, 1.0]]
            V = [[-trans * s, c, 0.0], [trans * c, s, 0.0], [1.0, 0.0, 1.0]]
            r1, t2, r2 = rot1 * rot1, trans * trans, rot2 * rot2
            M = [[0.0] * 3 for _ in range(3)]
            M[0][0] = noise_scale * (alpha[0] * r1 + alpha[1] * t2)
            M[1][1] = noise_scale * (alpha[2] * t2 + alpha[3] * (r1 + r2))
            M[2][2] = noise_scale * (alpha[0] * r2 + alpha[1] * t2)
            x, y, theta = x + trans * c, y + trans * s, normalize_angle(theta + rot1 + rot2)
            GPG = matmul(matmul(G, P), transpose(G))
            VMV = matmul(matmul(V, M), transpose(V))
            P = [[GPG[i][j] + VMV[i][j] for j in range(3)] for i in range(3)]
            pose_line(ev["t_s"])
        elif kind == "finish":
            out.write('{"type":"done"}\n')
            out.flush()
            return
        # scans, landmarks, gyro: dead reckoning ignores them


if __name__ == "__main__":
    main()
