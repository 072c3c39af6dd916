"""What the Python tests share: the rtiow program the command line runs, and a scratch directory."""

import os
import subprocess

import pytest


@pytest.fixture
def run_rtiow():
    """rtiow with an argument vector (no shell), its exit code and stderr."""

    def run(*args):
        done = subprocess.run([os.environ["RTIOW_BINARY"], *map(str, args)],
                              stdin=subprocess.DEVNULL, capture_output=True, text=True,
                              timeout=300, check=False)
        return done.returncode, done.stderr

    return run
