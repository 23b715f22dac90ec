#!/usr/bin/env python3
"""Writes random scenario files, to try the modules on worlds nobody tuned them on.

  scripts/random_scenarios.py OUTDIR lidar|lm N BATCH

lidar: an occupancy map (PGM + ROS map YAML) carved along a random path (a rectangle, a
notched rectangle, a loop with a cross street, a there-and-back, a figure eight) with a
random corridor width (1.4-12 m), side rooms and pillars, sometimes people walking the
corridors; a random LIDAR (90-360 deg, 91-720 beams, 8-40 m, 0.5-5 cm noise, dropouts),
odometry noise, speed and laps.  lm: a park of 8-250 posts along such a path with a random
landmark detector (90-360 deg, 6-30 m, noise, known or unknown ids, detection probability
0.7-1, clutter 0-1 per scan).  Scenario i of batch B is drawn from random.Random(1000 B + i),
so a file name (lidarB_i, lmB_i) says how to make it again.  Some draws are beyond any
sensor's reach (a 90-degree, 6 m detector in a sparse park); judge a module against the
others on the same file, e.g. `slambox run OUTDIR/lidar1_6.yaml --algo all --skip-unavailable -o D`.
"""
import sys, os, random, math
import numpy as np

def loop_path(rng, W, H, margin):
    kind = rng.choice(["rect", "notch", "grid", "outback", "eight"])
    x0, y0 = margin, margin
    x1, y1 = W - margin, H - margin
    if kind == "rect":
        p = [[x0, y0], [x1, y0], [x1, y1], [x0, y1], [x0, y0]]
    elif kind == "notch":
        xm = rng.uniform(x0 + (x1-x0)*0.3, x0 + (x1-x0)*0.7); ym = rng.uniform(y0 + (y1-y0)*0.3, y0 + (y1-y0)*0.7)
        p = [[x0, y0], [x1, y0], [x1, ym], [xm, ym], [xm, y1], [x0, y1], [x0, y0]]
    elif kind == "grid":  # a loop with an inner cross street, driven as a figure of rooms
        xm = (x0 + x1) / 2; ym = (y0 + y1) / 2
        p = [[x0, y0], [xm, y0], [xm, y1], [x1, y1], [x1, ym], [x0, ym], [x0, y0]]
    elif kind == "outback":  # there and back the same way (passes the other way)
        xm = rng.uniform(x0 + (x1-x0)*0.4, x1)
        p = [[x0, y0], [x1, y0], [x1, y1], [xm, y1], [x1, y1], [x1, y0], [x0, y0]]
    else:  # eight
        xm = (x0 + x1) / 2
        p = [[x0, y0], [xm, y0], [xm, y1], [x1, y1], [x1, y0], [xm, y0], [xm, y1], [x0, y1], [x0, y0]]
    return kind, [[round(a, 2), round(b, 2)] for a, b in p]

def carve_segment(grid, res, a, b, half):
    n = int(math.hypot(b[0]-a[0], b[1]-a[1]) / (res/2)) + 1
    h = int(math.ceil(half / res))
    for i in range(n + 1):
        t = i / n
        x = a[0] + t*(b[0]-a[0]); y = a[1] + t*(b[1]-a[1])
        cx, cy = int(x / res), int(y / res)
        grid[max(cy-h, 0):cy+h+1, max(cx-h, 0):cx+h+1] = 0

def segment_blocked(grid, res, a, b, radius):
    """True if a disc of `radius` moved from a to b overlaps an occupied cell of grid."""
    n = int(math.hypot(b[0]-a[0], b[1]-a[1]) / (res/2)) + 1
    h = int(math.ceil(radius / res)) + 1
    ny, nx = grid.shape
    for i in range(n + 1):
        x = a[0] + i/n*(b[0]-a[0]); y = a[1] + i/n*(b[1]-a[1])
        cx, cy = int(x / res), int(y / res)
        for gy in range(max(cy-h, 0), min(cy+h+1, ny)):
            for gx in range(max(cx-h, 0), min(cx+h+1, nx)):
                if not grid[gy, gx]: continue
                dx = max(abs(x - (gx+0.5)*res) - res/2, 0.0); dy = max(abs(y - (gy+0.5)*res) - res/2, 0.0)
                if dx*dx + dy*dy < radius*radius: return True
    return False

