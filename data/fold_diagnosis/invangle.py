import frames as F, math, sys
def inv_angle(points, th, half):
    tt, prev, nxt = F.turning(points, half)
    n = len(points)
    share = lambda j: 0.5 if half and (j == 0 or j == n-1) else 1.0
    o = 1.0 if sum(share(j)*tt[j] for j in range(n)) >= 0 else -1.0
    s = 0.0
    for j in range(n):
        if abs(math.remainder(th[j], 2*math.pi)) < 0.5*math.pi: continue
        v = o*tt[j]
        if v < 0: s += share(j)*v
    return math.degrees(-(2*s if half else s))
def report(kind, path):
    if kind == 'fe':
        out, _ = F.fe_frame_layer(path, 0.0254); mid, _ = F.fe_frame_layer(path, 0.0246)
        S = [F.inverted_arc(*out[r], True)*1e3 for r in sorted(out)]
        A = [inv_angle(*mid[r], True) for r in sorted(mid)]
        Ao = [inv_angle(*out[r], True) for r in sorted(out)]
        return S, A, Ao
    rings, _ = F.l2_frame(path)
    S = [F.inverted_arc(*rings[r], False)*1e3 for r in sorted(rings)]
    A = [inv_angle(*rings[r], False) for r in sorted(rings)]
    return S, A, None
if __name__ == '__main__':
    for kind, pvd in zip(sys.argv[1::2], sys.argv[2::2]):
        t, p = F.pvd_times(pvd)[-1]
        S, A, Ao = report(kind, p)
        print(f"{kind:3s} {pvd:32s} S(mm) {' '.join('%5.1f'%x for x in S)} | inverted angle (deg) {' '.join('%5.1f'%x for x in A)}" + (f" | outer {' '.join('%5.1f'%x for x in Ao)}" if Ao else ''))
