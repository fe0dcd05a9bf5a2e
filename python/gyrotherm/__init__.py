"""gyrotherm from Python: the thermal-test simulator and the bias-model fitter.

The same commands as the ``gyrotherm`` command line, on arrays as well as files:

>>> import gyrotherm
>>> record = gyrotherm.simulate("scenarios/cycle.toml", seed=3, hidden={"grad": 0.02})
>>> result = gyrotherm.fit(record, model="T + T^2 + dT")
>>> result.coefficients["T"], result.intervals_95["T"]
>>> gyrotherm.diagnose(record, model="T + T^2 + dT").missing_effects

A record (the ``data`` of fit, diagnose, allan, compensate) is a path to a
measurement CSV or an autopilot log, or a mapping of column names to 1-D
arrays (a dict, a pandas DataFrame, a :class:`Record`), read with the same
column names, unit options and defaults as the command line: time in s
(``time_s``), temperature in °C (``temp_c``), gyro output in °/h
(``gyro_dph``), an optional second temperature in °C (``temp2_c``); other
names and units through the options (``time_col``, ``gyro_unit``, ...).
float64 arrays that are C-contiguous are read in place (no copy); others are
copied once. While the library works the GIL is released: do not change the
arrays from another thread meanwhile.

Options are the command line's, with underscores for dashes
(``--deriv-span`` is ``deriv_span``); an option left out (or ``None``) keeps the
command line's default. :func:`options` lists them with their help. Bad input
raises :class:`InputError` (a ``ValueError``) with the command line's message.
"""

from ._gyrotherm import InputError, SolverError
from ._api import (
    Record, FitResult, Diagnosis, AllanResult, Compensation, ExportResult, PlanResult, CheckResult,
    ReportResult, simulate, fit, diagnose, allan, compensate, export, check, report, plan, effects, engines, options,
)
from . import plotting

__all__ = [
    "InputError", "SolverError",
    "Record", "FitResult", "Diagnosis", "AllanResult", "Compensation", "ExportResult", "PlanResult",
    "CheckResult", "ReportResult", "simulate", "fit", "diagnose", "allan", "compensate", "export", "check",
    "report", "plan", "effects", "engines",
    "options", "plotting",
]
