"""svgplot.py FE_SERIES_PVD L2_SHAPES_PVD OUT.svg [times_ms]: rings 1-2 mean lines, FE (mid layer) vs Level 2."""
import frames as F, sys
fe = F.pvd_times(sys.argv[1]); l2 = F.pvd_times(sys.argv[2]); out = sys.argv[3]
times = [float(x) for x in (sys.argv[4] if len(sys.argv) > 4 else '0.64,1.04,2.02,100').split(',')]
near = lambda fr, t: min(fr, key=lambda x: abs(x[0]-t*1e-3))
W, H, sc = 330, 300, 5.0  # px per mm
panels = []
for i, tm in enumerate(times):
    tf, pf = near(fe, tm); tl, pl = near(l2, tm)
    mid, _ = F.fe_frame_layer(pf, 0.0246); L2, _ = F.l2_frame(pl)
    yA2f = mid[2][0][0][1]; yA2l = L2[2][0][0][1]
    ox, oy = i*W + W/2, H*0.55
    g = [f'<g><text x="{i*W+10}" y="18" font-size="13">FE {tf*1e3:.2f} ms / Level 2 {tl*1e3:.2f} ms</text>']
    def poly(pts, y0, col, dash=''):
        s = ' '.join(f"{ox+x*1e3*sc:.1f},{oy-(y-y0)*1e3*sc:.1f}" for x, y in pts if abs(x*1e3) < 32 and -25 < (y-y0)*1e3 < 25)
        return f'<polyline points="{s}" fill="none" stroke="{col}" stroke-width="1.6" {dash}/>'
    for r in (1, 2):
        fp = mid[r][0]; full = [(-x, y) for x, y in reversed(fp)] + fp[1:]
        g.append(poly(full, yA2f, '#c0392b'))
        lp = L2[r][0]; g.append(poly(lp + lp[:1], yA2l, '#2471a3', 'stroke-dasharray="4,2"'))
        g.append(''.join(f'<circle cx="{ox+x*1e3*sc:.1f}" cy="{oy-(y-yA2l)*1e3*sc:.1f}" r="1.6" fill="#2471a3"/>' for x, y in lp if abs(x*1e3) < 32 and -25 < (y-yA2l)*1e3 < 25))
    g.append('</g>'); panels.append('\n'.join(g))
svg = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{W*len(times)}" height="{H+30}" font-family="sans-serif">',
       '<rect width="100%" height="100%" fill="white"/>', *panels,
       f'<text x="10" y="{H+20}" font-size="12">mean lines of rings 1 (top) and 2, y relative to ring 2\'s top node, 5 px/mm; red: FE 48x2 (middle node layer); blue dashed with nodes: Level 2 (N = 48, central difference)</text>', '</svg>']
open(out, 'w').write('\n'.join(svg))
