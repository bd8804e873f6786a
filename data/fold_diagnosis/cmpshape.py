import frames as F, math, sys
fe = F.pvd_times(sys.argv[1])  # FE series.pvd
l2 = F.pvd_times(sys.argv[2])  # Level 2 shapes.pvd
times = [float(x) for x in (sys.argv[3].split(',') if len(sys.argv) > 3 else '1,2,2.5,3,4,8,100'.split(','))]
ring = int(sys.argv[4]) if len(sys.argv) > 4 else 1
def near(fr, t): return min(fr, key=lambda x: abs(x[0]-t*1e-3))
for tm in times:
    tf, pf = near(fe, tm); tl, pl = near(l2, tm)
    mid, _ = F.fe_frame_layer(pf, 0.0246)
    L2, _ = F.l2_frame(pl)
    fp, fth = mid[ring]; lp, lth = L2[ring]
    f2, _ = mid[ring+1]; l2p, _ = L2[ring+1]
    n = len(lp)
    # reference: ring (ring+1)'s top A
    fA = f2[0]; lA = l2p[0]
    _, _, ftt = F.inverted_arc(fp, fth, True, detail=True)
    _, _, ltt = F.inverted_arc(lp, lth, False, detail=True)
    print(f"t FE {tf*1e3:.2f} ms, L2 {tl*1e3:.2f} ms ; S_mid FE {F.inverted_arc(fp,fth,True)*1e3:.1f} L2 {F.inverted_arc(lp,lth,False)*1e3:.1f}")
    print(" ang | FE x,y(rel A2) turn/7.5deg | L2 x,y turn")
    for k in range(n//4, n//2+1):
        ang = 360*k/n
        j = int(round(ang/1.875))  # FE mid-layer index (97 pts over 0..180)
        # FE turning summed over the 4 nodes around (window 7.5 deg)
        idx = [i for i in range(j-2, j+3) if 0 <= i < len(fp)]
        w = [0.5 if abs(i-j) == 2 else 1.0 for i in idx]
        if j == len(fp)-1: w = [x for x in w]; tf_sum = 2*sum(ww*ftt[i] for ww, i in zip(w, idx)) - ftt[j]  # mirror
        else: tf_sum = sum(ww*ftt[i] for ww, i in zip(w, idx))
        print(f" {ang:5.1f} | {(fp[j][0]-fA[0])*1e3:6.2f} {(fp[j][1]-fA[1])*1e3:6.2f} {math.degrees(tf_sum):+6.1f} | {(lp[k][0]-lA[0])*1e3:6.2f} {(lp[k][1]-lA[1])*1e3:6.2f} {math.degrees(ltt[k]):+6.1f}")
