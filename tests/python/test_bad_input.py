"""Bad arrays and options: a clear ValueError with the CLI's message, never a silent answer.
A seeded fuzz of broken records as well as the named cases."""

import numpy as np
import pytest

import gyrotherm


def good(n=4000, seed=0):
    """A small record: 1 Hz, a temperature ramp, a bias linear in it plus white noise."""
    rng = np.random.default_rng(seed)
    t = np.arange(n, dtype=float)
    temp = 20.0 + 20.0 * np.sin(t / n * 2 * np.pi)
    return {"time_s": t, "temp_c": temp, "gyro_dph": 1.0 + 0.05 * temp + rng.normal(0.0, 0.01, n)}


def test_nan_names_the_column_and_index():
    d = good()
    d["gyro_dph"][57] = np.nan
    with pytest.raises(gyrotherm.InputError, match=r"index 57.*gyro_dph|gyro_dph.*index 57"):
        gyrotherm.fit(d, model="T")


def test_inf_in_the_temperature():
    d = good()
    d["temp_c"][3] = np.inf
    with pytest.raises(ValueError, match="temp_c"):
        gyrotherm.fit(d, model="T")


def test_unequal_lengths():
    d = good()
    d["temp_c"] = d["temp_c"][:-1]
    with pytest.raises(ValueError, match="temp_c"):
        gyrotherm.fit(d, model="T")


def test_a_missing_column_lists_the_ones_there():
    d = good()
    d["gyro"] = d.pop("gyro_dph")
    with pytest.raises(ValueError, match="gyro_dph.*gyro-col|gyro-col.*gyro_dph"):
        gyrotherm.fit(d, model="T")
    assert gyrotherm.fit(d, model="T", gyro_col="gyro").coefficients["T"] == pytest.approx(0.05, rel=0.01)


@pytest.mark.parametrize("bad", [np.array(["a"] * 4000), np.zeros(4000, dtype=complex),
                                 np.zeros(4000, dtype=bool), np.zeros((4000, 2))])
def test_wrong_dtype_or_shape(bad):
    d = good()
    d["gyro_dph"] = bad
    with pytest.raises(ValueError, match="gyro_dph"):
        gyrotherm.fit(d, model="T")


def test_other_dtypes_and_layouts_are_copied_and_give_the_same_fit():
    d = good()
    reference = gyrotherm.fit(d, model="T").coefficients
    wide = {k: np.repeat(v, 2)[::2] for k, v in d.items()}  # non-contiguous views
    assert not wide["gyro_dph"].flags["C_CONTIGUOUS"]
    assert gyrotherm.fit(wide, model="T").coefficients == reference
    as_lists = {k: v.tolist() for k, v in d.items()}
    assert gyrotherm.fit(as_lists, model="T").coefficients == reference
    ints = dict(d, time_s=d["time_s"].astype(np.int64))
    assert gyrotherm.fit(ints, model="T").coefficients == reference
    f32 = dict(d, temp_c=d["temp_c"].astype(np.float32))
    assert gyrotherm.fit(f32, model="T").coefficients["T"] == pytest.approx(reference["T"], rel=1e-4)


def test_time_not_increasing():
    d = good()
    d["time_s"][100] = d["time_s"][99]
    with pytest.raises(ValueError, match="increasing"):
        gyrotherm.fit(d, model="T")


def test_too_short():
    d = {k: v[:1] for k, v in good().items()}
    with pytest.raises(ValueError):
        gyrotherm.fit(d, model="T")


def test_units_of_the_cli():
    d = good()
    ms = {"t": d["time_s"] * 1000.0, "temp_c": d["temp_c"], "gyro_dph": d["gyro_dph"]}
    a = gyrotherm.fit(d, model="T").coefficients
    assert gyrotherm.fit(ms, model="T", time_col="t", time_unit="ms").coefficients == a
    with pytest.raises(ValueError, match="time_s.*--time-unit"):  # the name states s: the CLI's rule
        gyrotherm.fit(d, model="T", time_unit="ms")
    named = {"time (ms)": ms["t"], "temp_c": d["temp_c"], "gyro_dph": d["gyro_dph"]}
    assert gyrotherm.fit(named, model="T", time_col="time (ms)").coefficients == a
    with pytest.raises(ValueError, match="--gyro-unit"):
        gyrotherm.fit(d, model="T", gyro_unit="furlongs")


def test_unknown_options_and_bad_values():
    d = good()
    with pytest.raises(ValueError, match="avgg"):
        gyrotherm.fit(d, model="T", avgg=10)
    with pytest.raises(ValueError, match="--avg"):
        gyrotherm.fit(d, model="T", avg="ten")
    with pytest.raises(ValueError, match="--deriv-span"):
        gyrotherm.fit(d, model="T", deriv_span=-1)
    with pytest.raises(ValueError, match="unknown term|nonsense"):
        gyrotherm.fit(d, model="T + nonsense")
    with pytest.raises(ValueError, match="engine"):
        gyrotherm.fit(d, model="T", engine="magic")
    with pytest.raises(ValueError, match="data"):
        gyrotherm.fit(42)


def test_a_fuzz_of_broken_records():
    """Seeded: each record broken in one random way gives a ValueError or a finite fit, never a crash,
    a hang or a NaN coefficient."""
    rng = np.random.default_rng(2026)
    outcomes = {"refused": 0, "fitted": 0}
    for trial in range(120):
        d = good(n=int(rng.integers(2, 3000)), seed=trial)
        name = ["time_s", "temp_c", "gyro_dph"][rng.integers(3)]
        kind = rng.integers(7)
        x = d[name]
        if kind == 0:
            x[rng.integers(x.size)] = [np.nan, np.inf, -np.inf][rng.integers(3)]
        elif kind == 1:
            d[name] = x[: rng.integers(x.size)]
        elif kind == 2:
            d[name] = x.astype([np.float32, np.int32, np.uint8, np.float16][rng.integers(4)])
        elif kind == 3:
            d[name] = np.repeat(x, 3)[:: 3] if rng.integers(2) else x[::-1].copy()
        elif kind == 4:
            x[rng.integers(x.size)] = rng.choice([1e300, -1e300, 1e-300, 5e12])
        elif kind == 5:
            d[name] = x.reshape(1, -1) if rng.integers(2) else x.astype(object)
        else:
            del d[name]
        try:
            r = gyrotherm.fit(d, model="T")
        except ValueError as e:
            assert str(e), "an error without a message"
            outcomes["refused"] += 1
            continue
        assert all(np.isfinite(v) for v in r.coefficients.values())
        outcomes["fitted"] += 1
    assert outcomes["refused"] > 30 and outcomes["fitted"] > 10, outcomes
