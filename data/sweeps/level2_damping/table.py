#!/usr/bin/env python3
"""Markdown rows: per case, FE against Level 2 at two settings (h53). usage: REF NEW_DIRS... -- OLD_DIRS... with label=dir, zb"""
import csv, json, os, sys, tomllib
ref_file = sys.argv[1]; zb_new, zb_old = float(sys.argv[2]), float(sys.argv[3]); dirs = sys.argv[4:]
ref = {r["case"]: r for r in csv.DictReader(l for l in open(ref_file) if not l.startswith("#"))}
def sign(a, b): d = b - a; return 0 if abs(d) < 0.05 else (1 if d > 0 else -1)
runs = {}
for a in dirs:
    label, d = a.split("=", 1)
    for case in sorted(os.listdir(d)):
        p = os.path.join(d, case)
        if not os.path.isfile(os.path.join(p, "summary.json")): continue
        sc = tomllib.load(open(os.path.join(p, "scene.toml"), "rb")); s = json.load(open(os.path.join(p, "summary.json")))
        v = sc["impactor"]["velocity_m_s"]; key = f"thesis_v{v:g}" if label == "thesis" else label
        runs[(key, sc["hinge"]["hinge_damping_ratio"], sc["hinge"]["membrane_damping_ratio"])] = s
def wr(w): 
    r = [str(i + 1) for i, x in enumerate(w) if x]; return ",".join(r) if r else "none"
def fails(fc, fw, fa, fp, s):
    hc = s["crush_ratio"]; hw = [bool(x) for x in s["wrap_around"]]; ha = s["alternation_index"]
    f = []
    if [bool(x) for x in fw] != hw: f.append("wraps")
    same = sum(sign(fc[i], fc[i+1]) == sign(hc[i], hc[i+1]) for i in range(5))
    if not (((fa > 0.3) == (ha > 0.3)) and same / 5 >= 0.75): f.append("alternation")
    if max(abs(hc[i] - fc[i]) for i in range(6)) > 0.15: f.append("crush")
    if abs(s["final_energy_J"]["plastic"] / fp - 1) > 0.15: f.append("absorbed")
    return f
print("| case | FE crush per ring | L2 crush per ring | FE wraps | L2 wraps | alternation FE / L2 | largest Δc (ζ_b 1) | plastic L2/FE (ζ_b 1) | failing (ζ_b 1) | IDA steps (ζ_b 1) |")
print("|---|---|---|---|---|---|---:|---:|---|---:|")
for c in ref:
    r = ref[c]; n = runs.get((c, zb_new, 1.0)); o = runs.get((c, zb_old, 1.0))
    if not n or not o: continue
    fc = [float(r[f"crush_{i}"]) for i in range(1, 7)]; fw = [int(r[f"wrap_{i}"]) for i in range(1, 7)]
    fa = float(r["alternation_index"]); fp = float(r["plastic_J"])
    dn = max(abs(n["crush_ratio"][i] - fc[i]) for i in range(6)); do = max(abs(o["crush_ratio"][i] - fc[i]) for i in range(6))
    fn = fails(fc, fw, fa, fp, n) or ["none"]; fo = fails(fc, fw, fa, fp, o) or ["none"]
    name = f"{float(r['velocity_m_s']):g} m/s" if c.startswith("thesis") else c.replace("test30_", "Test 30 ")
    print(f"| {name} | {' '.join(f'{x:.2f}' for x in fc)} | {' '.join(f'{x:.2f}' for x in n['crush_ratio'])} | {wr(fw)} | {wr(n['wrap_around'])} ({wr(o['wrap_around'])}) | "
          f"{fa:.2f} / {n['alternation_index']:.2f} ({o['alternation_index']:.2f}) | {dn:.3f} ({do:.3f}) | "
          f"{n['final_energy_J']['plastic']/fp:.2f} ({o['final_energy_J']['plastic']/fp:.2f}) | {', '.join(fn)} ({', '.join(fo)}) | {n['steps']} ({o['steps']}) |")
