"""variant.py NAME BASE 'section.key=value' ... : write scene, run L2 CD hinge-shapes, print S, crush, B turning."""
import sys, subprocess, re, os, math, json
import frames as F
name, base = sys.argv[1], sys.argv[2]
binp = os.environ.get('RC', 'build/ringcrush')
txt = open(base).read()
for kv in sys.argv[3:]:
    k, v = kv.split('=', 1); sec, key = k.rsplit('.', 1)
    # find section
    m = re.search(r'^\[' + re.escape(sec) + r'\]\s*$', txt, re.M)
    if not m: txt += f"\n[{sec}]\n"; m = re.search(r'^\[' + re.escape(sec) + r'\]\s*$', txt, re.M)
    start = m.end(); nxt = re.search(r'^\[', txt[start:], re.M); end = start + nxt.start() if nxt else len(txt)
    body = txt[start:end]
    if re.search(r'^' + re.escape(key) + r'\s*=', body, re.M):
        body = re.sub(r'^' + re.escape(key) + r'\s*=.*$', f'{key} = {v}', body, flags=re.M)
    else:
        body = f"\n{key} = {v}" + body
    txt = txt[:start] + body + txt[end:]
os.makedirs('var', exist_ok=True)
sc = f'var/{name}.toml'; open(sc, 'w').write(txt)
out = f'var/{name}'
subprocess.run(['rm', '-rf', out])
r = subprocess.run(['nice', '-n', '5', binp, 'hinge-shapes', sc, '--integrator', 'central_difference', '--frames', '60', '-o', out], capture_output=True, text=True)
if r.returncode: print(r.stdout, r.stderr); sys.exit(1)
s = json.load(open(out + '/summary.json'))
fr = F.pvd_times(out + '/shapes.pvd')
rings, _ = F.l2_frame(fr[-1][1])
Ss = []; tb = []
for rr in range(1, 7):
    pts, th = rings[rr]; L, inv, tt = F.inverted_arc(pts, th, False, detail=True)
    Ss.append(L*1e3); tb.append(math.degrees(tt[len(pts)//2]))
print(f"{name:28s} S {' '.join('%5.1f'%x for x in Ss)} | c {' '.join('%.3f'%x for x in s['crush_ratio'])} | turnB1 {tb[0]:+.1f} | bal {s['energy_balance_error']:.1e}")
