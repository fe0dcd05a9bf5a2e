#!/usr/bin/env bash
# Calibration of the default gyro and rigs against the paper's Table 1
# (results/calibration.md explains the choices). Optional, for users; not part
# of the tests. Needs python3 and a built gyrotherm.
#
#   scripts/calibrate.sh               the six figures for scenarios/ (default seeds
#                                      and the mean ± sd over 12 seeds)
#   scripts/calibrate.sh cycle         cycle raw instability and the gyro's temperature
#                                      range over a grid of shield-rig parameters
#   scripts/calibrate.sh warmup        Test 2 against INS power and record length
#   scripts/calibrate.sh noise         the compensated floors against ARW and its
#                                      temperature coefficient
#   scripts/calibrate.sh sensitivity   each parameter ×0.8 and ×1.25, change of every figure
#
# Every candidate is a copy of scenarios/ in a temporary folder with some keys
# changed; the figures are those of `gyrotherm reproduce` (ols on the cycle, the
# cycle fit applied causally to Test 1 and Test 2), computed with simulate, fit
# and compensate so that no figures are drawn.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
export GYROTHERM="${GYROTHERM:-$here/build/app/gyrotherm}"
export SCENARIOS="${SCENARIOS:-$here/scenarios}"
[[ -x "$GYROTHERM" ]] || { echo "no $GYROTHERM: build first (scripts/build.sh)" >&2; exit 2; }
command -v python3 >/dev/null || { echo "python3 is needed" >&2; exit 2; }

python3 - "${1:-check}" <<'PY'
import itertools, json, os, re, shutil, statistics, subprocess, sys, tempfile

BIN, SRC = os.environ["GYROTHERM"], os.environ["SCENARIOS"]
PAPER = dict(c_raw=0.00953, c_aft=0.00185, t1_b=0.0159, t1_a=0.00201, t2_b=0.0025, t2_a=0.0016)
NAMES = dict(c_raw="cycle raw", c_aft="cycle after", t1_b="Test 1 before", t1_a="Test 1 after",
             t2_b="Test 2 before", t2_a="Test 2 after")

def set_key(text, section, key, value):
    """Replace `key = ...` in [section] (None: top level; [[segment]]: the last one)."""
    lines, cur, hit = text.split("\n"), None, None
    for i, line in enumerate(lines):
        m = re.match(r"^\s*\[\[?([^\]]+)\]\]?", line)
        if m:
            cur = m.group(1)
            continue
        m = re.match(r'^("?[\w*^]+"?)\s*=\s*([^#]*?)(\s*#.*)?$', line)
        if m and cur == section and m.group(1).strip('"') == key:
            hit = (i, m)
    if hit is None:
        raise KeyError(f"{section}.{key}")
    i, m = hit
    lines[i] = f"{m.group(1)} = {value!r}" + (f"   {m.group(3).strip()}" if m.group(3) else "")
    return "\n".join(lines)

def candidate(over, seed_offset=0):
    d = tempfile.mkdtemp(prefix="gyrotherm-cal-")
    for f in os.listdir(SRC):
        if f.endswith(".toml"):
            shutil.copy(os.path.join(SRC, f), d)
    for (f, sec, key), v in over.items():
        p = os.path.join(d, f)
        with open(p) as fh:
            t = fh.read()
        with open(p, "w") as fh:
            fh.write(set_key(t, sec, key, v))
    if seed_offset:
        for f in ("cycle.toml", "random.toml", "warmup.toml"):
            p = os.path.join(d, f)
            with open(p) as fh:
                t = fh.read()
            seed = int(re.search(r"^seed = (\d+)", t, re.M).group(1))
            with open(p, "w") as fh:
                fh.write(set_key(t, None, "seed", seed + seed_offset))
    return d

def run(args):
    r = subprocess.run([BIN] + args, capture_output=True, text=True)
    if r.returncode:
        raise RuntimeError(" ".join(args) + ": " + r.stderr)
    return r.stdout

def figures(over, seed_offset=0):
    d = candidate(over, seed_offset)
    try:
        info = {}
        for s in ("cycle", "random", "warmup"):
            info[s] = json.loads(run(["simulate", f"{d}/{s}.toml", "-o", f"{d}/{s}.csv", "--json"]))
        f = json.loads(run(["fit", f"{d}/cycle.csv", "--json", "-o", f"{d}/fit.json"]))
        out = dict(c_raw=f["instability_before_dph"], c_aft=f["instability_after_dph"])
        for s, k in (("random", "t1"), ("warmup", "t2")):
            c = json.loads(run(["compensate", f"{d}/{s}.csv", "--fit", f"{d}/fit.json", "--causal", "--json"]))
            out[k + "_b"], out[k + "_a"] = c["instability_before_dph"], c["instability_after_dph"]
        out["cycle_T"] = (info["cycle"]["gyro_temp_min_c"], info["cycle"]["gyro_temp_max_c"])
        out["soak_c"] = max(info[s]["soak_control_error_c"] for s in ("cycle", "random"))
        return out
    finally:
        shutil.rmtree(d)

def over_seeds(over, n=12):
    runs = [figures(over, 1000 * k) for k in range(n)]
    return {k: (statistics.mean(r[k] for r in runs), statistics.pstdev(r[k] for r in runs)) for k in PAPER}

