import frames as F, math, sys
fe = F.pvd_times(sys.argv[1]); l2 = F.pvd_times(sys.argv[2])  # FE series.pvd, Level 2 shapes.pvd
wins = [(0.4, 0.64), (0.64, 0.88), (0.88, 1.14), (1.14, 1.54), (1.54, 2.02), (2.02, 3.0)]
def near(fr, t): return min(fr, key=lambda x: abs(x[0]-t*1e-3))
def fe_peeq(path):
    a = F._arrays(path); pts = a['Points']; conn = a['connectivity']; offs = a['offsets']; rg = a['ring']; pe = a['PEEQ']
    ys = []; els = []; start = 0
    for c, o in enumerate(offs):
        if rg[c] == 1: els.append((c, conn[start:o])); ys += [pts[i][1] for i in conn[start:o]]
        start = o
    cy = 0.5*(max(ys)+min(ys)); st = {}
    for c, nodes in els:
        th = sum(math.atan2(pts[i][0], pts[i][1]-cy) for i in nodes[:4])/4
        st.setdefault(round(math.degrees(th)/7.5)*7.5, []).append(pe[c])
    return {k: sum(v) for k, v in st.items()}   # sum of element-average PEEQ in 7.5 deg bins
def l2_abar(path):
    rings, a = F.l2_frame(path)
    # plastic_rotation point array: ring 1 first, 48 nodes
    pr = a['plastic_rotation']; n = len(rings[1][0])
    return {360*k/n: math.degrees(pr[k]) for k in range(n)}
print("plastic increments per window, ring 1 lower arc; FE: sum of element PEEQ increments per 7.5 deg bin (x100); L2: d(abar) deg per node")
angs = [120, 127.5, 135, 142.5, 150, 157.5, 165, 172.5, 180]
print(" window(ms)   | FE " + ' '.join('%6.1f' % a for a in angs) + " | L2 " + ' '.join('%6.1f' % a for a in angs))
for a_, b_ in wins:
    f0 = fe_peeq(near(fe, a_)[1]); f1 = fe_peeq(near(fe, b_)[1])
    l0 = l2_abar(near(l2, a_)[1]); l1 = l2_abar(near(l2, b_)[1])
    print(f" {a_:4.2f}-{b_:4.2f} | FE " + ' '.join('%6.2f' % (100*(f1[x]-f0[x])) for x in angs) + " | L2 " + ' '.join('%6.1f' % (l1[x]-l0[x]) for x in angs))
