"""The examples' guard (examples/python/godfinger_guard.py): a python that cannot import godfinger
or numpy gets the interpreter the module was built for and the command to run, not a traceback."""
import importlib.util
import os
import subprocess
import sys
import types

import godfinger
import godfinger_build_info

SOURCE = os.environ["GF_SOURCE_DIR"]
GUARD = os.path.join(SOURCE, "examples", "python", "godfinger_guard.py")
QUICKSTART = os.path.join("examples", "python", "quickstart.py")


def guard():
    spec = importlib.util.spec_from_file_location("godfinger_guard", GUARD)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


INFO = types.SimpleNamespace(PYTHON="/usr/bin/python3", VERSION="3.11",
                             MODULE="godfinger.cpython-311-x86_64-linux-gnu.so")


def test_another_interpreter_is_told_the_command_to_run_and_how_to_build_for_itself():
    text = guard().failure_message(ModuleNotFoundError("No module named 'numpy'"), "/usr/local/bin/python3", "3.12",
                                   ["examples/python/quickstart.py"], INFO)
    lines = text.splitlines()
    assert "/usr/local/bin/python3 (Python 3.12): No module named 'numpy'" in lines[0]
    assert "built for /usr/bin/python3 (Python 3.11)" in lines[1]
    assert lines[2] == "    /usr/bin/python3 examples/python/quickstart.py"
    assert "-DGF_PYTHON3=/usr/local/bin/python3" in lines[-1]


def test_the_built_for_interpreter_is_told_what_is_missing():
    text = guard().failure_message(ModuleNotFoundError("No module named 'numpy'"), "/usr/bin/python3", "3.11",
                                   ["quickstart.py"], INFO)
    assert "the interpreter the module was built for" in text and "python3-numpy" in text
    assert "-DGF_PYTHON3" not in text


def test_no_built_module_is_told_how_to_build_one():
    text = guard().failure_message(ImportError("No module named 'godfinger'"), "/opt/py/bin/python3", "3.13",
                                   ["quickstart.py"], None)
    assert "No built module found" in text and "scripts/demo" in text


def test_the_build_records_its_interpreter():
    assert os.path.realpath(godfinger_build_info.PYTHON) == os.path.realpath(sys.executable)
    assert godfinger_build_info.VERSION == f"{sys.version_info[0]}.{sys.version_info[1]}"
    assert os.path.basename(godfinger.__file__) == godfinger_build_info.MODULE


def quickstart(*python_options, pythonpath):
    env = dict(os.environ, PYTHONPATH=pythonpath)
    return subprocess.run([sys.executable, *python_options, QUICKSTART], cwd=SOURCE, env=env, capture_output=True,
                          text=True)


def test_quickstart_without_numpy_stops_with_the_message_not_a_traceback():
    # -S: no site-packages, so no numpy (Debian's is there); the module itself imports.
    done = quickstart("-S", pythonpath=os.environ["PYTHONPATH"])
    assert done.returncode == 1 and done.stdout == ""
    assert "Traceback" not in done.stderr
    assert "No module named 'numpy'" in done.stderr and "python3-numpy" in done.stderr


def test_quickstart_under_another_interpreter_names_the_one_to_use(tmp_path):
    # What an interpreter that is not the module's sees: its build info names another python.
    (tmp_path / "godfinger_build_info.py").write_text(
        'PYTHON = "/opt/built-for/bin/python3"\nVERSION = "3.99"\nMODULE = "godfinger.cpython-399.so"\n')
    done = quickstart("-S", pythonpath=f"{tmp_path}{os.pathsep}{os.environ['PYTHONPATH']}")
    assert done.returncode == 1 and "Traceback" not in done.stderr
    assert f"    /opt/built-for/bin/python3 {QUICKSTART}" in done.stderr.splitlines()
    assert f"-DGF_PYTHON3={sys.executable}" in done.stderr
