"""Python modules the tests share."""
import math

import numpy as np

import slambox


class DeadReckoning(slambox.Module):
    """Composes the odometry increments: x_t = x_{t-1} (+) delta (no covariance)."""
    name = "py-odometry"

    def start(self, header):
        p = header["start_pose"]
        self.x, self.y, self.th = p[0], p[1], p[2]
        self.poses = [(0.0, self.x, self.y, self.th)]

    def on_odometry(self, t_s, dx_m, dy_m, dtheta_rad):
        c, s = math.cos(self.th), math.sin(self.th)
        self.x += c * dx_m - s * dy_m
        self.y += s * dx_m + c * dy_m
        self.th = math.remainder(self.th + dtheta_rad, 2 * math.pi)
        self.poses.append((t_s, self.x, self.y, self.th))

    def finish(self):
        return slambox.Estimate(np.array(self.poses))


class Raising(slambox.Module):
    """Fails at the 100th odometry event."""
    name = "py-raising"

    def start(self, header):
        self.n = 0

    def on_odometry(self, t_s, dx_m, dy_m, dtheta_rad):
        self.n += 1
        if self.n == 100:
            raise ZeroDivisionError("planted at event 100")

    def finish(self):
        return np.zeros((1, 4))
