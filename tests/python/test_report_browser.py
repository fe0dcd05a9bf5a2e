"""The report page in a real browser (Debian's chromium-headless-shell, installed by
scripts/setup.sh --tests): it loads with no console error and no request leaving the file (a
control page with an external image shows the check can fail), every embedded figure decodes to a
sized PNG and paints, a screenshot and a print to PDF are written. And gyrotherm.report from
Python writes the same twin as the command line, and shows inline in Jupyter."""

import base64
import json
import os
import re
import shutil
import struct
import subprocess

import pytest

import gyrotherm
from conftest import run_cli

BROWSER = shutil.which("chromium-headless-shell") or shutil.which("chromium")
needs_browser = pytest.mark.skipif(BROWSER is None, reason="no chromium-headless-shell (scripts/setup.sh --tests)")


def browse(page, tmp_path, *flags):
    """Runs the headless browser on the page; returns its stderr (console messages logged there)."""
    done = subprocess.run(
        [BROWSER, "--no-sandbox", "--disable-gpu", "--hide-scrollbars", "--enable-logging=stderr", "--v=0",
         *flags, page.as_uri()],
        capture_output=True, text=True, timeout=120, cwd=tmp_path)
    assert done.returncode == 0, done.stderr[-2000:]
    return done.stderr


def requested_urls(net_log):
    """Every http(s) URL the browser's net log records."""
    with open(net_log) as f:
        return sorted(set(re.findall(r"https?://[^\"\\ ]+", f.read())))


def png_size(data):
    assert data[:8] == b"\x89PNG\r\n\x1a\n"
    return struct.unpack(">II", data[16:24])


@pytest.fixture(scope="module")
def report_page(cycle_csv, cycle_fit_file, tmp_path_factory):
    folder = tmp_path_factory.mktemp("report")
    page = folder / "report.html"
    run_cli("report", cycle_csv, "--fit", cycle_fit_file, "-o", page)
    return page


@needs_browser
def test_the_page_loads_paints_and_prints_offline(report_page, tmp_path):
    shot, pdf, net = tmp_path / "shot.png", tmp_path / "page.pdf", tmp_path / "net.json"
    err = browse(report_page, tmp_path, "--window-size=1200,6000", f"--screenshot={shot}", f"--log-net-log={net}")
    assert not re.search(r"CONSOLE|Uncaught|Failed to load", err), err[-2000:]
    assert requested_urls(net) == []
    # The figures: each decodes to a sized PNG, and the page paints them (the
    # screenshot is far from blank: the figures fill most of it).
    html = report_page.read_text()
    figures = re.findall(r'src="data:image/png;base64,([^"]+)"', html)
    assert len(figures) == 4
    for b64 in figures:
        width, height = png_size(base64.b64decode(b64))
        assert width >= 800 and height >= 400
    shot_bytes = shot.read_bytes()
    assert png_size(shot_bytes) == (1200, 6000)
    assert len(shot_bytes) > 100_000  # a blank 1200x6000 page compresses to a few KB
    browse(report_page, tmp_path, f"--print-to-pdf={pdf}")
    assert pdf.read_bytes()[:5] == b"%PDF-" and pdf.stat().st_size > 50_000


@needs_browser
def test_the_offline_check_can_fail(tmp_path):
    control = tmp_path / "control.html"
    control.write_text('<!DOCTYPE html><html><body><img src="http://127.0.0.1:9/x.png"></body></html>')
    net = tmp_path / "net.json"
    browse(control, tmp_path, f"--log-net-log={net}", "--screenshot=" + str(tmp_path / "c.png"))
    assert "http://127.0.0.1:9/x.png" in requested_urls(net)


def test_python_writes_the_twin_of_the_command_line(report_page, cycle_csv, cycle_fit_file, tmp_path):
    r = gyrotherm.report(cycle_csv, tmp_path / "py.html", fit=cycle_fit_file)
    with open(report_page.with_suffix(".json")) as f:
        cli = json.load(f)
    for twin in (r.twin, cli):
        twin.pop("created")
    assert r.twin == cli
    assert r._repr_html_().startswith("<!DOCTYPE html>")
    assert os.path.exists(r.html_file) and r.twin_file.endswith("py.json")
    with pytest.raises(gyrotherm.InputError, match="name it FILE.html"):
        gyrotherm.report(cycle_csv, tmp_path / "py.pdf", fit=cycle_fit_file)
