"""examples/ray_batch.py, run as Ray tasks on this machine over 3 CUReT
materials x 2 models, writes what `brdf batch` writes for the same fits:
the same summary (but for the wall-clock seconds) and the same fit lines;
a rerun after a kill (half a line written) fits only that line again."""

import csv
import json
import os
import subprocess
import sys

import brdf

from conftest import EXAMPLES, data_file, without_seconds

MATERIALS = ["curet/abrdf.dat#2", "curet/abrdf.dat#12", "curet/abrdf.dat#33"]
MODELS = "Lambert,blinn-phong"


def table_without_seconds(path):
    """The summary's rows with the last (seconds) column dropped."""
    if path.endswith(".csv"):
        with open(path, newline="") as f:
            rows = list(csv.reader(f))
        assert rows[0][-1] == "seconds"
        return [r[:-1] for r in rows]
    with open(path) as f:
        lines = f.read().split("\n")
    return [line.rsplit("|", 2)[0] if line.startswith("| ") else line for line in lines]


def fit_lines(path):
    with open(path) as f:
        return {(v["data"], v["model"]): without_seconds(v) for v in map(json.loads, f)}


def test_ray_batch_writes_what_brdf_batch_writes(brdf_cli, tmp_path):
    data = [data_file(m) for m in MATERIALS]
    ours, theirs = tmp_path / "ray", tmp_path / "cli"
    brdf_cli("batch", "--data", *data, "--models", MODELS, "--out", str(theirs))
    script = [sys.executable, str(EXAMPLES / "ray_batch.py"), "--data", *data,
              "--models", MODELS, "--out", str(ours)]
    env = {**os.environ, "RAY_USAGE_STATS_ENABLED": "0"}
    run = subprocess.run(script, capture_output=True, text=True, env=env, timeout=600)
    assert run.returncode == 0, run.stderr[-3000:]
    for name in ("summary.csv", "summary.md"):
        assert table_without_seconds(str(ours / name)) == \
            table_without_seconds(str(theirs / name)), name
    lines = fit_lines(ours / "fits.jsonl")
    assert len(lines) == 6
    assert lines == fit_lines(theirs / "fits.jsonl")
    # data named relative to BRDF_DATA, never by an absolute path
    assert all(not d.startswith("/") for d, _ in lines)

    # A killed run leaves half a line: the rerun fits that one again only.
    text = (ours / "fits.jsonl").read_text()
    (ours / "fits.jsonl").write_text(text[: len(text) - len(text.splitlines()[-1]) // 2 - 1])
    again = subprocess.run(script, capture_output=True, text=True, env=env, timeout=600)
    assert again.returncode == 0, again.stderr[-3000:]
    assert "6 fits, 1 to run" in again.stderr
    assert fit_lines_skipping_broken(ours / "fits.jsonl") == fit_lines(theirs / "fits.jsonl")
    assert table_without_seconds(str(ours / "summary.csv")) == \
        table_without_seconds(str(theirs / "summary.csv"))


def fit_lines_skipping_broken(path):
    """The fit lines of a file that may hold a half line (ignored, as read)."""
    lines = {}
    with open(path) as f:
        for line in f:
            try:
                v = json.loads(line)
            except json.JSONDecodeError:
                continue
            lines[(v["data"], v["model"])] = without_seconds(v)
    return lines


def test_the_formatters_are_the_workspace_s():
    # Hand-derived: three significant digits keep a trailing zero; outside
    # 1e-4 .. 1e6 the notation is scientific with Rust's exponent; in full,
    # Rust's shortest round-trip digits without an exponent.
    assert brdf.format_number(0.019, 3) == "0.0190"
    assert brdf.format_number(1234.6, 3) == "1235"
    assert brdf.format_number(1.5e-7, 2) == "1.5e-7"
    assert brdf.format_number(0.0, 4) == "0"
    assert brdf.format_number(float("nan"), 3) == "NaN"
    assert brdf.format_full(0.1) == "0.1"
    assert brdf.format_full(1e-7) == "0.0000001"
    assert brdf.format_full(2.5e6) == "2500000"
