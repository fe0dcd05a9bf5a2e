#!/usr/bin/python3
"""Coverage of gyrotherm.fit's 95 % intervals on the shipped cycle with a hidden
temperature gradient, and the temperature sensors' lag as the cause of the
under-coverage of dT and grad (results/sensor_lag_coverage.md).

Usage, from the source folder with the build's Python package (Debian's interpreter):
  PYTHONPATH=build/python /usr/bin/python3 bench/sensor_lag_coverage.py run EXPERIMENT SEED_FROM SEED_TO
  PYTHONPATH=build/python /usr/bin/python3 bench/sensor_lag_coverage.py report [EXPERIMENT ...]
  PYTHONPATH=build/python /usr/bin/python3 bench/sensor_lag_coverage.py mechanism   (the sensor-lag decomposition)
Rows and summaries go to build/sensor_lag_coverage/ (GYROTHERM_COVERAGE_OUT to change it).
results/sensor_lag_coverage.md used `run E 1 1000` for every experiment below (about 0.1 s a seed).

Experiments (each appends one JSON line per seed to OUT/EXPERIMENT.jsonl):
  grad       hidden grad=0.02, model T + T^2 + dT + grad, default intervals (auto)
  control    no hidden effect, model T + T^2 + dT (the paper's), default intervals
  grad_boot  as grad, option intervals=bootstrap (draws=1000)
  grad_ideal as grad on a rig whose temperature sensors are ideal (0.5 s lag,
             no reading noise, no resolution): regressors = the true temperatures
  ctrl_ideal as control on the ideal-sensor rig
  grad_lagonly / grad_readonly  sensors with only the 20 s lag / only reading noise + resolution
  grad_model / grad_boot / ctrl_boot  intervals=model / intervals=bootstrap forced
  grad_delag / ctrl_delag  the scenario's sensors, temperatures de-lagged (T + 20 s * dT/dt) before the fit

Each line also holds the "noise-free" fit: the same record with gyro_dph
replaced by bias_true_dph (the simulator's true bias, no gyro noise). Its
coefficients are what the estimator converges to on that record's measured
temperatures: their difference from the truth is the errors-in-variables /
discretisation bias, which no noise model can cover.
"""
import json
import math
import os
import sys
import time

import numpy as np

import gyrotherm

SOURCE = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SCENARIO = os.path.join(SOURCE, "scenarios", "cycle.toml")
OUT = os.environ.get("GYROTHERM_COVERAGE_OUT", os.path.join(SOURCE, "build", "sensor_lag_coverage"))
# The rig variants are written beside the rows.
IDEAL_RIG = os.path.join(OUT, "rig_shield_ideal_sensor.toml")
LAG_ONLY_RIG = os.path.join(OUT, "rig_shield_lag_only.toml")        # 20 s lag, no reading noise
READ_ONLY_RIG = os.path.join(OUT, "rig_shield_reading_only.toml")   # 0.5 s lag, reading noise + resolution
SENSOR_VARIANTS = {IDEAL_RIG: (0.5, 0.0, 0.0), LAG_ONLY_RIG: (20.0, 0.0, 0.0), READ_ONLY_RIG: (0.5, 0.003, 0.01)}

