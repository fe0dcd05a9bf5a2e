"""gyrotherm.fit against `gyrotherm fit` on the same input, and arrays against files."""

import json

import numpy as np
import pytest

import gyrotherm
from conftest import CYCLE, cli_json, run_cli, without_timing


def read_csv(path):
    """The CSV's columns as float64 arrays (numpy only; '#' lines skipped)."""
    with open(path) as f:
        lines = [line for line in f if not line.startswith("#")]
    names = lines[0].strip().split(",")
    values = np.loadtxt(lines[1:], delimiter=",", ndmin=2)
    return {name: values[:, k].copy() for k, name in enumerate(names)}


def test_a_path_gives_the_cli_json(cycle_csv):
    result = gyrotherm.fit(cycle_csv)
    assert without_timing(json.loads(result.to_json())) == cli_json("fit", cycle_csv)


def test_options_are_the_clis(cycle_csv):
    kw = dict(model="T + T^2 + dT + grad", avg=200, deriv_span=900.0, outlier_threshold=6)
    result = gyrotherm.fit(cycle_csv, **kw)
    cli = cli_json("fit", cycle_csv, "--model", "T + T^2 + dT + grad", "--avg", 200, "--deriv-span", 900,
                   "--outlier-threshold", 6)
    assert without_timing(result.as_dict()) == cli
    assert result.as_dict()["pipeline"]["avg_s"] == 200


def test_each_option_states_its_default_once():
    rows = {r["keyword"]: r for r in gyrotherm.options("fit")}
    assert rows["avg"]["default"] == "100"
    assert rows["avg"]["help"].endswith("(default: 100)")
    assert rows["model"]["default"] == "'T + T^2 + dT'"
    assert rows["imu"]["default"] == "the first with a temperature"
    assert rows["add"]["default"] == ""  # a list: empty by default
    assert rows["avg"]["help"].count("default") == 1


def test_the_summary_is_the_clis_table(cycle_csv):
    text = gyrotherm.fit(cycle_csv, model="T + T^2").summary()
    cli = run_cli("fit", cycle_csv, "--model", "T + T^2")
    timing = lambda s: [l for l in s.splitlines() if not l.startswith("engine:")]
    assert timing(text) == timing(cli)
    assert "instability" in text


def test_arrays_give_the_files_fit(cycle_csv):
    columns = read_csv(cycle_csv)
    from_arrays = gyrotherm.fit(columns).as_dict()
    from_file = gyrotherm.fit(cycle_csv).as_dict()
    assert from_arrays["data"]["file"] == "arrays"
    assert "sha256" not in from_arrays["data"]  # arrays have no bytes to hash
    assert len(from_file["data"].pop("sha256")) == 64
    for d in (from_arrays, from_file):
        d["data"].pop("file")
        d.pop("truth", None), d.pop("truth_parameters", None), d.pop("coefficient_error", None)
    assert without_timing(from_arrays) == without_timing(from_file)


def test_a_dataframe_gives_the_arrays_fit(cycle_csv):
    pandas = pytest.importorskip("pandas")
    columns = read_csv(cycle_csv)
    frame = pandas.DataFrame(columns)
    frame["label"] = "x"  # a text column the record does not use is left alone
    a = gyrotherm.fit(frame, model="T + dT")
    b = gyrotherm.fit(columns, model="T + dT")
    assert a.coefficients == b.coefficients


def test_coefficients_and_intervals_are_keyed_by_term(cycle_csv):
    r = gyrotherm.fit(cycle_csv, model="T + T^2 + dT")
    assert set(r.coefficients) == {"1", "T", "T^2", "dT"}
    assert set(r.intervals_95) == {"T", "T^2", "dT"}
    for term, (lo, hi) in r.intervals_95.items():
        assert lo < r.coefficients[term] < hi
    before, after = r.instability
    assert after < before
    assert r.noise["method"]


def test_a_simulated_record_is_fitted_against_its_truth():
    record = gyrotherm.simulate(CYCLE, seed=5, hidden={"grad": 0.02})
    r = gyrotherm.fit(record, model="T + T^2 + dT + grad")
    d = r.as_dict()
    assert d["truth"]["grad"] == pytest.approx(0.02)
    lo, hi = r.intervals_95["grad"]
    assert hi - lo < 0.02  # the record pins the hidden gradient down
    assert abs(r.coefficients["grad"] - 0.02) < 3 * (hi - lo)


def test_windows_and_residuals(cycle_csv):
    r = gyrotherm.fit(cycle_csv)
    w = r.windows
    assert len(w["time_s"]) == r.as_dict()["data"]["windows"]
    np.testing.assert_allclose(w["residual_dph"], w["gyro_dph"] - w["model_dph"], atol=1e-12)
    assert np.std(w["residual_dph"]) == pytest.approx(r.instability[1], rel=0.02)


def test_predict_is_compensate_model(cycle_csv, cycle_fit_file, tmp_path):
    r = gyrotherm.fit(cycle_csv)
    model = r.predict(cycle_csv)
    out = tmp_path / "comp.csv"
    run_cli("compensate", cycle_csv, "--fit", cycle_fit_file, "-o", out)
    np.testing.assert_allclose(model, read_csv(out)["model_dph"], atol=1e-9)  # the CSV's 9 decimals


def test_several_channels(tmp_path, cycle_csv):
    columns = read_csv(cycle_csv)
    columns["gyro_b"] = columns["gyro_dph"] * 0.5 + 1.0
    r = gyrotherm.fit(columns, gyro_col="gyro_dph,gyro_b", model="T")
    assert set(r.channels) == {"gyro_dph", "gyro_b"}
    assert r.channels["gyro_b"].coefficients["T"] == pytest.approx(0.5 * r.channels["gyro_dph"].coefficients["T"],
                                                                   rel=1e-6)
    with pytest.raises(ValueError, match="channels"):
        r.coefficients


def test_saved_fit_is_the_cli_fit_file(cycle_csv, cycle_fit_file, tmp_path):
    r = gyrotherm.fit(cycle_csv, output=tmp_path / "py.json")
    assert without_timing(json.loads((tmp_path / "py.json").read_text())) == \
        without_timing(json.loads(cycle_fit_file.read_text()))
    assert r.file == tmp_path / "py.json" or str(r.file) == str(tmp_path / "py.json")
