"""gyrotherm.simulate against `gyrotherm simulate` with the same scenario and seed."""

import json

import numpy as np
import pytest

import gyrotherm
from conftest import CYCLE, run_cli, without_timing
from test_fit import read_csv


@pytest.fixture(scope="module")
def both(tmp_path_factory):
    folder = tmp_path_factory.mktemp("sim")
    csv = folder / "run.csv"
    summary = json.loads(run_cli("simulate", CYCLE, "--seed", 11, "--hidden", "grad=0.02", "--hidden", "T^3=1e-6",
                                 "-o", csv, "--json"))
    record = gyrotherm.simulate(CYCLE, seed=11, hidden={"grad": 0.02, "T^3": 1e-6})
    return record, csv, summary


def test_the_record_is_the_csv_unrounded(both):
    record, csv, _ = both
    written = read_csv(csv)
    assert list(record) == list(written)
    # the CSV's decimals: time 3, temperatures 5, gyro and bias 9
    for name, decimals in [("time_s", 3), ("chamber_c", 5), ("case_c", 5), ("temp_c", 5), ("temp2_c", 5),
                           ("gyro_dph", 9), ("bias_true_dph", 9)]:
        assert record[name].dtype == np.float64
        np.testing.assert_allclose(record[name], written[name], rtol=0, atol=0.51 * 10.0 ** -decimals)


def test_the_truth_is_the_clis(both):
    record, csv, _ = both
    truth = json.loads(csv.with_suffix(".truth.json").read_text())
    # The CLI's names the file it wrote beside it; a record in memory has none.
    assert truth.pop("record")["file"] == csv.name
    assert "record" not in record.truth
    assert record.truth == truth
    assert record.truth["coefficients"]["grad"] == 0.02


def test_the_summary_is_simulate_json(both):
    record, _, summary = both
    mine = without_timing(record.summary)
    theirs = without_timing(summary)
    assert mine.pop("csv") is None and mine.pop("truth") is None
    theirs.pop("csv"), theirs.pop("truth")
    assert mine == theirs


def test_arrays_own_their_memory_and_outlive_the_record(both):
    record, _, _ = both
    g = record["gyro_dph"]
    assert not g.flags["OWNDATA"]  # a view of the simulator's vector, kept by a capsule
    del record
    assert np.isfinite(g).all()


def test_to_dataframe(both):
    pandas = pytest.importorskip("pandas")
    record, _, _ = both
    frame = record.to_dataframe()
    assert list(frame.columns) == list(record)
    assert len(frame) == len(record["time_s"])


def test_output_writes_the_clis_files(tmp_path):
    gyrotherm.simulate(CYCLE, seed=11, output=tmp_path / "a.csv")
    run_cli("simulate", CYCLE, "--seed", 11, "-o", tmp_path / "b.csv")
    assert (tmp_path / "a.csv").read_bytes() == (tmp_path / "b.csv").read_bytes()


def test_bad_options_are_the_clis_errors():
    with pytest.raises(gyrotherm.InputError, match="no_such.toml"):
        gyrotherm.simulate("no_such.toml")
    with pytest.raises(ValueError, match="nonsense"):
        gyrotherm.simulate(CYCLE, hidden={"nonsense": 1.0})
    with pytest.raises(ValueError, match="colour"):
        gyrotherm.simulate(CYCLE, colour="red")