EXPERIMENTS = {
    "grad": dict(hidden={"grad": 0.02}, model="T + T^2 + dT + grad", option=None, rig=None),
    "control": dict(hidden={}, model="T + T^2 + dT", option=None, rig=None),
    "grad_boot": dict(hidden={"grad": 0.02}, model="T + T^2 + dT + grad",
                      option=["intervals=bootstrap"], rig=None),
    "grad_ideal": dict(hidden={"grad": 0.02}, model="T + T^2 + dT + grad", option=None, rig=IDEAL_RIG),
    "ctrl_ideal": dict(hidden={}, model="T + T^2 + dT", option=None, rig=IDEAL_RIG),
    "grad_lagonly": dict(hidden={"grad": 0.02}, model="T + T^2 + dT + grad", option=None, rig=LAG_ONLY_RIG),
    "grad_readonly": dict(hidden={"grad": 0.02}, model="T + T^2 + dT + grad", option=None, rig=READ_ONLY_RIG),
    "grad_model": dict(hidden={"grad": 0.02}, model="T + T^2 + dT + grad", option=["intervals=model"], rig=None),
    # the scenario's sensors, but both temperature columns de-lagged before the fit:
    # T_corr = T + tau_s * dT/dt (tau_s = 20 s, the rig's sensor time constant; dT/dt by
    # central differences over +-5 s). Tests whether the sensor lag is the cause.
    "grad_delag": dict(hidden={"grad": 0.02}, model="T + T^2 + dT + grad", option=None, rig=None, delag=20.0),
    "ctrl_delag": dict(hidden={}, model="T + T^2 + dT", option=None, rig=None, delag=20.0),
    "ctrl_boot": dict(hidden={}, model="T + T^2 + dT", option=["intervals=bootstrap"], rig=None),
}


def make_sensor_rig(path, tau, noise, resolution):
    """rig_shield.toml with only the [sensor] section changed (everything else the same)."""
    src = open(os.path.join(SOURCE, "scenarios", "rig_shield.toml")).read().splitlines()
    out, section = [], None
    for line in src:
        s = line.strip()
        if s.startswith("["):
            section = s
        if section == "[sensor]" and s.startswith("time_constant_s"):
            line = f"time_constant_s = {tau}"
        elif section == "[sensor]" and s.startswith("noise_c"):
            line = f"noise_c = {noise}"
        elif section == "[sensor]" and s.startswith("resolution_c"):
            line = f"resolution_c = {resolution}"
        out.append(line)
    with open(path, "w") as f:
        f.write("\n".join(out) + "\n")


def delag(t, x, tau, h=5):
    """x + tau * dx/dt, dx/dt by central differences over +-h samples (one-sided at the ends)."""
    x = np.asarray(x, dtype=float)
    d = np.empty_like(x)
    n = len(x)
    d[h:n - h] = (x[2 * h:] - x[:n - 2 * h]) / (t[2 * h:] - t[:n - 2 * h])
    d[:h] = (x[h] - x[0]) / (t[h] - t[0])
    d[n - h:] = (x[-1] - x[-1 - h]) / (t[-1] - t[-1 - h])
    return np.ascontiguousarray(x + tau * d)


def one_fit(data, model, option):
    kw = {}
    if option:
        kw["option"] = option
    f = gyrotherm.fit(data, model=model, **kw)
    d = f.as_dict()
    return f, d


def run(name, seed):
    e = EXPERIMENTS[name]
    sim_kw = {}
    if e["rig"]:
        sim_kw["rig"] = e["rig"]
    t0 = time.time()
    rec = gyrotherm.simulate(SCENARIO, seed=seed, hidden=e["hidden"], **sim_kw)
    t1 = time.time()
    data = rec
    if e.get("delag"):
        t = np.asarray(rec["time_s"], dtype=float)
        data = {"time_s": rec["time_s"], "gyro_dph": rec["gyro_dph"],
                "temp_c": delag(t, rec["temp_c"], e["delag"]),
                "temp2_c": delag(t, rec["temp2_c"], e["delag"])}
    f, d = one_fit(data, e["model"], e["option"])
    t2 = time.time()
    # the same record without gyro noise: the estimator's limit on these regressors
    clean = {k: data[k] for k in ("time_s", "temp_c", "temp2_c")}
    clean["gyro_dph"] = np.ascontiguousarray(rec["bias_true_dph"], dtype=float)
    fc = gyrotherm.fit(clean, model=e["model"])
    t3 = time.time()
    row = dict(
        experiment=name, seed=seed, model=e["model"], hidden=e["hidden"], option=e["option"],
        rig=e["rig"] or "scenario's",
        truth=rec.truth["coefficients"],
        truth_noise=rec.truth.get("noise"),
        coefficients=f.coefficients,
        intervals_95={k: list(v) for k, v in f.intervals_95.items()},
        interval_method=d.get("interval_method"),
        noise=f.noise,
        instability=list(f.instability),
        noise_free_coefficients=fc.coefficients,
        seconds=dict(simulate=t1 - t0, fit=t2 - t1, noise_free_fit=t3 - t2),
    )
    return row


