"""Figures of gyrotherm's results on matplotlib Axes.

Each function draws on the Axes given (or on a new figure's) and returns the
Axes; none calls ``show()``. matplotlib is imported when a function is called,
not when gyrotherm is.
"""

import numpy as np


def _axes(ax):
    if ax is not None:
        return ax
    import matplotlib.pyplot as plt
    return plt.figure().add_subplot()


def _window_means(t, y, window_s):
    """Means of y over consecutive windows of window_s seconds (by time, gaps not bridged)."""
    t = np.asarray(t, dtype=float)
    y = np.asarray(y, dtype=float)
    if t.size == 0:
        return t, y
    index = np.floor((t - t[0]) / window_s).astype(np.int64)
    edges = np.flatnonzero(np.diff(index)) + 1
    starts = np.concatenate(([0], edges))
    counts = np.diff(np.concatenate((starts, [t.size])))
    return np.add.reduceat(t, starts) / counts, np.add.reduceat(y, starts) / counts


def plot_record(record, ax=None, window_s=100.0):
    """A record's gyro output as window_s averages (°/h, left axis; the true bias too for a simulated
    record) and its temperature (°C, right axis) against time in hours. Returns the left Axes."""
    ax = _axes(ax)
    t, g = _window_means(record["time_s"], record["gyro_dph"], window_s)
    ax.plot(t / 3600.0, g, ".", ms=2, label=f"gyro, {window_s:g} s means")
    if "bias_true_dph" in record:
        tb, b = _window_means(record["time_s"], record["bias_true_dph"], window_s)
        ax.plot(tb / 3600.0, b, "-", lw=1, label="true bias")
    ax.set_xlabel("time (h)")
    ax.set_ylabel("gyro output (°/h)")
    right = ax.twinx()
    right.plot(np.asarray(record["time_s"]) / 3600.0, record["temp_c"], "r-", lw=0.8, label="temperature")
    right.set_ylabel("temperature (°C)")
    ax.legend(loc="upper left", fontsize="small")
    return ax


def plot_fit(result, ax=None):
    """A fit's averaged windows: the gyro output and the model (°/h) against time (h), and the
    residual below them. Returns the Axes."""
    ax = _axes(ax)
    w = result.windows
    hours = np.asarray(w["time_s"]) / 3600.0
    ax.plot(hours, w["gyro_dph"], ".", ms=3, label="window means")
    ax.plot(hours, w["model_dph"], "-", lw=1, label="model")
    ax.plot(hours, w["residual_dph"] + np.min(w["gyro_dph"]) - np.max(w["residual_dph"]), ".", ms=2,
            label="residual (shifted)")
    before, after = result.instability
    ax.set_title(f"instability {before:.4g} → {after:.4g} °/h")
    ax.set_xlabel("time (h)")
    ax.set_ylabel("°/h")
    ax.legend(fontsize="small")
    return ax


def plot_residual_vs_temperature(result, ax=None):
    """A fit's residual per window (°/h) against the window's temperature (°C): structure left here
    is a temperature effect the model lacks. Returns the Axes."""
    ax = _axes(ax)
    w = result.windows
    ax.plot(w["temp_c"], w["residual_dph"], ".", ms=3)
    ax.axhline(0.0, color="k", lw=0.5)
    ax.set_xlabel("temperature (°C)")
    ax.set_ylabel("residual (°/h)")
    return ax


def plot_allan(result, ax=None):
    """Allan deviation (°/h) against τ (s), log-log, each series (raw, compensated) with its interval
    band. Returns the Axes."""
    ax = _axes(ax)
    studies = result.as_dict()
    for study in studies.get("channels", [studies]) if isinstance(studies, dict) else studies:
        prefix = f"{study['channel']}: " if study.get("channel") else ""
        for s in study["series"]:
            line, = ax.loglog(s["taus_s"], s["adev_dph"], "-o", ms=3, label=prefix + s["name"])
            ax.fill_between(s["taus_s"], s["lo_dph"], s["hi_dph"], color=line.get_color(), alpha=0.2)
    ax.set_xlabel("τ (s)")
    ax.set_ylabel("Allan deviation (°/h)")
    ax.grid(True, which="both", lw=0.3)
    ax.legend(fontsize="small")
    return ax


def plot_diagnosis(diagnosis, ax=None):
    """The missing-effect candidates: how much each would lower the instability (%), significant ones
    filled. Returns the Axes."""
    ax = _axes(ax)
    rows = diagnosis.missing_effects
    names = [r["term"] for r in rows]
    gains = [r.get("reduction_pct") or 0.0 for r in rows]
    colours = ["tab:red" if r.get("significant") or r.get("group_significant") else "tab:gray" for r in rows]
    ax.barh(range(len(rows)), gains, color=colours)
    ax.set_yticks(range(len(rows)))
    ax.set_yticklabels(names)
    ax.invert_yaxis()
    ax.set_xlabel("instability reduction if added (%)")
    ax.set_title(diagnosis.verdict or "")
    return ax
