"""Long work releases the GIL: another Python thread runs while a fit works."""

import threading
import time

import numpy as np

import gyrotherm


def test_a_thread_runs_while_fitting():
    n = 400_000
    t = np.arange(n, dtype=float)
    temp = 20.0 + 20.0 * np.sin(t / n * 2 * np.pi)
    record = {"time_s": t, "temp_c": temp, "gyro_dph": 0.05 * temp + np.random.default_rng(1).normal(0, 0.01, n)}
    ticks = []
    done = threading.Event()

    def tick():
        while not done.is_set():
            ticks.append(time.perf_counter())
            time.sleep(0.001)

    ticker = threading.Thread(target=tick)
    ticker.start()
    start = time.perf_counter()
    gyrotherm.fit(record, model="T + T^2 + dT")
    end = time.perf_counter()
    done.set()
    ticker.join()
    during = [x for x in ticks if start < x < end]
    # A call that held the GIL would leave the ticker no turn between its start and its end (a
    # thread switch needs the GIL); released, the ticker runs throughout, ~1 tick per ms.
    assert end - start > 0.05
    assert len(during) >= 10, (len(during), end - start)
