"""The package's functions and result types (re-exported by gyrotherm)."""

import json
import os
from collections.abc import Mapping

from . import _gyrotherm as _g

_RECORD_NAME = "arrays"  # how a record given as arrays is named in reports and JSON


def _text(value):
    """An option's value as the command line would read it."""
    if isinstance(value, os.PathLike):
        return os.fspath(value)
    if isinstance(value, str):
        return value
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, float) or type(value).__name__.startswith("float"):
        return repr(float(value))  # the shortest text that reads back to the same double
    return str(value)


def _keywords(values):
    """Keyword options → (keyword, text) pairs; None keeps the default, False leaves a flag off,
    a list or tuple repeats the option."""
    pairs = []
    for key, value in values.items():
        if value is None or value is False:
            continue
        if isinstance(value, (list, tuple)):
            pairs.extend((key, _text(v)) for v in value)
        else:
            pairs.append((key, _text(value)))
    return pairs


def _data(data):
    """A record argument as (path, mapping, truth JSON text): exactly one of path and mapping."""
    if isinstance(data, Record):
        return None, data.columns, data.truth_json
    if isinstance(data, (str, os.PathLike)):
        return os.fspath(data), None, None
    if hasattr(data, "columns") and hasattr(data, "__getitem__") and not isinstance(data, Mapping):
        # a pandas DataFrame: its columns by name (views of float64 blocks)
        return None, {str(name): data[name].to_numpy() for name in data.columns}, None
    if isinstance(data, Mapping):
        return None, data, None
    raise InputError(f"data: expected a path, a mapping of column names to arrays, a pandas DataFrame or a "
                     f"gyrotherm.Record; got {type(data).__name__}")


InputError = _g.InputError


def _fit_json_of(fit):
    """A fit argument as (fit JSON text, its file or None)."""
    if isinstance(fit, FitResult):
        return fit.to_json(), fit.file
    if isinstance(fit, (str, os.PathLike)):
        return None, os.fspath(fit)
    raise InputError(f"fit: expected a gyrotherm.FitResult or the path of a fit file; got {type(fit).__name__}")


def _fit_to_read(fit):
    """A fit for allan and compensate as (its JSON, None) when it was never saved, else (None,
    its file): a saved fit is read from its file and named by it, as on the command line."""
    fit_json, fit_file = _fit_json_of(fit)
    return (None, fit_file) if fit_file is not None else (fit_json, None)


class Record(Mapping):
    """A simulated record: its columns as numpy arrays (time_s in s; chamber_c, case_c, temp_c,
    temp2_c in °C; gyro_dph and bias_true_dph in °/h), the truth (``truth``: the true coefficients
    by term name, the noise, the hidden effects, as ``simulate`` writes beside its CSV) and the
    run's summary (``summary``, as ``simulate --json``). A Record is a mapping of column names to
    arrays, so it can be given to fit, diagnose, allan and compensate as it is (a fit then reports
    the truth beside its coefficients)."""

    def __init__(self, columns, truth_json=None, summary=None):
        self.columns = dict(columns)
        self.truth_json = truth_json
        self.truth = json.loads(truth_json) if truth_json else None
        self.summary = summary or {}

    def __getitem__(self, name):
        return self.columns[name]

    def __iter__(self):
        return iter(self.columns)

    def __len__(self):
        return len(self.columns)

    def __getattr__(self, name):
        columns = self.__dict__.get("columns", {})
        if name in columns:
            return columns[name]
        raise AttributeError(name)

    def __repr__(self):
        n = len(self.columns.get("time_s", ()))
        return f"<gyrotherm.Record {n} samples, columns {', '.join(self.columns)}>"

    def to_dataframe(self):
        """The columns as a pandas DataFrame (pandas is imported here, only when asked for)."""
        import pandas
        return pandas.DataFrame(self.columns)


class _Report:
    """What a command printed: ``to_json()`` the JSON text of ``--json``, ``summary()`` the text
    report, ``as_dict()`` the JSON as Python objects."""

    def __init__(self, json_text, text):
        self._json = json_text
        self._text = text
        self._dict = json.loads(json_text)

    def to_json(self):
        """The JSON text the command prints with --json."""
        return self._json

    def as_dict(self):
        return self._dict

    def summary(self):
        """The command's report for people (what the command line prints without --json)."""
        return self._text

    def __repr__(self):
        return f"<gyrotherm.{type(self).__name__}>\n{self._text}"


