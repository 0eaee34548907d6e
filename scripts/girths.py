#!/usr/bin/env python3
"""How tight a drape is round the body: girths of the cloth and the body, slice by slice.

    python3 scripts/girths.py RUN_FOLDER [SLICES]

RUN_FOLDER holds a run's `cloth.obj` (with its material coordinates) and `bodies.obj`,
both z-up as the run writes them. At SLICES heights (12 by default) across the cloth, it
prints the cloth's rest length round the slice (from the material coordinates of the
segments cut), its draped girth and the body's there: each girth the perimeter of the
convex hull of the slice, as a tape measure goes round, the body's taken only within the
cloth's reach from the slice's centre (so a skirt's slice leaves the hands out). A cloth
shorter round at rest than the body is round must stretch to go on. Meaningful where the
slice is one closed tube (skirts, waistbands, bodices below the arms); not across
armholes, where a hull spans the gap, nor across two trouser legs, whose rest lengths add
up under one hull. Needs numpy.
"""
import sys

import numpy as np


def index(text, count):
    """A face's 1-based index, or a negative one counted back from the last read."""
    i = int(text)
    return i - 1 if i > 0 else count + i


def read_obj(path):
    """Vertices, texture coordinates, and triangles as (vertex, texture) index triples."""
    v, vt, tris = [], [], []
    with open(path) as f:
        for line in f:
            s = line.split()
            if not s:
                continue
            if s[0] == "v":
                v.append([float(c) for c in s[1:4]])
            elif s[0] == "vt":
                vt.append([float(c) for c in (s[1:3] + ["0"])[:2]])
            elif s[0] == "f":
                corners = [c.split("/") for c in s[1:]]
                ids = [
                    (index(c[0], len(v)), index(c[1], len(vt)) if len(c) > 1 and c[1] else -1)
                    for c in corners
                ]
                for k in range(1, len(ids) - 1):
                    tris.append((ids[0], ids[k], ids[k + 1]))
    return np.array(v), np.array(vt) if vt else None, tris


def hull_perimeter(points):
    """Perimeter of the convex hull of 2-d points (monotone chain)."""
    pts = sorted(set(map(tuple, np.round(points, 9))))
    if len(pts) < 3:
        return 0.0

    def turn(o, a, b):
        return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])

    lower, upper = [], []
    for p in pts:
        while len(lower) >= 2 and turn(lower[-2], lower[-1], p) <= 0:
            lower.pop()
        lower.append(p)
    for p in reversed(pts):
        while len(upper) >= 2 and turn(upper[-2], upper[-1], p) <= 0:
            upper.pop()
        upper.append(p)
    hull = np.array(lower[:-1] + upper[:-1])
    return float(np.sum(np.linalg.norm(hull - np.roll(hull, 1, axis=0), axis=1)))


def slice_at(v, vt, tris, z):
    """The points where the plane at height z cuts the triangles' edges, and the rest
    length of the cut (0 without texture coordinates)."""
    points, rest = [], 0.0
    for tri in tris:
        h = [v[i][2] - z for i, _ in tri]
        cut3, cut2 = [], []
        for a in range(3):
            b = (a + 1) % 3
            if h[a] * h[b] < 0:
                t = h[a] / (h[a] - h[b])
                (ia, ta), (ib, tb) = tri[a], tri[b]
                cut3.append(v[ia] + (v[ib] - v[ia]) * t)
                if vt is not None and ta >= 0 and tb >= 0:
                    cut2.append(vt[ta] + (vt[tb] - vt[ta]) * t)
        if len(cut3) == 2:
            points += cut3
            if len(cut2) == 2:
                rest += float(np.linalg.norm(cut2[0] - cut2[1]))
    return np.array(points), rest


def main():
    if len(sys.argv) not in (2, 3):
        sys.exit(__doc__)
    folder = sys.argv[1]
    slices = int(sys.argv[2]) if len(sys.argv) == 3 else 12
    cloth, uv, cloth_tris = read_obj(f"{folder}/cloth.obj")
    body, _, body_tris = read_obj(f"{folder}/bodies.obj")
    if uv is None:
        sys.exit(f"{folder}/cloth.obj has no texture coordinates: no rest lengths")
    low, high = cloth[:, 2].min() + 0.01, cloth[:, 2].max() - 0.01
    print("height m | cloth at rest cm | cloth draped cm | body cm")
    for z in np.linspace(low, high, slices):
        pts, rest = slice_at(cloth, uv, cloth_tris, z)
        if len(pts) < 3:
            continue
        around, _ = slice_at(body, None, body_tris, z)
        centre = pts[:, :2].mean(axis=0)
        reach = np.linalg.norm(pts[:, :2] - centre, axis=1).max() + 0.01
        if len(around):
            around = around[np.linalg.norm(around[:, :2] - centre, axis=1) < reach]
        draped = hull_perimeter(pts[:, :2])
        girth = hull_perimeter(around[:, :2]) if len(around) > 2 else 0.0
        print(f"{z:8.3f} | {100 * rest:16.1f} | {100 * draped:15.1f} | {100 * girth:7.1f}")


if __name__ == "__main__":
    main()
