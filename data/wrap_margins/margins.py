#!/usr/bin/env python3
"""Wrap margins (issue 7 (d), session 15, h59): per ring, the inverted arc S against the wrap
threshold 0.25 pi R, from the final outlines in run_result.json (FE: outer surface, half ring,
97 points; Level 2: mean line, 48 points, closed). S is recomputed here with the formula of
compare/measures.cpp inverted_arc_length and checked against the stored value, then again
under the variants that put both models on one measure (see README "FE against the hinge model").
usage: margins.py [--variants] [--csv OUT.csv] LABEL=RUN_DIR ...   (RUN_DIR holds run_result.json)"""
import json, math, os, sys

D, T = 0.0508, 0.0016
R = 0.5 * (D - T)
THRESHOLD = 0.25 * math.pi * R

def shape_of(run):
    """points, material angles, half flag, from a RunResult's outlines."""
    half = run["outline_half"]
    shapes = []
    for o in run["ring_outline_m"]:
        pts = [tuple(p) for p in o]
        if not half and len(pts) > 1 and pts[0] == pts[-1]:
            pts = pts[:-1]  # the closing point of the report outline
        n = len(pts)
        th = [math.pi * k / (n - 1) for k in range(n)] if half else [2 * math.pi * k / n for k in range(n)]
        shapes.append((pts, th, half))
    return shapes

def mirror_closed(pts, th):
    """A half ring (theta 0..pi, x >= 0) as the whole ring it stands for (x = 0 mirror)."""
    n = len(pts)
    back = [(-pts[k][0], pts[k][1]) for k in range(n - 2, 0, -1)]
    tb = [2 * math.pi - th[k] for k in range(n - 2, 0, -1)]
    return pts + back, th + tb

def turning(a, b):
    return math.atan2(a[0] * b[1] - a[1] * b[0], a[0] * b[0] + a[1] * b[1])

def inverted_arc(pts, th, half, tol=-1.0, endpoints=False):
    """compare/measures inverted_arc_length; endpoints=True takes a half ring's turning at its
    axis points (A, B) from the mirrored neighbour instead of skipping them."""
    if half and endpoints:
        p, t = mirror_closed(pts, th)
        return inverted_arc(p, t, False, tol if tol >= 0 else 0.1 * 2 * math.pi / (2 * (len(pts) - 1)))
    n = len(pts)
    closed = not half
    per_ring = 2.0 * (n - 1) if half else float(n)
    if tol < 0: tol = 0.1 * 2 * math.pi / per_ring
    turn = [0.0] * n
    for j in range(n):
        if not closed and (j == 0 or j + 1 == n): continue
        p0, p1, p2 = pts[(j - 1) % n], pts[j], pts[(j + 1) % n]
        turn[j] = turning((p1[0] - p0[0], p1[1] - p0[1]), (p2[0] - p1[0], p2[1] - p1[1]))
    orient = 1.0 if sum(turn) >= 0 else -1.0
    s = 0.0
    for j in range(n):
        if not closed and (j == 0 or j + 1 == n): continue
        if abs(math.remainder(th[j], 2 * math.pi)) < 0.5 * math.pi: continue
        if orient * turn[j] < -tol:
            p0, p1, p2 = pts[(j - 1) % n], pts[j], pts[(j + 1) % n]
            s += 0.5 * (math.dist(p0, p1) + math.dist(p1, p2))
    return 2 * s if half else s

def offset(pts, d):
    """The closed polyline moved by d along its outward normal (mean line -> outer surface)."""
    n = len(pts)
    area = sum(pts[k][0] * pts[(k + 1) % n][1] - pts[(k + 1) % n][0] * pts[k][1] for k in range(n))
    sgn = 1.0 if area > 0 else -1.0  # counter-clockwise: outward normal is the tangent turned clockwise
    out = []
    for k in range(n):
        a, b = pts[(k - 1) % n], pts[(k + 1) % n]
        tx, ty = b[0] - a[0], b[1] - a[1]
        l = math.hypot(tx, ty)
        nx, ny = sgn * ty / l, -sgn * tx / l
        out.append((pts[k][0] + d * nx, pts[k][1] + d * ny))
    return out

def resample(pts, th, m):
    """A closed polyline resampled at m points equally spaced in material angle (linear)."""
    n = len(pts)
    out, tout = [], []
    for k in range(m):
        t = 2 * math.pi * k / m
        x = t / (2 * math.pi) * n
        i = int(math.floor(x)) % n
        f = x - math.floor(x)
        a, b = pts[i], pts[(i + 1) % n]
        out.append((a[0] + f * (b[0] - a[0]), a[1] + f * (b[1] - a[1])))
        tout.append(t)
    return out, tout

def main():
    args = sys.argv[1:]
    variants = "--variants" in args
    args = [a for a in args if a != "--variants"]
    csv_out = None
    if "--csv" in args:
        k = args.index("--csv"); csv_out = open(args[k + 1], "w"); del args[k:k + 2]
        csv_out.write("case,ring,inverted_arc_mm,margin_mm,wrapped_angle_deg,wrap_flag\n")
    print(f"threshold 0.25 pi R = {THRESHOLD*1e3:.1f} mm")
    hdr = "case ring | S mm, margin mm | W deg | flag"
    if variants: hdr += " | S with A, B skipped (before) | on the mean line (FE) / outer surface (L2) | FE resampled at 48 points"
    print(hdr)
    for a in args:
        label, d = a.split("=", 1)
        run = json.load(open(os.path.join(d, "run_result.json")))
        shapes = shape_of(run)
        for i, (pts, th, half) in enumerate(shapes):
            # The measure as it is (a half ring's axis points A, B turn against their mirror,
            # session 15) and as it was (they were skipped): the stored S is one of the two.
            s = inverted_arc(pts, th, half, endpoints=True)
            s_before = inverted_arc(pts, th, half)
            stored = run["inverted_arc_m"][i]
            assert min(abs(s - stored), abs(s_before - stored)) < 1e-9, (label, i, s, s_before, stored)
            line = (f"{label:16s} {i+1} | {s*1e3:5.1f} {1e3*(s-THRESHOLD):+6.1f} | {run['wrapped_angle_deg'][i]:6.1f} | "
                    f"{int(run['wrap_around'][i])}")
            if variants:
                sb = s_before
                full, tf = mirror_closed(pts, th) if half else (pts, th)
                if half:  # FE outer surface -> mean line: offset inward by t/2
                    other = inverted_arc(offset(full, -0.5 * T), tf, False, 0.1 * 2 * math.pi / len(full))
                else:     # Level 2 mean line -> outer surface: offset outward by t/2
                    other = inverted_arc(offset(full, 0.5 * T), tf, False)
                r48, t48 = resample(full, tf, 48)
                s48 = inverted_arc(r48, t48, False)
                line += f" | {sb*1e3:5.1f} | {other*1e3:5.1f} | {s48*1e3:5.1f}"
            print(line)
            if csv_out:
                csv_out.write(f"{label},{i+1},{s*1e3:.2f},{1e3*(s-THRESHOLD):.2f},{run['wrapped_angle_deg'][i]:.2f},{int(run['wrap_around'][i])}\n")

if __name__ == "__main__":
    main()
