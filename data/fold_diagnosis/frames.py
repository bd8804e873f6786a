"""Read FE VTU frames and Level 2 VTP shape frames; per-ring outlines and S."""
import math, re, os, sys
import xml.etree.ElementTree as ET

D = 0.0508; T = 0.0016; RM = 0.5 * (D - T)

def _arrays(path):
    root = ET.parse(path).getroot()
    out = {}
    for da in root.iter('DataArray'):
        name = da.get('Name') or 'Points'
        nc = int(da.get('NumberOfComponents') or 1)
        vals = da.text.split()
        typ = da.get('type')
        conv = float if typ.startswith('Float') else int
        vals = [conv(v) for v in vals]
        if nc > 1:
            vals = [vals[i:i + nc] for i in range(0, len(vals), nc)]
        out[name] = vals
    return out

def pvd_times(pvd):
    root = ET.parse(pvd).getroot()
    base = os.path.dirname(pvd)
    return [(float(d.get('timestep')), os.path.join(base, d.get('file'))) for d in root.iter('DataSet')]

_fe_cache = {}
def fe_topology(a):
    """outer node ids per ring sorted by material angle (from top, clockwise toward +x)."""
    pts = a['Points']; conn = a['connectivity']; offs = a['offsets']; ring = a['ring']
    key = (len(pts), len(conn))
    if key in _fe_cache: return _fe_cache[key]
    nodes_of = {}
    start = 0
    for c, o in enumerate(offs):
        r = ring[c]
        nodes_of.setdefault(r, set()).update(conn[start:o])
        start = o
    rings = {}
    for r, ids in sorted(nodes_of.items()):
        if r <= 0: continue
        ys = [pts[i][1] for i in ids]
        cy = 0.5 * (max(ys) + min(ys))
        outer = []
        for i in ids:
            dx, dy = pts[i][0], pts[i][1] - cy
            if abs(math.hypot(dx, dy) - 0.5 * D) < 1e-6:
                outer.append((math.atan2(dx, dy), i))
        outer.sort()
        rings[r] = ([i for _, i in outer], [th for th, _ in outer], cy)
    _fe_cache[key] = rings
    return rings

def fe_frame(path):
    """{ring: (points [(x,y)] outer surface deformed, material angles)}"""
    a = _arrays(path)
    pts = a['Points']; u = a['displacement']
    topo = fe_topology(a)
    out = {}
    for r, (ids, th, cy) in topo.items():
        out[r] = ([(pts[i][0] + u[i][0], pts[i][1] + u[i][1]) for i in ids], th)
    return out, a

def l2_frame(path):
    a = _arrays(path)
    pts = a['Points']; conn = a['connectivity']; offs = a['offsets']
    ringc = a.get('ring')
    out = {}
    start = 0
    for c, o in enumerate(offs):
        ids = conn[start:o]; start = o
        r = ringc[c] if ringc else c + 1
        if r <= 0: continue
        ids = ids[:-1] if ids[0] == ids[-1] else ids
        n = len(ids)
        out[r] = ([(pts[i][0], pts[i][1]) for i in ids], [2 * math.pi * k / n for k in range(n)])
    return out, a

def turning(points, half):
    n = len(points)
    def prev(j):
        if not half or j > 0: return points[(j - 1) % n]
        return (-points[1][0], points[1][1])
    def nxt(j):
        if not half or j + 1 < n: return points[(j + 1) % n]
        return (-points[n - 2][0], points[n - 2][1])
    tt = []
    for j in range(n):
        p = prev(j); q = nxt(j); b = points[j]
        ax, ay = b[0] - p[0], b[1] - p[1]; bx, by = q[0] - b[0], q[1] - b[1]
        tt.append(math.atan2(ax * by - ay * bx, ax * bx + ay * by))
    return tt, prev, nxt

def inverted_arc(points, th, half, tol=None, detail=False):
    n = len(points)
    ppr = 2.0 * (n - 1) if half else float(n)
    if tol is None: tol = 0.1 * 2 * math.pi / ppr
    tt, prev, nxt = turning(points, half)
    share = lambda j: 0.5 if half and (j == 0 or j == n - 1) else 1.0
    total = sum(share(j) * tt[j] for j in range(n))
    o = 1.0 if total >= 0 else -1.0
    L = 0.0; inv = []
    for j in range(n):
        a = abs(math.remainder(th[j], 2 * math.pi))
        if a < 0.5 * math.pi: continue
        if o * tt[j] < -tol:
            pj = points[j]; p = prev(j); q = nxt(j)
            L += share(j) * 0.5 * (math.dist(pj, p) + math.dist(q, pj))
            inv.append(j)
    L = 2 * L if half else L
    return (L, inv, [o * x for x in tt]) if detail else L

_fe_mid = {}
def fe_layer(a, radius):
    pts = a['Points']; conn = a['connectivity']; offs = a['offsets']; ring = a['ring']
    key = (len(pts), radius)
    if key in _fe_mid: return _fe_mid[key]
    nodes_of = {}; start = 0
    for c, o in enumerate(offs):
        nodes_of.setdefault(ring[c], set()).update(conn[start:o]); start = o
    rings = {}
    for r, ids in sorted(nodes_of.items()):
        if r <= 0: continue
        ys = [pts[i][1] for i in ids]; cy = 0.5 * (max(ys) + min(ys))
        lay = sorted((math.atan2(pts[i][0], pts[i][1]-cy), i) for i in ids
                     if abs(math.hypot(pts[i][0], pts[i][1]-cy) - radius) < 1e-6)
        rings[r] = ([i for _, i in lay], [t for t, _ in lay])
    _fe_mid[key] = rings
    return rings

def fe_frame_layer(path, radius):
    a = _arrays(path); pts = a['Points']; u = a['displacement']
    out = {}
    for r, (ids, th) in fe_layer(a, radius).items():
        out[r] = ([(pts[i][0]+u[i][0], pts[i][1]+u[i][1]) for i in ids], th)
    return out, a
