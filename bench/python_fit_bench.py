#!/usr/bin/python3
"""gyrotherm.fit on a record already in numpy arrays, against the C++ library's own
fit of the same arrays (bench_table's BM_FitTable, reading them from a raw file),
and the fit's peak memory beyond the arrays.

    PYTHONPATH=build/python /usr/bin/python3 bench/python_fit_bench.py [ROWS] [--json OUT]

The record: bench_table's formula (1 Hz; a chamber cycling ±30 °C about 20 °C
every 6 h; g = −7 − 0.03 T + 0.001 T² + 20 dT/dt + white noise of 0.5 °/h, a
+25 °/h glitch every 100 003rd sample), the noise drawn by numpy from a seed.
Both sides fit `T + T^2 + dT` with ols on the same float64 arrays (the C++
benchmark reads them from a raw file); each is timed REPEATS times and the
medians compared. Memory:
the peak resident set (VmHWM, reset through /proc/self/clear_refs before the fit)
minus the resident set with the arrays made, in this process.
"""

import json
import os
import statistics
import subprocess
import sys
import tempfile
import time

import numpy as np

import gyrotherm

REPEATS = 5


def record(n, seed=1):
    t = np.arange(n, dtype=np.float64)
    w = 2.0 * np.pi / 21600.0
    temp = 20.0 + 30.0 * np.sin(w * t)
    gyro = -7.0 - 0.03 * temp + 0.001 * temp * temp + 20.0 * 30.0 * w * np.cos(w * t)
    gyro += np.random.default_rng(seed).normal(0.0, 0.5, n)
    gyro[::100003] += 25.0
    return {"time_s": t, "temp_c": temp, "gyro_dph": gyro}


def status_kb(field):
    with open("/proc/self/status") as f:
        for line in f:
            if line.startswith(field + ":"):
                return int(line.split()[1])
    raise RuntimeError(field)


def main():
    argv = sys.argv[1:]
    out = None
    if "--json" in argv:
        k = argv.index("--json")
        out = argv[k + 1]
        del argv[k:k + 2]
    n = int(float(argv[0])) if argv else 10_000_000
    data = record(n)
    arrays_mb = sum(a.nbytes for a in data.values()) / 2**20

    # Peak memory of one fit beyond the arrays.
    rss_before = status_kb("VmRSS")
    with open("/proc/self/clear_refs", "w") as f:
        f.write("5")  # resets VmHWM to the current RSS
    gyrotherm.fit(data, model="T + T^2 + dT")
    peak_extra_mb = (status_kb("VmHWM") - rss_before) / 1024.0

    # Python and C++ in turn, REPEATS times each (one BM_FitTable run per turn), so that both
    # see the same load on a shared machine.
    bench = os.environ.get("GYROTHERM_BENCH_TABLE_PROGRAM",
                           os.path.join(os.path.dirname(__file__), "..", "build", "bench", "bench_table"))
    unit = {"ns": 1e-9, "us": 1e-6, "ms": 1e-3, "s": 1.0}
    seconds, cpu, cpp_wall, cpp_cpu = [], [], [], []
    with tempfile.TemporaryDirectory() as folder:
        raw = os.path.join(folder, "record.f64")
        np.stack([data["time_s"], data["temp_c"], data["gyro_dph"]], axis=1).tofile(raw)
        for _ in range(REPEATS):
            start, start_cpu = time.perf_counter(), time.process_time()
            gyrotherm.fit(data, model="T + T^2 + dT")
            seconds.append(time.perf_counter() - start)
            cpu.append(time.process_time() - start_cpu)
            done = subprocess.run([bench, "--benchmark_filter=BM_FitTable", "--benchmark_format=json"],
                                  env=dict(os.environ, GYROTHERM_BENCH_TABLE=raw), capture_output=True, text=True,
                                  check=True)
            run = [b for b in json.loads(done.stdout)["benchmarks"] if b.get("run_type") == "iteration"][0]
            cpp_wall.append(run["real_time"] * unit[run["time_unit"]])
            cpp_cpu.append(run["cpu_time"] * unit[run["time_unit"]])
    python_s, python_cpu_s = statistics.median(seconds), statistics.median(cpu)
    cpp_s, cpp_cpu_s = statistics.median(cpp_wall), statistics.median(cpp_cpu)

    # The ratio is of CPU seconds (both single-threaded here): on a shared machine the wall
    # clock also counts the other jobs' turns.
    result = {"rows": n, "arrays_mb": round(arrays_mb, 1), "python_fit_s": round(python_s, 3),
              "cpp_fit_s": round(cpp_s, 3), "python_fit_cpu_s": round(python_cpu_s, 3),
              "cpp_fit_cpu_s": round(cpp_cpu_s, 3), "ratio": round(python_cpu_s / cpp_cpu_s, 3),
              "peak_beyond_arrays_mb": round(peak_extra_mb, 1), "repeats": REPEATS}
    print(json.dumps(result, indent=2))
    if out:
        with open(out, "w") as f:
            json.dump(result, f, indent=2)
            f.write("\n")


if __name__ == "__main__":
    main()