class FitResult(_Report):
    """A fitted bias model B = b0 + Σ b_j·x_j (``fit``). ``coefficients``: term → value in the
    term's unit ("1" is b0 in °/h; "T" in °/h/°C, ...); ``intervals_95``: term → (lower, upper);
    ``noise``: the record's noise model as identified; ``instability``: (before, after) in °/h;
    ``windows``: the averaged windows (time_s, temp_c, gyro_dph, model_dph, residual_dph);
    ``predict(data)``: the model's bias at every sample of a record. With several gyro channels,
    ``channels`` holds one FitResult per channel and the single-channel fields raise."""

    def __init__(self, json_text, text, windows, file=None, channel=None, data=None):
        super().__init__(json_text, text)
        self.file = file  # where it was saved (output=...), else None
        self.data = data  # the record it was fitted on when given as arrays (export's default data)
        d = self._dict
        if "channels" in d and channel is None:
            self.channels = {
                c["channel"]: FitResult(json.dumps(c, indent=2, ensure_ascii=False) + "\n", text, windows.get(c["channel"]), file,
                                        c["channel"], data)
                for c in d["channels"]}
            self._single = None
        else:
            self.channels = None
            self._single = d
            self.windows = windows if channel is not None else next(iter(windows.values()), None)

    def _one(self):
        if self._single is None:
            raise InputError(f"this fit has {len(self.channels)} channels ({', '.join(self.channels)}): "
                             f"use .channels[name]")
        return self._single

    @property
    def coefficients(self):
        """Term → coefficient ("1": the intercept b0, °/h)."""
        c = self._one()["coefficients"]
        return {k: v for k, v in c.items()}

    @property
    def intervals_95(self):
        """Term → (lower, upper) of the 95 % interval (terms without one are left out)."""
        d = self._one()
        return {k: tuple(v) for k, v in d.get("intervals_95", {}).items()}

    @property
    def parameters(self):
        """Term → its nonlinear parameter (e.g. lag → tau_s), for the terms that have one."""
        return dict(self._one().get("parameters", {}))

    @property
    def noise(self):
        """The record's noise model as identified (noise_model in the fit JSON), or None."""
        return self._one().get("noise_model")

    @property
    def instability(self):
        """(before, after): the standard deviation of the window averages, raw and compensated, °/h."""
        d = self._one()
        return d["instability_before_dph"], d["instability_after_dph"]

    @property
    def residuals(self):
        """The residual of each averaged window (°/h): gyro − model."""
        return self._one_windows()["residual_dph"]

    def _one_windows(self):
        self._one()
        return self.windows

    def predict(self, data, **options):
        """The model's bias B (°/h) at every sample of a record (a path, arrays or a Record), as
        ``compensate`` computes it; column and unit options as for fit."""
        return compensate(data, self, **options).columns["model_dph"]

    def save(self, path):
        """Writes the fit file (what ``fit -o`` writes), for compensate and export; returns the path."""
        path = os.fspath(path)
        tmp = f"{path}.tmp{os.getpid()}"
        with open(tmp, "w", encoding="utf-8") as out:
            out.write(self._json)
        os.replace(tmp, path)
        self.file = path
        return path


class Diagnosis(_Report):
    """Where the model fails and which effect is missing (``diagnose``): ``missing_effects`` (the
    candidates, strongest first, with p-values that hold under the record's noise), ``verdict``, and
    the rest of ``diagnose --json`` in ``as_dict()``."""

    @property
    def missing_effects(self):
        return self._dict.get("missing_effects", [])

    @property
    def verdict(self):
        return self._dict.get("verdict")

    @property
    def verdict_data(self):
        """The verdict as data: kind (found, group, none, nothing_to_try), the terms found or the
        group the record cannot tell apart, the share of the excess they remove."""
        return self._dict.get("verdict_data")

    @property
    def next_call(self):
        """The next step as a Python call, ``gyrotherm.diagnose(data, model="...")`` with the
        model the diagnosis suggests (``next`` in ``as_dict()`` holds it as data), or None; with
        several gyro channels, a dict of channel -> call (or None)."""
        if isinstance(self._dict.get("channels"), list):
            return {c.get("channel"): _next_call(c.get("next")) for c in self._dict["channels"]}
        return _next_call(self._dict.get("next"))


def _literal(text):
    """A data option's value (text, as the command line takes it) as a Python literal."""
    if text in ("true", "false"):
        return "True" if text == "true" else "False"
    try:
        float(text)
        return text
    except ValueError:
        return repr(text)


def _next_call(step):
    if not step:
        return None
    channel = f", gyro_col={step['channel']!r}" if step.get("channel") else ""
    # The data options the diagnosis was given (columns, units, avg ...), as keywords.
    given = "".join(f", {k}={_literal(v)}" for k, v in (step.get("options") or {}).items())
    return f'gyrotherm.diagnose(data, model="{step["model"]}"{channel}{given})'


