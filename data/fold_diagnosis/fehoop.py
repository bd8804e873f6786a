"""Hoop force N (kN, + tension) per angular station of a ring in the FE frames, from the element stress."""
import frames as F, math, sys
L = 0.0125
_topo = {}
def stations(a, ring):
    key = (len(a['Points']), ring)
    if key in _topo: return _topo[key]
    pts = a['Points']; conn = a['connectivity']; offs = a['offsets']; rg = a['ring']
    els = []; start = 0
    ys = []
    for c, o in enumerate(offs):
        if rg[c] == ring: els.append((c, conn[start:o])); ys += [pts[i][1] for i in conn[start:o]]
        start = o
    cy = 0.5*(max(ys)+min(ys))
    st = {}
    for c, nodes in els:
        corners = nodes[:4]
        angs = [math.atan2(pts[i][0], pts[i][1]-cy) for i in corners]
        th = sum(angs)/4
        lo = [i for i, a_ in zip(corners, angs) if a_ < th]; hi = [i for i, a_ in zip(corners, angs) if a_ >= th]
        st.setdefault(round(math.degrees(th), 3), []).append((c, lo, hi))
    _topo[key] = sorted(st.items())
    return _topo[key]
def hoop(path, ring):
    a = F._arrays(path); pts = a['Points']; u = a['displacement']; s = a['stress']
    out = []
    for th, els in stations(a, ring):
        N = 0.0
        for c, lo, hi in els:
            P = lambda ids: [sum(pts[i][k]+u[i][k] for i in ids)/len(ids) for k in (0, 1)]
            pl, ph = P(lo), P(hi); tx, ty = ph[0]-pl[0], ph[1]-pl[1]; n = math.hypot(tx, ty); tx /= n; ty /= n
            sxx, syy, sxy = s[c]
            stt = sxx*tx*tx + 2*sxy*tx*ty + syy*ty*ty
            N += stt * (F.T/len(els)) * L
        out.append((th, N/1e3))
    return out
if __name__ == '__main__':
    d = sys.argv[1]; ring = int(sys.argv[2]); sel = sys.argv[3].split(',') if len(sys.argv) > 3 else None
    fr = F.pvd_times(d + '/series.pvd')
    for t, p in fr:
        if sel and not any(abs(t*1e3-float(x)) < 0.07 for x in sel): continue
        h = hoop(p, ring)
        print(f"{t*1e3:5.2f} " + ' '.join(f"{th:.0f}:{N:+.2f}" for th, N in h[::4]) + f" | B {h[-1][1]:+.2f}")
