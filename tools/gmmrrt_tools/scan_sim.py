"""Simulated planar laser scans for the scenario logs: beams ray-cast from a sensor pose through a
map_server map (blocked cells by its trinary rules) and through axis-aligned boxes that are not in
the map, as planar_scan_t messages (docs/world.md, "Scans in gmmrrtd").

The cast marches each beam in steps of `step_m` and stops at the first sample inside a blocked
cell or box, so a range is exact to one step; beams that meet nothing within range_max_m are "no
return" (+inf), as a real lidar reports them.
"""
import math
import os

import numpy as np

from gmmrrt import planar_scan_t


def read_map(yaml_path):
    """(blocked[row, col] with row 0 at the bottom, resolution, origin_x, origin_y) of a map_server
    map written as floor.yaml (PGM, trinary, negate 0, zero yaw); unknown cells count as blocked."""
    meta = {}
    with open(yaml_path) as f:
        for line in f:
            if ":" in line:
                k, v = line.split("#", 1)[0].split(":", 1)
                meta[k.strip()] = v.strip()
    origin = [float(v) for v in meta["origin"].strip("[]").split(",")]
    if abs(origin[2]) > 0 or int(meta.get("negate", "0")) != 0:
        raise ValueError("%s: only zero yaw and negate 0 are simulated" % yaml_path)
    with open(os.path.join(os.path.dirname(yaml_path), meta["image"]), "rb") as f:
        data = f.read()
    fields, pos = [], 0
    while len(fields) < 4:  # P5, width, height, maxval; comments start with '#'
        while data[pos:pos + 1].isspace():
            pos += 1
        if data[pos:pos + 1] == b"#":
            pos = data.index(b"\n", pos) + 1
            continue
        end = pos
        while not data[end:end + 1].isspace():
            end += 1
        fields.append(data[pos:end])
        pos = end
    w, h = int(fields[1]), int(fields[2])
    img = np.frombuffer(data[pos + 1:pos + 1 + w * h], dtype=np.uint8).reshape(h, w)
    p = (255.0 - img) / 255.0
    blocked = p > float(meta["free_thresh"])  # occupied and unknown
    return blocked[::-1, :].copy(), float(meta["resolution"]), origin[0], origin[1]


class Caster:
    def __init__(self, yaml_path, n_beams=541, fov_rad=1.5 * math.pi, range_min_m=0.05, range_max_m=10.0,
                 step_m=0.01):
        self.blocked, self.res, self.ox, self.oy = read_map(yaml_path)
        self.rad0 = -0.5 * fov_rad
        self.radstep = fov_rad / (n_beams - 1)
        self.n, self.rmin, self.rmax = n_beams, range_min_m, range_max_m
        self.dist = np.arange(1, int(round(range_max_m / step_m)) + 1) * step_m

    def ranges(self, x, y, yaw, boxes=()):
        """Ranges (float32, +inf for no return) of the beams from sensor pose (x, y, yaw) through
        the map and the boxes (xmin, ymin, xmax, ymax)."""
        ang = yaw + self.rad0 + self.radstep * np.arange(self.n)
        px = x + np.cos(ang)[:, None] * self.dist[None, :]
        py = y + np.sin(ang)[:, None] * self.dist[None, :]
        i = np.floor((px - self.ox) / self.res).astype(np.int64)
        j = np.floor((py - self.oy) / self.res).astype(np.int64)
        h, w = self.blocked.shape
        outside = (i < 0) | (j < 0) | (i >= w) | (j >= h)
        hit = outside.copy()
        hit[~outside] = self.blocked[j[~outside], i[~outside]]
        for (x0, y0, x1, y1) in boxes:
            hit |= (px >= x0) & (px <= x1) & (py >= y0) & (py <= y1)
        first = np.where(hit.any(axis=1), hit.argmax(axis=1), -1)
        r = np.where(first >= 0, self.dist[np.maximum(first, 0)], np.inf)
        return r.astype(np.float32)

    def message(self, utime, ranges):
        m = planar_scan_t()
        m.utime = int(utime)
        m.rad0, m.radstep, m.range_min_m, m.range_max_m = self.rad0, self.radstep, self.rmin, self.rmax
        m.num_ranges = self.n
        m.ranges = [float(v) for v in ranges] + [0.0] * (planar_scan_t.MAX_RANGES - self.n)
        return m
