"""Fixtures: the CLI binary (FRACTERRA_CLI, set by CTest; else build/fracterra) and the test data."""
import json
import os
import subprocess

import pytest

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), os.pardir, os.pardir))
DATA = os.path.join(ROOT, "tests", "data")


@pytest.fixture(scope="session")
def data():
    return lambda name: os.path.join(DATA, name)


@pytest.fixture(scope="session")
def cli_exe():
    exe = os.environ.get("FRACTERRA_CLI", os.path.join(ROOT, "build", "fracterra"))
    if not os.path.exists(exe):
        pytest.skip("no fracterra CLI at %s" % exe)
    return exe


@pytest.fixture(scope="session")
def cli(cli_exe):
    exe = cli_exe

    def run(*args, json_out=True):
        p = subprocess.run([exe, *map(str, args)] + (["--json"] if json_out else []), capture_output=True,
                           text=True)
        assert p.returncode == 0, p.stderr
        return json.loads(p.stdout) if json_out else p.stdout

    return run
