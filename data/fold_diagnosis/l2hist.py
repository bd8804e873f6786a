import frames as F, math, sys
d = sys.argv[1]; ring = int(sys.argv[2]) if len(sys.argv) > 2 else 1
T = F.T
def segdist(p, a, b):
    ax, ay = b[0]-a[0], b[1]-a[1]; L2 = ax*ax+ay*ay
    s = max(0, min(1, ((p[0]-a[0])*ax+(p[1]-a[1])*ay)/L2)) if L2 > 0 else 0
    return math.hypot(a[0]+s*ax-p[0], a[1]+s*ay-p[1])
def ringdist(p, pts):
    n = len(pts); return min(segdist(p, pts[k], pts[(k+1) % n]) for k in range(n))
print("t_ms  S1_mm  crush1  gapB_mm(mean-line dist-t)  contact_nodes_of_ring1_lower(deg)")
for t, path in F.pvd_times(d + '/shapes.pvd')[::4]:
    rings, a = F.l2_frame(path)
    p1, th1 = rings[ring]; p2, _ = rings[ring+1]
    S = F.inverted_arc(p1, th1, False)
    ys = [p[1] for p in p1]; c = 1 - (max(ys)-min(ys)+T)/F.D
    n = len(p1); B = p1[n//2]
    gB = ringdist(B, p2) - T
    cont = [round(360*k/n) for k in range(n//4, n//2+1) if ringdist(p1[k], p2) - T < 0.02*T]
    print(f"{t*1e3:6.2f} {S*1e3:6.1f} {c:6.3f} {gB*1e3:8.3f}  {cont}")
