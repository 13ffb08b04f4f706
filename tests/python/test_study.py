"""godfinger.study(): an accuracy study run as `godfinger study` runs it, results.csv as arrays."""
import csv

import numpy as np
import pytest

import godfinger
from conftest import cli_error

# The smallest quick grid of the bundled studies: a handful of short runs.
STUDY = "rolling"
# Wall-clock columns: they differ between any two runs of the same configuration.
TIMINGS = {"step_us_median", "step_us_p99", "patch_us_mean"}


def test_quick_results_equal_the_command_lines_results_csv(cli, tmp_path):
    cli("study", STUDY, "--quick", "--jobs", "1", "--out", str(tmp_path / "cli"))
    with open(tmp_path / "cli" / "results.csv", newline="", encoding="utf-8") as f:
        rows = list(csv.reader(f))
    header, rows = rows[0], rows[1:]
    results = godfinger.study(STUDY, quick=True, jobs=1)
    assert list(results) == header
    assert len(results["measure"]) == len(rows) > 0
    assert (results["step_us_median"] > 0).all()
    for i, column in enumerate(header):
        cells = [row[i] for row in rows]
        if column in TIMINGS:
            assert results[column].dtype == np.float64, column
            continue
        if results[column].dtype == np.float64:
            assert results[column].tobytes() == np.array([float(c) for c in cells]).tobytes(), column
        else:
            assert list(results[column]) == cells, column


def test_an_unknown_study_raises_input_error_with_the_command_lines_message(cli):
    said = cli_error(cli("study", "no-such-study", "--quick", check=False))
    with pytest.raises(godfinger.InputError) as raised:
        godfinger.study("no-such-study", quick=True)
    assert str(raised.value) == said


def test_jobs_out_of_range_raises_input_error():
    with pytest.raises(godfinger.InputError, match="jobs"):
        godfinger.study(STUDY, jobs=0)


def test_a_study_into_its_folder_again_keeps_its_runs_unless_restart(tmp_path):
    """A second study() into the same folder keeps the finished runs (their files untouched, the
    results equal, step times included, since they are the kept runs' own); restart=True runs
    them all again."""
    out = tmp_path / "study"
    first = godfinger.study(STUDY, quick=True, jobs=1, out=out)
    summaries = sorted(out.glob("runs/*/summary.json"))
    assert summaries, "the study left no run folders"
    stamps = [p.stat().st_mtime_ns for p in summaries]
    again = godfinger.study(STUDY, quick=True, jobs=1, out=out)
    assert [p.stat().st_mtime_ns for p in summaries] == stamps, "a finished run was run again"
    assert list(again) == list(first)
    for column in first:
        if first[column].dtype == np.float64:
            assert again[column].tobytes() == first[column].tobytes(), column
        else:
            assert list(again[column]) == list(first[column]), column
    godfinger.study(STUDY, quick=True, jobs=1, out=out, restart=True)
    assert all(p.stat().st_mtime_ns != s for p, s in zip(summaries, stamps)), "restart=True kept a run"
