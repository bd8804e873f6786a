"""Reversed turning at B (deg): FE within +-3.75 deg of B (mid layer, half-weight at the window ends), Level 2 node B; and the B gap."""
import frames as F, math, sys, invangle as I
for kind, pvd in zip(sys.argv[1::2], sys.argv[2::2]):
    t, p = F.pvd_times(pvd)[-1]
    res = []
    if kind == 'fe':
        mid, _ = F.fe_frame_layer(p, 0.0246)
        for r in sorted(mid):
            P, th = mid[r]; _, _, tt = F.inverted_arc(P, th, True, detail=True); n = len(P)
            s = tt[n-1] + 2*(tt[n-2] + tt[n-3] + 0.5*tt[n-4] + 0*tt[n-5])  # window 176.25..180 mirrored, = +-3.75 deg
            res.append((math.degrees(-s), I.inv_angle(P, th, True)))
    else:
        rings, _ = F.l2_frame(p)
        for r in sorted(rings):
            P, th = rings[r]; _, _, tt = F.inverted_arc(P, th, False, detail=True); n = len(P)
            res.append((math.degrees(-tt[n//2]), I.inv_angle(P, th, False)))
    print(f"{kind:3s} {pvd:30s} reversed turning at B / total reversed turning of the lower half (deg): " + '  '.join(f"{a:+5.1f}/{b:4.1f}" for a, b in res))
