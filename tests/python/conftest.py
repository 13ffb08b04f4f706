"""Shared by the Python module's tests (ctest Python.*): the godfinger executable of the same
build, run the way a user would, to compare the module's answers with the command line's.

ctest sets PYTHONPATH to <build>/python (where the module is) and GF_BINARY_DIR to the build."""
import json
import os
import subprocess

import pytest


@pytest.fixture(scope="session")
def cli():
    """Runs `godfinger ARGS...`; returns the finished process (text output)."""
    exe = os.path.join(os.environ["GF_BINARY_DIR"], "godfinger")

    def run(*args, stdin=None, check=True):
        done = subprocess.run([exe, *args], input=stdin, capture_output=True, text=True)
        if check and done.returncode != 0:
            raise AssertionError(f"godfinger {' '.join(args)} exited {done.returncode}:\n{done.stderr}")
        return done

    return run


def cli_error(done):
    """The message of a refused command: its stderr without 'godfinger: error: '."""
    assert done.returncode != 0, done.stdout
    line = done.stderr.strip().splitlines()[-1]
    prefix = "godfinger: error: "
    assert line.startswith(prefix), done.stderr
    return line[len(prefix):]


def read_json(path):
    with open(path, encoding="utf-8") as f:
        return json.load(f)
