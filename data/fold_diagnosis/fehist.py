import frames as F, math, sys
d = sys.argv[1]; ring = int(sys.argv[2]) if len(sys.argv) > 2 else 1
step = int(sys.argv[3]) if len(sys.argv) > 3 else 1
def segdist(p, a, b):
    ax, ay = b[0]-a[0], b[1]-a[1]; L2 = ax*ax+ay*ay
    s = max(0, min(1, ((p[0]-a[0])*ax+(p[1]-a[1])*ay)/L2)) if L2 > 0 else 0
    return math.hypot(a[0]+s*ax-p[0], a[1]+s*ay-p[1])
def ringdist(p, pts):  # half ring mirrored
    allp = [(-x, y) for x, y in reversed(pts)] + pts
    return min(segdist(p, allp[k], allp[k+1]) for k in range(len(allp)-1))
print("t_ms  S1_mm  crush1  gapB_mm(outer-outer)  contact arc of ring1 (deg, gap<0.05mm)")
fr = F.pvd_times(d + '/series.pvd')
for t, path in fr[::step]:
    rings, a = F.fe_frame(path)
    p1, th1 = rings[ring]; p2, _ = rings[ring+1]
    S = F.inverted_arc(p1, th1, True)
    ys = [p[1] for p in p1]; c = 1 - (max(ys)-min(ys))/F.D
    B = p1[-1]
    gB = ringdist(B, p2)
    cont = [round(math.degrees(th1[k])) for k in range(len(p1)) if th1[k] > math.pi/2 and ringdist(p1[k], p2) < 5e-5]
    rng = f"{min(cont)}-{max(cont)} ({len(cont)})" if cont else "-"
    print(f"{t*1e3:6.2f} {S*1e3:6.1f} {c:6.3f} {gB*1e3:8.3f}  {rng}")
