#!/usr/bin/env python3
"""Gathers the FE reference runs (ringcrush fe ... --solver explicit --threads 1) into one CSV.
usage: gather_fe_reference.py OUT_DIR TIME_DIR HEADER_FILE [--partial] > data/reference/fe_explicit_velocity.csv
--partial: leave out the cases OUT_DIR does not hold (a subset, e.g. fe_explicit_48x2.csv)."""
import json, sys, os
out, tdir, header = sys.argv[1:4]
partial = "--partial" in sys.argv[4:]
cases = [f"thesis_v{v}" for v in (15, 20, 25, 30, 35, 40, 45, 50)] + [f"test30_{j}" for j in ("welded", "free", "plates")]
sys.stdout.write(open(header).read())
cols = ["case", "base_scene", "joints", "velocity_m_s"] + [f"crush_{i}" for i in range(1, 7)] + \
       [f"wrap_{i}" for i in range(1, 7)] + ["alternation_index", "plastic_J", "absorbed_J", "initial_kinetic_energy_J",
       "energy_balance_error", "arrest_time_s", "steps", "cpu_s"]
print(",".join(cols))
for c in cases:
    if partial and not os.path.isfile(os.path.join(out, c, "summary.json")): continue
    d = json.load(open(os.path.join(out, c, "summary.json")))
    scene = "thesis_dynamic" if c.startswith("thesis") else c
    joints = "welded" if c.startswith("thesis") else c.split("_")[1]
    v = float(c[len("thesis_v"):]) if c.startswith("thesis") else 27.7
    e = d["final_energy_J"]
    ke0 = d["initial_kinetic_energy_J"]
    absorbed = ke0 - e["kinetic"] - e["elastic"]
    u, s, _ = open(os.path.join(tdir, f"time_{c}.txt")).read().split()[-3:]
    row = [c, scene, joints, f"{v:g}"] + [f"{x:.4f}" for x in d["crush_ratio"]] + \
          [str(int(w)) for w in d["wrap_around"]] + [f"{d['alternation_index']:.4f}", f"{e['plastic']:.3f}",
          f"{absorbed:.3f}", f"{ke0:.3f}", f"{d['energy_balance_error']:.2e}", f"{d['arrest_time_s']:.5f}",
          str(d["steps"]), f"{float(u) + float(s):.1f}"]
    print(",".join(row))