class AllanResult(_Report):
    """Allan deviation with intervals (``allan``): per channel the curve(s) and the noise
    coefficients read off them; ``as_dict()`` is ``allan --json``."""


class Compensation(_Report):
    """A fit applied to a record (``compensate``): ``columns`` as numpy arrays (time_s, temp_c,
    gyro_dph, model_dph, compensated_dph in s, °C, °/h; outlier 0/1) and the summary."""

    def __init__(self, json_text, text, columns):
        super().__init__(json_text, text)
        self.columns = columns


class ExportResult(_Report):
    """A fit written as firmware parameters or C (``export``): the file, and what the firmware
    achieves on the fitted record (``as_dict()['firmware_outcome']``)."""

    def __init__(self, json_text, text, warnings):
        super().__init__(json_text, text)
        self.warnings = list(warnings)


class CheckResult(_Report):
    """A calibration checked on another log (``check``): per axis the instability raw and
    compensated, the residual against temperature and the share outside TMIN..TMAX
    (``as_dict()['axes']``), the failure modes found (``findings``), and ``passed``: with
    max_residual whether every axis is within it, else None."""

    @property
    def passed(self):
        return self._dict["passed"]

    @property
    def findings(self):
        """The issues found (``calibration_span_minimum``, ``moving``, ``already_enabled``, …)."""
        return [f["issue"] for f in self._dict["findings"]]


class ReportResult:
    """The report page (``report``): ``html_file`` and ``twin_file`` written, ``twin`` the JSON
    twin as Python objects (every number on the page); shown inline in Jupyter."""

    def __init__(self, out):
        self.html = out["html"]
        self.html_file = out["html_file"]
        self.twin_file = out["twin_file"]
        self.twin = json.loads(out["twin"])
        self._text = out["text"]

    def _repr_html_(self):
        return self.html

    def __repr__(self):
        return f"<gyrotherm.ReportResult> {self._text.strip()}"


class PlanResult(_Report):
    """A designed thermal test (``plan``): the profile, its duration and the predicted standard
    errors; the files in ``out``."""


def simulate(scenario, seed=None, hidden=None, **options):
    """Runs a scenario (a TOML file) in memory: the record at the scenario's rate with its truth.

    seed: the noise seed (default: the scenario's). hidden: effects the gyro has and the model may
    not, {term: coefficient} or ["term=coefficient", ...] (units of the term's coefficient, e.g.
    grad in °/h/°C). Other options as ``gyrotherm simulate``: rig, gyro (files replacing the
    scenario's), output (also write the CSV and its truth), plot (a PNG)."""
    if isinstance(hidden, Mapping):
        hidden = [f"{k}={_text(v)}" for k, v in hidden.items()]
    pairs = _keywords(dict(scenario=scenario, seed=seed, hidden=hidden, **options))
    out = _g.simulate(pairs)
    return Record(out["columns"], out["truth"], json.loads(out["summary"]))


def fit(data, model=None, engine=None, **options):
    """Fits the bias model to a record (a path, arrays, a DataFrame or a Record).

    model: the formula, terms joined by + (default 'T + T^2 + dT'; see effects()); engine: the
    fitting engine (default ols; see engines()). Other options as ``gyrotherm fit``: seed, budget,
    target (°/h), option (engine KEY=VALUE, a list), output (save the fit file), and the data options
    (avg in s, deriv_span in s, causal, keep_outliers, outlier_threshold, time_col, temp_col,
    gyro_col, temp2_col, time_unit, gyro_unit, temp_unit, gyro_scale, temp_scale, temp_offset,
    delimiter, decimal_comma, imu, rate in Hz). Returns a FitResult whose to_json() is what
    ``fit --json`` prints."""
    path, columns, truth = _data(data)
    pairs = _keywords(dict(data=path, model=model, engine=engine, **options))
    out = _g.fit(pairs, columns, truth)
    return FitResult(out["json"], out["text"], out["windows"], file=options.get("output"),
                     data=None if path is not None else data)


def diagnose(data, model=None, add=None, **options):
    """Compares the model with a record: where it fails, which effect is missing, and (with add)
    the error before and after adding terms. Options as ``gyrotherm diagnose`` (engine, seed,
    candidates, plots, and the data options of fit)."""
    path, columns, _ = _data(data)
    pairs = _keywords(dict(data=path, model=model, add=add, **options))
    out = _g.diagnose(pairs, columns)
    return Diagnosis(out["json"], out["text"])