def binomial_cdf(k, n, p):
    """P(X <= k) for X ~ Binomial(n, p), summed in logs (n up to a few thousand)."""
    if p <= 0.0:
        return 1.0
    if p >= 1.0:
        return 1.0 if k >= n else 0.0
    lp, lq = math.log(p), math.log1p(-p)
    terms = [math.lgamma(n + 1) - math.lgamma(j + 1) - math.lgamma(n - j + 1) + j * lp + (n - j) * lq
             for j in range(0, k + 1)]
    top = max(terms)
    return min(1.0, math.exp(top) * sum(math.exp(t - top) for t in terms))


def clopper_pearson(k, n, alpha=0.05):
    """The exact (Clopper-Pearson) 95 % range of a binomial proportion k/n, by bisection."""
    def solve(f):  # the p in (0, 1) where the decreasing f(p) crosses 0
        lo, hi = 0.0, 1.0
        for _ in range(60):
            mid = (lo + hi) / 2
            lo, hi = (mid, hi) if f(mid) > 0 else (lo, mid)
        return (lo + hi) / 2
    lower = 0.0 if k == 0 else solve(lambda p: (1.0 - binomial_cdf(k - 1, n, p)) * -1 + alpha / 2)
    upper = 1.0 if k == n else solve(lambda p: binomial_cdf(k, n, p) - alpha / 2)
    return lower, upper


def load(name):
    path = os.path.join(OUT, f"{name}.jsonl")
    if not os.path.exists(path):
        return []
    rows = [json.loads(l) for l in open(path) if l.strip()]
    seen, out = set(), []
    for r in rows:
        if r["seed"] not in seen:
            seen.add(r["seed"])
            out.append(r)
    return sorted(out, key=lambda r: r["seed"])


def summarise(rows):
    """Per term: coverage vs the truth and vs the noise-free limit, bias/half-width, spread ratio."""
    terms = [t for t in rows[0]["intervals_95"]]
    for t in rows[0]["coefficients"]:
        if t not in terms and t in rows[0]["truth"]:
            terms.append(t)
    out = {}
    for t in terms:
        est = np.array([r["coefficients"][t] for r in rows])
        tru = np.array([r["truth"].get(t, 0.0) for r in rows])
        lim = np.array([r["noise_free_coefficients"][t] for r in rows])
        has = all(t in r["intervals_95"] for r in rows)
        res = dict(n=len(rows), truth=float(tru.mean()), mean_estimate=float(est.mean()),
                   std_estimate=float(est.std(ddof=1)), noise_free_limit=float(lim.mean()),
                   noise_free_limit_sd=float(lim.std(ddof=1)) if len(rows) > 1 else 0.0)
        if has:
            lo = np.array([r["intervals_95"][t][0] for r in rows])
            hi = np.array([r["intervals_95"][t][1] for r in rows])
            hw = (hi - lo) / 2
            k = int(((lo <= tru) & (tru <= hi)).sum())
            k_lim = int(((lo <= lim) & (lim <= hi)).sum())
            se = hw / 1.96
            res.update(
                covered=k, coverage=k / len(rows), coverage_ci=clopper_pearson(k, len(rows)),
                covered_noise_free_limit=k_lim, coverage_noise_free_limit=k_lim / len(rows),
                coverage_noise_free_limit_ci=clopper_pearson(k_lim, len(rows)),
                mean_half_width=float(hw.mean()),
                bias_over_half_width=float(((est - tru) / hw).mean()),
                limit_bias_over_half_width=float(((lim - tru) / hw).mean()),
                spread_over_se=float(est.std(ddof=1) / se.mean()),
                # spread about the noise-free limit (removes the seed-dependence of the limit)
                spread_about_limit_over_se=float((est - lim).std(ddof=1) / se.mean()),
                rms_z=float(np.sqrt((((est - tru) / se) ** 2).mean())),
            )
        out[t] = res
    return out


