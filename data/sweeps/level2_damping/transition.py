#!/usr/bin/env python3
"""The alternation transition speed of Level 2 and of the FE near 35 m/s (issue 7 (d), session 16, h62):
the speed at which the alternation index first falls through the threshold 0.30 going up in speed,
by linear interpolation between neighbouring speeds.
usage: transition.py REFERENCE.csv SWEEP_DIR [SWEEP_DIR ...]
REFERENCE.csv: data/reference/fe_explicit_48x2.csv (its thesis_v* rows); SWEEP_DIR: ringcrush sweep
of transition_cd.toml (Level 2 per hinge_damping_ratio)."""
import csv, json, os, sys, tomllib
from collections import defaultdict

THRESHOLD = 0.30  # compare/agreement: alternation_threshold


def crossing(points):
    """First downward crossing of THRESHOLD in (speed, index) points sorted by speed; None if none."""
    for (v0, a0), (v1, a1) in zip(points, points[1:]):
        if a0 > THRESHOLD >= a1:
            return v0 + (v1 - v0) * (a0 - THRESHOLD) / (a0 - a1)
    return None


ref_file, *dirs = sys.argv[1:]
fe = sorted((float(r["velocity_m_s"]), float(r["alternation_index"]))
            for r in csv.DictReader(l for l in open(ref_file) if not l.startswith("#")) if r["case"].startswith("thesis_v"))
fe_in = [p for p in fe if 30 <= p[0] <= 42]
print("FE 48x2 index by speed: " + "  ".join(f"{v:g}:{a:.3f}" for v, a in fe_in))
v_fe = crossing(fe)
print(f"FE transition (index through {THRESHOLD}): {v_fe:.2f} m/s" if v_fe else "FE: no crossing")
l2 = defaultdict(list)
for d in dirs:
    for case in sorted(os.listdir(d)):
        p = os.path.join(d, case)
        if not os.path.isfile(os.path.join(p, "summary.json")): continue
        sc = tomllib.load(open(os.path.join(p, "scene.toml"), "rb"))
        s = json.load(open(os.path.join(p, "summary.json")))
        zb = sc["hinge"].get("hinge_damping_ratio", s.get("level2_settings", {}).get("hinge_damping_ratio"))
        dm = sc["hinge"].get("level2_hinge_damper", s.get("level2_settings", {}).get("hinge_damper", "total"))
        l2[(zb, dm)].append((sc["impactor"]["velocity_m_s"], s["alternation_index"]))
for (zb, dm), pts in sorted(l2.items()):
    pts.sort()
    v = crossing(pts)
    print(f"Level 2 zeta_b {zb:g} ({dm}) index by speed: " + "  ".join(f"{x:g}:{a:.3f}" for x, a in pts))
    print(f"Level 2 zeta_b {zb:g} ({dm}) transition: " + (f"{v:.2f} m/s" if v else "no crossing") +
          (f"; Level 2 - FE = {v - v_fe:+.2f} m/s" if v and v_fe else ""))