def dist_to_path(x, y, path):
    best = 1e9
    for a, b in zip(path[:-1], path[1:]):
        ax, ay = a; bx, by = b
        dx, dy = bx-ax, by-ay; L2 = dx*dx+dy*dy
        t = 0 if L2 == 0 else max(0, min(1, ((x-ax)*dx+(y-ay)*dy)/L2))
        best = min(best, math.hypot(x-ax-t*dx, y-ay-t*dy))
    return best

def lidar_scenario(rng, name, outdir):
    W = rng.uniform(25, 110); H = rng.uniform(18, 70)
    half = rng.choice([0.7, 0.9, 1.2, 1.8, 3.0, 6.0])
    margin = half + 1.0
    kind, path = loop_path(rng, W, H, margin)
    res = rng.choice([0.05, 0.1])
    nx, ny = int(W / res) + 1, int(H / res) + 1
    grid = np.ones((ny, nx), np.uint8)
    for a, b in zip(path[:-1], path[1:]):
        carve_segment(grid, res, a, b, half)
    # side rooms along the path
    for _ in range(rng.randint(0, 12)):
        seg = rng.randrange(len(path) - 1); t = rng.random()
        a, b = path[seg], path[seg+1]
        x = a[0] + t*(b[0]-a[0]); y = a[1] + t*(b[1]-a[1])
        w, h = rng.uniform(2, 8), rng.uniform(2, 8)
        ox, oy = rng.uniform(-w, 0), rng.uniform(-h, 0)
        x0, y0 = max(int((x+ox)/res), 1), max(int((y+oy)/res), 1)
        grid[y0:min(int((y+oy+h)/res), ny-1), x0:min(int((x+ox+w)/res), nx-1)] = 0
    # pillars / clutter in free space, away from the path
    clear = 0.9
    for _ in range(rng.randint(0, 60)):
        x, y = rng.uniform(0, W), rng.uniform(0, H)
        s = rng.uniform(0.1, 1.0)
        if dist_to_path(x, y, path) < clear + s: continue
        grid[int((y-s/2)/res):int((y+s/2)/res)+1, int((x-s/2)/res):int((x+s/2)/res)+1] = 1
    grid[0, :] = grid[-1, :] = 1; grid[:, 0] = grid[:, -1] = 1
    img = np.where(grid[::-1] == 1, 0, 254).astype(np.uint8)  # image rows top-down
    with open(os.path.join(outdir, name + ".pgm"), "wb") as f:
        f.write(b"P5\n%d %d\n255\n" % (nx, ny)); f.write(img.tobytes())
    with open(os.path.join(outdir, name + "_map.yaml"), "w") as f:
        f.write("image: %s.pgm\nmode: trinary\nresolution: %g\norigin: [0, 0, 0]\nnegate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n" % (name, res))
    fov = rng.choice([180, 240, 270, 360])
    beams = rng.choice([91, 181, 271, 361, 541, 720])
    rmax = rng.choice([8, 12, 20, 30, 40])
    sr = rng.choice([0.005, 0.01, 0.02, 0.03, 0.05])
    sb = rng.choice([0.0, 0.0, 0.1, 0.2])
    drop = rng.choice([0.0, 0.0, 0.05, 0.2])
    a1 = rng.choice([0.02, 0.05, 0.1, 0.2]); a2 = rng.choice([0.002, 0.005, 0.01, 0.03])
    rate = rng.choice([5, 10, 20])
    speed = rng.choice([0.5, 1.0, 1.5])
    laps = rng.choice([1, 2, 2, 3])
    movers = ""
    if rng.random() < 0.3 and half >= 1.2:
        ms = []
        for _ in range(rng.randint(1, 6)):
            seg = rng.randrange(len(path) - 1); a, b = path[seg], path[seg+1]
            dx, dy = b[0]-a[0], b[1]-a[1]; L = math.hypot(dx, dy) or 1
            off = half * 0.75
            nxo, nyo = -dy/L*off, dx/L*off
            speed_mps = rng.uniform(0.3, 1.2)  # drawn either way, so later draws stay as they were
            p0, p1 = (a[0]+nxo, a[1]+nyo), (b[0]+nxo, b[1]+nyo)
            if segment_blocked(grid, res, p0, p1, 0.25):  # a pillar on its lane: slambox refuses it
                continue
            ms.append("    - {circle: {radius_m: 0.25}, path: [[%.2f, %.2f], [%.2f, %.2f]], speed_mps: %.1f, loop: true}"
                      % (p0[0], p0[1], p1[0], p1[1], speed_mps))
        movers = "  movers:\n" + "\n".join(ms) + "\n" if ms else ""
    s = f"""version: 1
name: {name}
description: "random lidar world ({kind}, {W:.0f} x {H:.0f} m, corridor half width {half} m)"
world:
  occupancy_map: {name}_map.yaml
{movers}robot:
  start: {{x: {path[0][0]}, y: {path[0][1]}, theta_deg: {math.degrees(math.atan2(path[1][1]-path[0][1], path[1][0]-path[0][0])):.1f}}}
  max_speed_mps: {speed}
  path: {path[1:]}
  laps: {laps}
sensors:
  odometry: {{rate_hz: 50, alpha: [{a1}, {a2}, {a1}, {a2}]}}
  lidar: {{rate_hz: {rate}, beams: {beams}, fov_deg: {fov}, range_max_m: {rmax}, sigma_range_m: {sr}, sigma_bearing_deg: {sb}, dropout_prob: {drop}}}
"""
    open(os.path.join(outdir, name + ".yaml"), "w").write(s)