def noise_summary(rows):
    comps = {}
    for r in rows:
        n = (r.get("noise") or {}).get("components", {})
        for k, v in n.items():
            comps.setdefault(k, []).append(v["value"])
            comps.setdefault(k + " identified", []).append(1.0 if v.get("identified") else 0.0)
    return {k: (float(np.median(v)), float(np.min(v)), float(np.max(v)), len(v)) for k, v in comps.items()}


def report(names):
    for name in names:
        rows = load(name)
        if not rows:
            continue
        s = summarise(rows)
        print(f"\n== {name}: {len(rows)} seeds ({rows[0]['seed']}..{rows[-1]['seed']}), "
              f"model {rows[0]['model']}, hidden {rows[0]['hidden']}, option {rows[0]['option']}, rig {rows[0]['rig']}")
        print(f"   mean s/seed: " + ", ".join(f"{k} {np.mean([r['seconds'][k] for r in rows]):.2f}"
                                             for k in rows[0]["seconds"]))
        print("term | truth | mean est | cover | CP95 | bias/hw | spread/se | noise-free limit | limit-truth/hw | cover of limit | spread about limit/se | mean hw")
        for t, r in s.items():
            if "coverage" not in r:
                print(f"{t} | {r['truth']:.6g} | {r['mean_estimate']:.6g} | (no interval) | | | | {r['noise_free_limit']:.6g}")
                continue
            print(f"{t} | {r['truth']:.6g} | {r['mean_estimate']:.6g} | {r['covered']}/{r['n']} = {100*r['coverage']:.1f} % | "
                  f"{100*r['coverage_ci'][0]:.1f}-{100*r['coverage_ci'][1]:.1f} % | {r['bias_over_half_width']:+.3f} | "
                  f"{r['spread_over_se']:.3f} | {r['noise_free_limit']:.6g} (sd {r['noise_free_limit_sd']:.2g}) | "
                  f"{r['limit_bias_over_half_width']:+.3f} | {100*r['coverage_noise_free_limit']:.1f} % | "
                  f"{r['spread_about_limit_over_se']:.3f} | {r['mean_half_width']:.4g}")
        ns = noise_summary(rows)
        print("   noise model (median [min, max] over seeds): " +
              "; ".join(f"{k} {m:.3g} [{a:.3g}, {b:.3g}] (n={c})" for k, (m, a, b, c) in ns.items()))
        meth = {}
        for r in rows:
            m = r.get("interval_method") or ""
            m = ("bootstrap" if m.startswith("parametric bootstrap") else "analytic (model)") + \
                (", widest of several structures" if "best of several" in m else ", one structure")
            meth[m] = meth.get(m, 0) + 1
        print("   interval methods: " + "; ".join(f"{c}x {m}" for m, c in meth.items()))
        print("   truth noise: " + json.dumps(rows[0].get("truth_noise")))
        with open(os.path.join(OUT, f"{name}.summary.json"), "w") as f:
            json.dump(dict(summary=s, noise=ns), f, indent=1)


def windows(t, x, w=100.0):
    k = np.floor((t - t[0]) / w).astype(int)
    n = np.bincount(k)
    return np.bincount(k, weights=x) / n


