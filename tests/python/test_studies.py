"""diagnose, allan, compensate, export, plan, effects, engines against the CLI on the same input."""

import json

import numpy as np
import pytest

import gyrotherm
from conftest import CYCLE, cli_json, run_cli, without_timing
from test_fit import read_csv


def test_effects_and_engines_are_the_clis():
    assert gyrotherm.effects() == json.loads(run_cli("effects", "--json"))
    assert gyrotherm.engines() == json.loads(run_cli("engines", "--json"))


def test_diagnose_is_the_clis(cycle_csv):
    d = gyrotherm.diagnose(cycle_csv, model="T + T^2 + dT")
    assert without_timing(d.as_dict()) == cli_json("diagnose", cycle_csv, "--model", "T + T^2 + dT")
    assert d.missing_effects[0]["term"] == "grad"  # the hidden effect is named first
    with_it = gyrotherm.diagnose(cycle_csv, model="T + T^2 + dT", add=["grad"])
    ba = with_it.as_dict()["before_after"]
    assert with_it.as_dict()["instability_dph"] < ba["instability_before_dph"]


def test_diagnose_on_arrays_is_the_files(cycle_csv):
    a = gyrotherm.diagnose(read_csv(cycle_csv), model="T + T^2 + dT").as_dict()
    b = gyrotherm.diagnose(cycle_csv, model="T + T^2 + dT").as_dict()
    assert [m["term"] for m in a["missing_effects"]] == [m["term"] for m in b["missing_effects"]]
    assert a["instability_dph"] == b["instability_dph"]


def test_diagnose_on_arrays_suggests_a_python_call(cycle_csv):
    d = gyrotherm.diagnose(read_csv(cycle_csv), model="T + T^2 + dT")
    model = d.as_dict()["next_command"].split("--model ")[1].strip('"')
    assert "grad" in model
    assert d.next_call == f'gyrotherm.diagnose(data, model="{model}")'
    assert f"next: {d.next_call}\n" in d.summary() and "gyrotherm diagnose arrays" not in d.summary()
    # On a file the report keeps the command line.
    assert "next: gyrotherm diagnose " in gyrotherm.diagnose(cycle_csv, model="T + T^2 + dT").summary()


def test_the_next_call_repeats_the_data_options_and_runs(cycle_csv):
    data = read_csv(cycle_csv)
    d = gyrotherm.diagnose(data, model="T + T^2 + dT", avg=200, deriv_span=900)
    assert d.as_dict()["next"]["options"] == {"avg": "200", "deriv_span": "900"}
    call = d.next_call
    assert call.endswith(", avg=200, deriv_span=900)"), call
    again = eval(call, {"gyrotherm": gyrotherm, "data": data})  # runs as printed
    assert again.as_dict()["model"] == d.as_dict()["next"]["model"]


def test_diagnose_on_arrays_of_several_channels_suggests_each_channels_call(cycle_csv):
    data = dict(read_csv(cycle_csv))
    data["gyro a"] = data["gyro_dph"]  # a channel name with a space
    data["gyro_b"] = data["gyro_dph"] + 1e-4 * np.sin(np.arange(len(data["gyro_dph"])))
    d = gyrotherm.diagnose(data, model="T + T^2 + dT", gyro_col="gyro a,gyro_b")
    calls = d.next_call
    assert set(calls) == {"gyro a", "gyro_b"}
    assert calls["gyro a"].endswith(", gyro_col='gyro a')") and calls["gyro_b"].endswith(", gyro_col='gyro_b')")
    for call in calls.values():
        assert f"next: {call}\n" in d.summary()


def test_a_saved_fit_result_is_read_from_its_file(cycle_csv, tmp_path):
    r = gyrotherm.fit(cycle_csv)
    saved = r.save(tmp_path / "f.json")
    a = gyrotherm.allan(read_csv(cycle_csv), fit=r).as_dict()
    c = gyrotherm.compensate(read_csv(cycle_csv), r).as_dict()
    assert a["fit"] == saved and c["fit"] == saved
    assert a == gyrotherm.allan(read_csv(cycle_csv), fit=saved).as_dict()


def test_allan_is_the_clis(cycle_csv, cycle_fit_file):
    a = gyrotherm.allan(cycle_csv, fit=cycle_fit_file)
    assert without_timing(a.as_dict()) == cli_json("allan", cycle_csv, "--fit", cycle_fit_file)
    b = gyrotherm.allan(cycle_csv, taus="decade", ci=0.95)
    assert without_timing(b.as_dict()) == cli_json("allan", cycle_csv, "--taus", "decade", "--ci", 0.95)


def test_allan_with_an_unsaved_fit_and_arrays(cycle_csv, cycle_fit_file):
    r = gyrotherm.fit(cycle_csv)
    a = gyrotherm.allan(read_csv(cycle_csv), fit=r).as_dict()
    b = gyrotherm.allan(cycle_csv, fit=cycle_fit_file).as_dict()
    assert [s["adev_dph"] for s in a["series"]] == [s["adev_dph"] for s in b["series"]]


def test_a_fit_in_memory_is_named_so(cycle_csv):
    # A unit typed when fitting carries over, named as the fit in memory's; one
    # its record's header gave yields to the arrays' own names (time_s: s).
    a = gyrotherm.allan(read_csv(cycle_csv), fit=gyrotherm.fit(cycle_csv, time_unit="s"))
    assert "time s (the fit given in memory, --time-unit when fitting)" in a.summary()
    assert "gyro dph (header 'gyro_dph')" in a.summary() and "the fit file" not in a.summary()