def allan(data, fit=None, **options):
    """Allan deviation of a record's gyro output with intervals and noise coefficients; with fit,
    also of the output compensated by it. Options as ``gyrotherm allan``: taus (octave, decade,
    all), tau_max (s), ci (confidence), plot (PNG), and the column and unit options."""
    path, columns, _ = _data(data)
    fit_json, fit_file = _fit_to_read(fit) if fit is not None else (None, None)
    pairs = _keywords(dict(data=path, fit=fit_file, **options))
    out = _g.allan(pairs, columns, fit_json)
    return AllanResult(out["json"], out["text"])


def compensate(data, fit, **options):
    """Applies a fit (a FitResult or a fit file) to a record: the model and the compensated output
    at every sample. Options as ``gyrotherm compensate``: causal, output (also write the CSV), and
    the column and unit options (default: the fit's)."""
    path, columns, _ = _data(data)
    fit_json, fit_file = _fit_to_read(fit)
    pairs = _keywords(dict(data=path, fit=fit_file, **options))
    out = _g.compensate(pairs, columns, fit_json)
    return Compensation(out["json"], out["text"], out["columns"])


def export(fit, format, output, data=None, **options):
    """Writes a fit as firmware parameters or C: format px4, ardupilot or c; output the file.

    data: the record the fit was made on (a path, arrays or a Record), for what the firmware achieves
    on it and the cost of drop_unsupported; default: the fit's own (a FitResult made on arrays keeps
    them). Options as ``gyrotherm export``: axes, channel, prefix, instance, device_id, boot_temp
    (°C), drop_unsupported. A FitResult that was not saved is saved first beside the output
    (OUTPUT.fit.json), since the exported file names the fit it came from; a refused export leaves
    no file."""
    fit_json, fit_file = _fit_json_of(fit)
    if data is None and isinstance(fit, FitResult):
        data = fit.data
    path, columns, _ = _data(data) if data is not None else (None, None, None)
    saved_here = fit_file is None
    if saved_here:
        fit_file = fit.save(os.fspath(output) + ".fit.json")
    pairs = _keywords(dict(fit=fit_file, format=format, output=output, data=path, **options))
    try:
        out = _g.export(pairs, columns)
    except BaseException:
        if saved_here:  # nothing is left behind by a refused export
            os.remove(fit_file)
            fit.file = None
        raise
    return ExportResult(out["json"], out["text"], list(out["warnings"]))


def check(log, params, **options):
    """Applies a calibration to another log as the firmware applies it and judges it: log a PX4
    ULog, an ArduPilot DataFlash log or a measurement CSV (a path); params a PX4 .params, an
    ArduPilot .parm or a fit file (a path, or a FitResult that was saved). Options as
    ``gyrotherm check``: max_residual (with residual_unit, default dph), avg, boot, imu and the
    column and unit options for a CSV. A failed limit is ``passed == False``, not an error."""
    if isinstance(params, FitResult):
        if params.file is None:
            raise InputError("check: save the fit first (FitResult.save), the check names the file it applies")
        params = params.file
    pairs = _keywords(dict(log=os.fspath(log), params=os.fspath(params), **options))
    out = _g.check(pairs)
    return CheckResult(out["json"], out["text"])


def report(data, output, fit=None, params=None, **options):
    """Writes one self-contained HTML page (output, FILE.html) and its JSON twin (FILE.json) for a
    log (a path): the fit (a saved fit file or FitResult, else one made here with model= and the
    data options), compensation, Allan deviation, diagnosis and, with params (a PX4 .params,
    ArduPilot .parm or fit file), its check on this log (max_residual in °/h for PASS/FAIL)."""
    fit_file = None
    if fit is not None:
        fit_file = fit.file if isinstance(fit, FitResult) else os.fspath(fit)
        if fit_file is None:
            raise InputError("report: save the fit first (FitResult.save), the report names the file it shows")
    pairs = _keywords(dict(data=os.fspath(data), output=os.fspath(output), fit=fit_file,
                           params=None if params is None else os.fspath(params), **options))
    return ReportResult(_g.report(pairs))


def plan(**options):
    """Designs the shortest thermal test that pins the model's coefficients to a precision.
    Options as ``gyrotherm plan`` (model, se, rel_se, separate, gyro, noise, rig, tau, range,
    max_rate, min_soak, longest, verify, out, ...)."""
    out = _g.plan(_keywords(options))
    return PlanResult(out["json"], out["text"])


def effects():
    """The model terms: name, unit of the coefficient, what physical effect (``effects --json``)."""
    return json.loads(_g.effects_json())


def engines():
    """The fitting engines and their options (``engines --json``)."""
    return json.loads(_g.engines_json())


def options(command):
    """The options of a command (fit, diagnose, allan, compensate, export, simulate, plan, check,
    report), as the command line has them: keyword, flag, help (ending "(default: VALUE)" where there
    is one), default (the value, or the rule in words; "" for none), kind, required."""
    return _g.option_table(command)
