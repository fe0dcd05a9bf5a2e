"""Fixtures of the Python package's tests (run by ctest as python.pytest, on the
package in the build tree: PYTHONPATH=build/python, GYROTHERM_CLI the binary)."""

import json
import os
import subprocess

import pytest

SOURCE_DIR = os.environ.get("GYROTHERM_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", ".."))
CLI = os.environ.get("GYROTHERM_CLI", os.path.join(SOURCE_DIR, "build", "app", "gyrotherm"))
CYCLE = os.path.join(SOURCE_DIR, "scenarios", "cycle.toml")
WARMUP = os.path.join(SOURCE_DIR, "scenarios", "warmup.toml")

# Fields that time the work: the only ones two runs of the same command may differ in.
TIMING = {"seconds", "seconds_total"}


def run_cli(*args, expect=0, cwd=None):
    """Runs the gyrotherm binary; returns stdout (checks the exit code)."""
    done = subprocess.run([CLI, *map(str, args)], capture_output=True, text=True, cwd=cwd)
    assert done.returncode == expect, f"exit {done.returncode}: {done.stderr}"
    return done.stdout if expect == 0 else done.stderr


def without_timing(value):
    """A parsed JSON value without its timing fields, anywhere in it."""
    if isinstance(value, dict):
        return {k: without_timing(v) for k, v in value.items() if k not in TIMING}
    if isinstance(value, list):
        return [without_timing(v) for v in value]
    return value


def cli_json(*args):
    return without_timing(json.loads(run_cli(*args, "--json")))


@pytest.fixture(scope="session")
def cycle_csv(tmp_path_factory):
    """The paper's cycle simulated by the CLI with a hidden gradient effect (CSV + truth)."""
    folder = tmp_path_factory.mktemp("cycle")
    csv = folder / "cycle.csv"
    run_cli("simulate", CYCLE, "--seed", 7, "--hidden", "grad=0.02", "-o", csv)
    return csv


@pytest.fixture(scope="session")
def cycle_fit_file(cycle_csv, tmp_path_factory):
    path = tmp_path_factory.mktemp("fit") / "fit.json"
    run_cli("fit", cycle_csv, "-o", path)
    return path