def landmark_scenario(rng, name, outdir):
    W = rng.uniform(30, 150); H = rng.uniform(30, 120)
    margin = 5
    kind, path = loop_path(rng, W, H, margin)
    n = rng.randint(8, 250)
    lms = []
    tries = 0
    mind = rng.choice([1.0, 2.0, 3.0])
    while len(lms) < n and tries < 20000:
        tries += 1
        x, y = rng.uniform(1, W-1), rng.uniform(1, H-1)
        if dist_to_path(x, y, path) < 1.2: continue
        if any((x-a)**2 + (y-b)**2 < mind**2 for a, b in lms): continue
        lms.append((x, y))
    fov = rng.choice([90, 120, 180, 270, 360])
    rmax = rng.choice([6, 8, 12, 20, 30])
    sr = rng.choice([0.02, 0.05, 0.1, 0.2, 0.3])
    sb = rng.choice([0.5, 1.0, 2.0, 3.0])
    known = rng.choice(["true", "false", "false"])
    det = rng.choice([1.0, 0.95, 0.9, 0.8, 0.7])
    clut = rng.choice([0, 0, 0.2, 0.5, 1.0])
    a1 = rng.choice([0.02, 0.05, 0.1, 0.2]); a2 = rng.choice([0.002, 0.005, 0.01, 0.03])
    rate = rng.choice([2, 5, 10])
    laps = rng.choice([1, 2, 2, 3])
    L = "\n".join("    - {pos: [%.2f, %.2f], radius_m: 0.15}" % p for p in lms)
    s = f"""version: 1
name: {name}
description: "random landmark park ({kind}, {W:.0f} x {H:.0f} m, {len(lms)} posts)"
world:
  walls:
    - polygon: [[0, 0], [{W:.2f}, 0], [{W:.2f}, {H:.2f}], [0, {H:.2f}]]
  landmarks:
{L}
robot:
  start: {{x: {path[0][0]}, y: {path[0][1]}, theta_deg: {math.degrees(math.atan2(path[1][1]-path[0][1], path[1][0]-path[0][0])):.1f}}}
  path: {path[1:]}
  laps: {laps}
sensors:
  odometry: {{rate_hz: 50, alpha: [{a1}, {a2}, {a1}, {a2}]}}
  landmarks: {{rate_hz: {rate}, range_max_m: {rmax}, fov_deg: {fov}, sigma_range_m: {sr}, sigma_bearing_deg: {sb}, known_ids: {known}, detection_prob: {det}, clutter_per_scan: {clut}}}
"""
    open(os.path.join(outdir, name + ".yaml"), "w").write(s)

if __name__ == "__main__":
    if len(sys.argv) != 5 or sys.argv[2] not in ("lidar", "lm"):
        sys.exit("usage: random_scenarios.py OUTDIR lidar|lm N BATCH")
    out, kind, N, s0 = sys.argv[1], sys.argv[2], int(sys.argv[3]), int(sys.argv[4])
    os.makedirs(out, exist_ok=True)
    for i in range(N):
        rng = random.Random(1000 * s0 + i)
        name = f"{kind}{s0}_{i}"
        (lidar_scenario if kind == "lidar" else landmark_scenario)(rng, name, out)