def test_compensate_is_the_clis(cycle_csv, cycle_fit_file, tmp_path):
    c = gyrotherm.compensate(cycle_csv, cycle_fit_file, output=tmp_path / "py.csv")
    cli = cli_json("compensate", cycle_csv, "--fit", cycle_fit_file, "-o", tmp_path / "cli.csv")
    mine = without_timing(c.as_dict())
    assert mine.pop("output") == str(tmp_path / "py.csv") and cli.pop("output") == str(tmp_path / "cli.csv")
    assert mine == cli
    assert (tmp_path / "py.csv").read_bytes() == (tmp_path / "cli.csv").read_bytes()
    written = read_csv(tmp_path / "cli.csv")
    for name in ("model_dph", "compensated_dph"):
        np.testing.assert_allclose(c.columns[name], written[name], atol=0.51e-9)


def test_export_is_the_clis(cycle_csv, cycle_fit_file, tmp_path):
    e = gyrotherm.export(cycle_fit_file, format="px4", output=tmp_path / "py.params", drop_unsupported=True)
    cli = run_cli("export", cycle_fit_file, "--format", "px4", "--drop-unsupported", "-o", tmp_path / "cli.params",
                  "--json")
    mine = without_timing(json.loads(e.to_json().replace("py.params", "OUT")))
    assert mine == without_timing(json.loads(cli.replace("cli.params", "OUT")))
    strip = lambda p: [l for l in p.read_text().splitlines() if " exported 20" not in l]  # the header's date
    assert strip(tmp_path / "py.params") == strip(tmp_path / "cli.params")


def test_export_saves_an_unsaved_fit_beside_its_output(cycle_csv, tmp_path):
    r = gyrotherm.fit(cycle_csv, model="T + T^2")
    e = gyrotherm.export(r, format="c", output=tmp_path / "comp.h")
    assert (tmp_path / "comp.h.fit.json").exists()
    assert "comp.h.fit.json" in (tmp_path / "comp.h").read_text()
    assert e.as_dict()["format"] == "c"


def test_export_on_arrays_suggests_the_refit_as_a_python_call(cycle_csv, tmp_path):
    r = gyrotherm.fit(read_csv(cycle_csv))  # dT: dropped for PX4, with the cost and the refit to try
    e = gyrotherm.export(r, format="px4", output=tmp_path / "x.params", drop_unsupported=True)
    said = e.summary() + "\n".join(e.warnings)
    assert 'gyrotherm.fit(data, model="' in said and "gyrotherm fit arrays" not in said


def test_plan_is_the_clis(tmp_path):
    kw = ["--model", "T", "--longest", "4", "--range", "0,40"]
    p = gyrotherm.plan(model="T", longest=4, range=(0, 40), out=tmp_path / "py")
    cli = run_cli("plan", *kw, "--out", tmp_path / "cli", "--json")
    mine = without_timing(json.loads(p.to_json().replace(str(tmp_path / "py"), "OUT")))
    assert mine == without_timing(json.loads(cli.replace(str(tmp_path / "cli"), "OUT")))
    assert mine["scenario_file"] == "OUT/plan.toml" and (tmp_path / "py" / "plan.toml").exists()


def test_a_refused_export_leaves_no_file(cycle_csv, tmp_path):
    r = gyrotherm.fit(cycle_csv)  # dT: PX4's cubic cannot express it
    with pytest.raises(ValueError, match="PX4 cannot express"):
        gyrotherm.export(r, format="px4", output=tmp_path / "x.params")
    assert list(tmp_path.iterdir()) == []
    assert r.file is None


def test_compensate_holds_outside_the_fitted_range_unless_told(cycle_csv, tmp_path):
    data = read_csv(cycle_csv)
    cool = {k: v[data["temp_c"] < 30.0] for k, v in data.items()}  # fitted below 30 °C only
    r = gyrotherm.fit(cool, model="T + T^2")
    held = gyrotherm.compensate(data, r).as_dict()
    far = gyrotherm.compensate(data, r, extrapolate=True).as_dict()
    assert held["outside_range"] == "held" and far["outside_range"] == "extrapolated"
    assert 0.2 < held["share_outside_range"] == far["share_outside_range"] < 0.8
    assert held["instability_after_dph"] != far["instability_after_dph"]


def test_export_refuses_a_two_plateau_fit_unless_the_caution_is_accepted(tmp_path):
    t = np.arange(4 * 3600.0)
    temp = np.where(t < 7200, 13.0, 47.5) + 0.4 * np.sin(2 * np.pi * t / 1800)
    gyro = 2.0 + 0.05 * temp + 0.01 * np.sin(0.37 * t)
    r = gyrotherm.fit({"time_s": t, "temp_c": temp, "gyro_dph": gyro}, model="T + T^2")
    with pytest.raises(ValueError, match="cannot support these terms"):
        gyrotherm.export(r, format="px4", output=tmp_path / "x.params")
    assert not (tmp_path / "x.params").exists()
    e = gyrotherm.export(r, format="px4", output=tmp_path / "x.params", accept_caution=True)
    assert (tmp_path / "x.params").read_text().startswith("# CAUTION")
    assert any(w.startswith("caution: ") for w in e.warnings)
