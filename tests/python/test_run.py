"""godfinger.run(): the same run as `godfinger run`, read back into numpy arrays and dicts."""
import os

import numpy as np
import pytest

import godfinger
from conftest import cli_error, read_json


def read_trace(path):
    """trace.csv as the command wrote it: Python's float() reads shortest round-trip decimals exactly."""
    with open(path, encoding="utf-8") as f:
        header = f.readline().strip().split(",")
        rows = [[float(x) for x in line.split(",")] for line in f]
    return header, np.array(rows)


def test_trace_is_bit_identical_to_the_command_line(cli, tmp_path):
    cli("run", "fig8-pinch-oscillation", "--duration", "0.9", "--quiet", "--out", str(tmp_path / "cli"))
    header, rows = read_trace(tmp_path / "cli" / "trace.csv")
    run = godfinger.run("fig8-pinch-oscillation", duration=0.9)
    assert list(run.trace) == header
    assert run.steps == len(rows) == 900
    for i, column in enumerate(header):
        array = run.trace[column]
        assert array.dtype == np.float64
        assert array.tobytes() == rows[:, i].tobytes(), column


def test_set_gives_the_same_run_as_the_command_lines_set(cli, tmp_path):
    cli("run", "press-box", "--duration", "0.3", "--quiet", "--out", str(tmp_path / "cli"),
        "--set", "fingers.index.n_sgo=0", "--set", "fingers.index.friction=0.5")
    header, rows = read_trace(tmp_path / "cli" / "trace.csv")
    run = godfinger.run("press-box", duration=0.3, set={"fingers.index.n_sgo": 0, "fingers.index.friction": 0.5})
    assert list(run.trace) == header
    assert np.array_equal(np.column_stack([run.trace[c] for c in header]), rows)
    assert (run.trace["index.n_sgo"] == 0).all()


def test_summary_and_contacts_are_the_command_lines_files(cli, tmp_path):
    cli("run", "press-box", "--duration", "1.05", "--quiet", "--out", str(tmp_path / "cli"))
    run = godfinger.run("press-box", duration=1.05)
    expected = read_json(tmp_path / "cli" / "summary.json")
    # "render": the command draws a close-up beside each contact snapshot; run() only with close_ups=True.
    assert set(run.summary) == set(expected) - {"render"}
    assert run.summary["settings"] == expected["settings"]
    assert run.summary["counters"] == expected["counters"]
    names = sorted(os.path.splitext(f)[0] for f in os.listdir(tmp_path / "cli" / "contacts") if f.endswith(".json"))
    assert list(run.contacts) == names and names
    for name in names:
        assert run.contacts[name] == read_json(tmp_path / "cli" / "contacts" / f"{name}.json")


def test_close_ups_are_drawn_on_request(cli, tmp_path):
    run = godfinger.run("press-box", duration=1.05, out=str(tmp_path / "py"), close_ups=True)
    assert "render" in run.summary
    assert sorted(p.name for p in (tmp_path / "py" / "contacts").iterdir() if p.suffix == ".png")


def test_out_keeps_the_run_folder(tmp_path):
    run = godfinger.run("press-box", duration=0.05, out=str(tmp_path / "kept"))
    assert run.out == str(tmp_path / "kept")
    assert (tmp_path / "kept" / "trace.csv").exists() and (tmp_path / "kept" / "summary.json").exists()


def test_a_bad_field_raises_input_error_with_the_command_lines_message(cli):
    said = cli_error(cli("run", "press-box", "--set", "fingers.index.d0=-1", check=False))
    with pytest.raises(godfinger.InputError) as raised:
        godfinger.run("press-box", set={"fingers.index.d0": -1})
    assert str(raised.value) == said
    assert isinstance(raised.value, ValueError)


def test_a_set_value_with_a_newline_is_refused_as_the_command_line_refuses_it(cli):
    said = cli_error(cli("run", "press-box", "--set", "duration=0.05\nfingers.index.r_max = 0.5", check=False))
    assert "duration: holds a control character (0x0a, a newline)" in said
    with pytest.raises(godfinger.InputError) as raised:
        godfinger.run("press-box", set={"duration": "0.05\nfingers.index.r_max = 0.5"})
    assert str(raised.value) == said


def test_an_unknown_scene_raises_input_error_with_the_command_lines_message(cli):
    said = cli_error(cli("run", "no-such-scene", check=False))
    with pytest.raises(godfinger.InputError, match="no-such-scene") as raised:
        godfinger.run("no-such-scene")
    assert str(raised.value) == said


def test_a_duration_out_of_range_raises_input_error():
    with pytest.raises(godfinger.InputError, match="duration"):
        godfinger.run("press-box", duration=-1.0)


def test_a_value_of_another_type_raises_input_error_naming_the_field():
    with pytest.raises(godfinger.InputError, match="fingers.index.n_sgo"):
        godfinger.run("press-box", set={"fingers.index.n_sgo": object()})
