import frames as F, math, sys
EA = 202e9*0.0016*0.0125
d = sys.argv[1]; ring = int(sys.argv[2]); sel = sys.argv[3].split(',')
fr = F.pvd_times(d + '/shapes.pvd')
for t, p in fr:
    if not any(abs(t*1e3-float(x)) < 0.045 for x in sel): continue
    rings, a = F.l2_frame(p); P = rings[ring][0]; n = len(P); l0 = 2*F.RM*math.sin(math.pi/n)
    N = [EA*(math.dist(P[k], P[(k+1) % n])-l0)/l0/1e3 for k in range(n//2)]
    print(f"{t*1e3:5.2f} " + ' '.join(f"{360*(k+0.5)/n:.0f}:{N[k]:+.2f}" for k in range(0, n//2, 2)) + f" | B {N[-1]:+.2f}")