def pct(k, v):
    return f"{100 * (v / PAPER[k] - 1):+.0f} %"

def line(res, keys=PAPER):
    return "  ".join(f"{k}={res[k]:.5f} ({pct(k, res[k])})" for k in keys)

mode = sys.argv[1]
SH, INS, ROOM, GY = "rig_shield.toml", "rig_ins.toml", "rig_room.toml", "gyro.toml"

if mode == "check":
    r = figures({})
    s = over_seeds({})
    print(f"{'figure':14s} {'paper':>8s} {'default seeds':>22s} {'12 seeds, mean ± sd':>28s}")
    for k in PAPER:
        m, sd = s[k]
        print(f"{NAMES[k]:14s} {PAPER[k]:8.5f} {r[k]:10.5f} ({pct(k, r[k]):>6s}) {m:10.5f} ± {sd:.5f} ({pct(k, m):>6s})")
    print(f"cycle: gyro block {r['cycle_T'][0]:.1f} .. {r['cycle_T'][1]:.1f} °C; "
          f"chamber in soaks within ±{r['soak_c']:.4f} °C")
elif mode == "cycle":
    for C, hA, G in itertools.product([2500.0, 5000.0, 8000.0, 12000.0], [0.8, 1.2, 2.4, 4.0],
                                      [0.15, 0.25, 0.5, 1.0, 2.0]):
        over = {(SH, "case", "capacity_j_per_k"): C, (SH, "case", "convection_w_per_k"): hA,
                (SH, "block", "anode_case_w_per_k"): round(0.4 * G, 3),
                (SH, "block", "far_case_w_per_k"): round(0.6 * G, 3)}
        r = figures(over)
        print(f"C={C:6.0f} J/K  hA={hA:3.1f} W/K  G={G:4.2f} W/K  cycle raw={r['c_raw']:.5f} "
              f"({pct('c_raw', r['c_raw'])})  gyro {r['cycle_T'][0]:6.1f} .. {r['cycle_T'][1]:5.1f} °C", flush=True)
elif mode == "warmup":
    for P, hours in itertools.product([25.0, 35.0, 45.0, 55.0], [6.0, 8.0, 16.0]):
        over = {(INS, "power", "electronics_w"): P, (ROOM, "power", "electronics_w"): P,
                ("warmup.toml", "segment", "duration_h"): hours}
        r = figures(over)
        print(f"P={P:4.0f} W  {hours:4.0f} h  " + line(r, ("t1_b", "t2_b", "t2_a")), flush=True)
elif mode == "noise":
    for N, k in itertools.product([2.5e-4, 2.6e-4, 2.7e-4, 2.8e-4], [1e-4, 2e-4, 3e-4, 4e-4]):
        over = {(GY, "noise", "arw_deg_per_sqrt_h"): N, (GY, "noise", "arw_temp_coeff_per_c2"): k}
        d, s = figures(over), over_seeds(over)
        print(f"ARW={N:.1e} k={k:.0e}  default: " + line(d, ("c_aft", "t1_a", "t2_a")) + "  | 12 seeds: "
              + "  ".join(f"{x}={s[x][0]:.5f} ({pct(x, s[x][0])})" for x in ("c_aft", "t1_a", "t2_a")), flush=True)
elif mode == "sensitivity":
    def current(f, sec, key):
        with open(os.path.join(SRC, f)) as fh:
            text = fh.read()
        cur = None
        for l in text.split("\n"):
            m = re.match(r"^\s*\[\[?([^\]]+)\]\]?", l)
            if m:
                cur = m.group(1)
            m = re.match(r'^("?[\w*^]+"?)\s*=\s*([^#]*?)(\s*#.*)?$', l)
            if m and cur == sec and m.group(1).strip('"') == key:
                val = float(m.group(2))
        return val
    groups = {
        "shield capacity": [(SH, "case", "capacity_j_per_k")],
        "shield h·A": [(SH, "case", "convection_w_per_k")],
        "block-shield G": [(SH, "block", "anode_case_w_per_k"), (SH, "block", "far_case_w_per_k")],
        "INS h·A": [(INS, "case", "convection_w_per_k")],
        "INS power": [(INS, "power", "electronics_w"), (ROOM, "power", "electronics_w")],
        "room h·A": [(ROOM, "case", "convection_w_per_k")],
        "warm-up length": [("warmup.toml", "segment", "duration_h")],
        "sensor tau": [(r, "sensor", "time_constant_s") for r in (SH, INS, ROOM)],
        "ARW": [(GY, "noise", "arw_deg_per_sqrt_h")],
        "ARW k(T)": [(GY, "noise", "arw_temp_coeff_per_c2")],
        "flicker": [(GY, "noise", "bias_instability_dph")],
    }
    base = over_seeds({}, 8)
    for name, keys in groups.items():
        for f in (0.8, 1.25):
            s = over_seeds({k: current(*k) * f for k in keys}, 8)
            print(f"{name:16s} ×{f:<4}  " + "  ".join(f"{k}={100 * (s[k][0] / base[k][0] - 1):+5.1f}%" for k in PAPER),
                  flush=True)
else:
    sys.exit(f"unknown mode '{mode}' (check, cycle, warmup, noise, sensitivity)")
PY