def mechanism(seed=1):
    """Why the 20 s sensor lag biases dT and grad: the same thermal run read by ideal and by
    lagged sensors (no reading noise), at the fit's 100 s windows."""
    ideal = gyrotherm.simulate(SCENARIO, seed=seed, hidden={"grad": 0.02}, rig=IDEAL_RIG)
    lag = gyrotherm.simulate(SCENARIO, seed=seed, hidden={"grad": 0.02}, rig=LAG_ONLY_RIG)
    t = np.asarray(ideal["time_s"], float)
    tw = windows(t, t)
    T_i, T_l = windows(t, ideal["temp_c"]), windows(t, lag["temp_c"])
    g_i = windows(t, ideal["temp2_c"] - ideal["temp_c"])
    g_l = windows(t, lag["temp2_c"] - lag["temp_c"])
    dT_i = np.gradient(T_i, tw)
    dT_l = np.gradient(T_l, tw)
    print(f"windows {len(tw)}; grad range {g_i.min():.3f}..{g_i.max():.3f} degC; |dT/dt| max {abs(dT_i).max():.4f} degC/s")
    print(f"corr(dT, grad) over windows: {np.corrcoef(dT_i, g_i)[0, 1]:.4f}")
    X = np.column_stack([T_i, T_i ** 2, dT_i, g_i])
    Xc = X - X.mean(0)
    for j, nm in enumerate(["T", "T^2", "dT", "grad"]):
        others = np.delete(Xc, j, 1)
        r = Xc[:, j] - others @ np.linalg.lstsq(others, Xc[:, j], rcond=None)[0]
        print(f"  VIF {nm}: {Xc[:, j].var() / r.var():.1f}")
    print(f"lagged-sensor error: T rms {np.sqrt(np.mean((T_l - T_i) ** 2)):.4f} degC (max {abs(T_l - T_i).max():.4f}); "
          f"grad rms {np.sqrt(np.mean((g_l - g_i) ** 2)):.5f} degC (max {abs(g_l - g_i).max():.5f})")
    # the omitted term: true bias minus the true model evaluated on the lagged regressors
    b = {"1": -7.07712, "T": -3.05e-4, "T^2": 1.06e-6, "dT": 1.81, "grad": 0.02}
    def model(T, dT, g):
        return b["1"] + b["T"] * T + b["T^2"] * T ** 2 + b["dT"] * dT + b["grad"] * g
    miss_all = model(T_i, dT_i, g_i) - model(T_l, dT_l, g_l)
    miss_grad = b["grad"] * (g_i - g_l)
    miss_T = miss_all - miss_grad
    Xl = np.column_stack([np.ones_like(tw), T_l, T_l ** 2, dT_l, g_l])
    for label, m in (("all", miss_all), ("grad's lag only", miss_grad), ("T's lag only", miss_T)):
        shift = np.linalg.lstsq(Xl, m, rcond=None)[0]
        print(f"omitted term ({label}): rms {np.sqrt(np.mean((m - m.mean()) ** 2)):.2e} deg/h -> coefficient shift "
              f"dT {shift[3]:+.4f}, grad {shift[4]:+.6f}, T {shift[1]:+.3g}, T^2 {shift[2]:+.3g}")
    # is the grad lag error tau * d(grad)/dt?
    dg = np.gradient(g_i, tw)
    print(f"grad_i - grad_l vs 20 s * d(grad)/dt: corr {np.corrcoef(g_i - g_l, 20 * dg)[0, 1]:.4f}, "
          f"ratio of rms {np.std(g_i - g_l) / np.std(20 * dg):.3f}")


def main():
    os.makedirs(OUT, exist_ok=True)
    for path, v in SENSOR_VARIANTS.items():
        make_sensor_rig(path, *v)
    cmd = sys.argv[1]
    if cmd == "run":
        name, a, b = sys.argv[2], int(sys.argv[3]), int(sys.argv[4])
        done = {r["seed"] for r in load(name)}
        with open(os.path.join(OUT, f"{name}.jsonl"), "a") as f:
            for seed in range(a, b + 1):
                if seed in done:
                    continue
                row = run(name, seed)
                f.write(json.dumps(row) + "\n")
                f.flush()
                print(name, seed, {k: round(v, 2) for k, v in row["seconds"].items()}, flush=True)
    elif cmd == "mechanism":
        mechanism()
    elif cmd == "report":
        report(sys.argv[2:] or list(EXPERIMENTS))
    else:
        sys.exit(__doc__)


if __name__ == "__main__":
    main()
