"""The plotting helpers return Axes, draw what they say, and never show()."""

import sys

import pytest

import gyrotherm
from conftest import CYCLE

matplotlib = pytest.importorskip("matplotlib")
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def test_matplotlib_is_not_imported_by_the_package():
    import subprocess
    code = "import sys, gyrotherm; print('matplotlib' in sys.modules)"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    assert out.strip() == "False"


def test_each_helper_returns_its_axes(cycle_csv, monkeypatch):
    monkeypatch.setattr(plt, "show", lambda *a, **k: pytest.fail("show() called"))
    record = gyrotherm.simulate(CYCLE, seed=3)
    r = gyrotherm.fit(record)
    fig, axes = plt.subplots(2, 3)
    assert gyrotherm.plotting.plot_record(record, ax=axes[0, 0]) is axes[0, 0]
    assert gyrotherm.plotting.plot_fit(r, ax=axes[0, 1]) is axes[0, 1]
    assert gyrotherm.plotting.plot_residual_vs_temperature(r, ax=axes[0, 2]) is axes[0, 2]
    assert gyrotherm.plotting.plot_allan(gyrotherm.allan(record, fit=r), ax=axes[1, 0]) is axes[1, 0]
    d = gyrotherm.diagnose(cycle_csv)
    assert gyrotherm.plotting.plot_diagnosis(d, ax=axes[1, 1]) is axes[1, 1]
    assert len(axes[1, 1].patches) == len(d.missing_effects)
    assert len(axes[1, 0].get_lines()) == 2  # raw and compensated
    ax = gyrotherm.plotting.plot_fit(r)  # a new figure when none is given
    assert ax.figure is not fig
    plt.close("all")
