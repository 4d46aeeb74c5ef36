"""Shared by the Python tests: the measured data (skipped, and said, when
BRDF_DATA is unset; a loud failure when it is set and a file is missing) and
the `brdf` command the Python results are compared with."""

import json
import os
import shutil
import subprocess
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[3]
EXAMPLES = Path(__file__).resolve().parents[1] / "examples"


def data_file(rel):
    """The file `rel` under BRDF_DATA, or skip (said) when it is unset."""
    root = os.environ.get("BRDF_DATA")
    if not root:
        pytest.skip("skipped: BRDF_DATA is not set")
    path = Path(root) / rel.split("#")[0]
    assert path.exists(), f"BRDF_DATA is set but {path} is missing"
    return str(Path(root) / rel)


@pytest.fixture(scope="session")
def brdf_cli():
    """The `brdf` binary: $BRDF_BIN, else built with cargo (debug)."""
    exe = os.environ.get("BRDF_BIN")
    if not exe:
        subprocess.run(["cargo", "build", "-q", "-p", "brdf-cli"], cwd=REPO, check=True)
        target = os.environ.get("CARGO_TARGET_DIR", str(REPO / "target"))
        exe = str(Path(target) / "debug" / "brdf")
    assert shutil.which(exe), f"the brdf binary {exe} is missing"

    def run(*args):
        out = subprocess.run([exe, *args], capture_output=True, text=True)
        assert out.returncode == 0, f"brdf {' '.join(args)} failed: {out.stderr}"
        return out.stdout

    return run


def cli_json(brdf_cli, *args):
    """`brdf ... --json` parsed."""
    return json.loads(brdf_cli(*args, "--json"))


def without_seconds(value):
    """A report with its wall-clock times removed (they differ run to run)."""
    if isinstance(value, dict):
        return {k: without_seconds(v) for k, v in value.items() if k != "seconds"}
    if isinstance(value, list):
        return [without_seconds(v) for v in value]
    return value
