import frames as F, math, sys
fe = F.pvd_times(sys.argv[1]); l2 = F.pvd_times(sys.argv[2]); ring = 1
tmax = float(sys.argv[3]) if len(sys.argv) > 3 else 3.0
def segdist(p, a, b):
    ax, ay = b[0]-a[0], b[1]-a[1]; L2 = ax*ax+ay*ay
    s = max(0, min(1, ((p[0]-a[0])*ax+(p[1]-a[1])*ay)/L2)) if L2 > 0 else 0
    return math.hypot(a[0]+s*ax-p[0], a[1]+s*ay-p[1])
def rd(p, pts, half):
    allp = ([(-x, y) for x, y in reversed(pts)] + pts) if half else pts + pts[:1]
    return min(segdist(p, allp[k], allp[k+1]) for k in range(len(allp)-1))
print("  t  | FE: turn window(deg) 157.5 165 172.5 B | gap(mm) at 165 172.5 B || L2: turn 157.5 165 172.5 B | gap 165 172.5 B")
for tl, pl in l2:
    if tl > tmax*1e-3: break
    tf, pf = min(fe, key=lambda x: abs(x[0]-tl))
    if abs(tf - tl) > 4e-5: continue
    mid, _ = F.fe_frame_layer(pf, 0.0246); L2, _ = F.l2_frame(pl)
    fp, fth = mid[1]; lp, lth = L2[1]
    _, _, ftt = F.inverted_arc(fp, fth, True, detail=True)
    _, _, ltt = F.inverted_arc(lp, lth, False, detail=True)
    def fwin(j):
        s = 0
        for i in range(j-2, j+3):
            w = 0.5 if abs(i-j) == 2 else 1.0
            ii = i if i < len(fp) else 2*(len(fp)-1)-i
            s += w*ftt[ii]
        return math.degrees(s)
    fj = [84, 88, 92, 96]; lj = [21, 22, 23, 24]
    fg = [ (rd(fp[j], mid[2][0], True) - F.T)*1e3 for j in fj[1:]]
    lg = [ (rd(lp[k], L2[2][0], False) - F.T)*1e3 for k in lj[1:]]
    print(f"{tl*1e3:5.2f}| " + ' '.join(f"{fwin(j):+6.1f}" for j in fj) + " | " + ' '.join(f"{g:+6.2f}" for g in fg)
          + " || " + ' '.join(f"{math.degrees(ltt[k]):+6.1f}" for k in lj) + " | " + ' '.join(f"{g:+6.2f}" for g in lg))
