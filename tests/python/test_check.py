"""gyrotherm.check: a calibration applied to another log as the firmware applies it, the same
numbers as ``gyrotherm check --json``; a failed limit is data (passed False), bad input an
InputError naming the file and line."""

import json
import math

import numpy as np
import pytest

import gyrotherm
from conftest import run_cli

DPH_TO_RAD_S = math.pi / (180.0 * 3600.0)


def write_log(path, from_c, to_c, seed, curve=0.1):
    """2 h at 1 Hz, temperature from_c → to_c, X bias 50 + 2 d + curve d² °/h (d = T − 30), white noise 30 °/h."""
    rng = np.random.default_rng(seed)
    t = np.arange(7200.0)
    temp = from_c + (to_c - from_c) * t / t[-1]
    d = temp - 30.0
    x = (50.0 + 2.0 * d + curve * d * d + rng.normal(0.0, 30.0, t.size)) * DPH_TO_RAD_S
    y = (rng.normal(0.0, 30.0, t.size)) * DPH_TO_RAD_S
    with open(path, "w") as f:
        f.write("time_s,temp_c,gyro_x (rad/s),gyro_y (rad/s)\n")
        for row in zip(t, temp, x, y):
            f.write(",".join(repr(float(v)) for v in row) + "\n")


def parm(path, curve):
    """ArduPilot's polynomial for the X bias above about 35 °C: B(35 + x) − B(35), ×1e6 rad/s."""
    g1 = (2.0 + 2.0 * curve * 5.0) * DPH_TO_RAD_S * 1e6
    g2 = curve * DPH_TO_RAD_S * 1e6
    with open(path, "w") as f:
        f.write(f"INS_TCAL1_ENABLE 1\nINS_TCAL1_TMIN 10\nINS_TCAL1_TMAX 60\n"
                f"INS_TCAL1_GYR1_X {g1!r}\nINS_TCAL1_GYR2_X {g2!r}\nINS_TCAL1_GYR3_X 0\n")


def test_check_gives_the_numbers_of_the_command_line(tmp_path):
    log = tmp_path / "run2.csv"
    write_log(log, 55.0, 15.0, 1)
    parm(tmp_path / "right.parm", 0.1)
    result = gyrotherm.check(log, tmp_path / "right.parm", gyro_col="gyro_x (rad/s),gyro_y (rad/s)", max_residual=15)
    assert result.passed is True
    cli = json.loads(run_cli("check", log, "--params", tmp_path / "right.parm", "--gyro-col",
                             "gyro_x (rad/s),gyro_y (rad/s)", "--max-residual", "15", "--json"))
    assert result.as_dict() == cli
    x = result.as_dict()["axes"][0]
    assert x["before_dph"] > 4.0 * x["after_dph"]  # the curve is taken out
    assert x["after_dph"] < 4.5  # to the noise of a 100 s mean, 30/√100 °/h


def test_a_failed_limit_is_data_and_bad_input_an_error(tmp_path):
    log = tmp_path / "run2.csv"
    write_log(log, 55.0, 15.0, 2)
    parm(tmp_path / "line.parm", 0.0)  # misses the 0.1 °/h/°C² curve
    result = gyrotherm.check(log, tmp_path / "line.parm", gyro_col="gyro_x (rad/s)", max_residual=15)
    assert result.passed is False
    assert "residual_over_limit" in result.findings
    assert result.as_dict()["axes"][0]["residual_dph"] > 30.0
    (tmp_path / "bad.parm").write_text("INS_TCAL1_TMIN 10\nINS_TCAL1_TMAX ten\n")
    with pytest.raises(gyrotherm.InputError, match=r"bad.parm:2: INS_TCAL1_TMAX: 'ten' is not a finite number"):
        gyrotherm.check(log, tmp_path / "bad.parm", gyro_col="gyro_x (rad/s)")
