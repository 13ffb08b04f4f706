#!/usr/bin/env python3
"""Browser test of a web experiment (app/experiment/web_participant.hpp): a participant runs both
blocks of tests/browser/experiment/pilot.toml in headless Chromium with the mouse, in two sessions.

`godfinger experiment pilot.toml --participant 1 --serve 127.0.0.1:0` serves the page; for each
block the test waits for the ready panel, clicks Start, drags the hand across the box while the
trial runs (the pointer moves the task's finger), waits for the questionnaire, sets its six
scales and the realism rating with the mouse and submits. The first session stops after one
trial (--stop-after 1: exit 130 once the block's questionnaire is in); the same command again
resumes at the second trial on the same port (its first phase is ready-2, which the page left open
follows), and then exits 0, and:

- the trial table has both trials, each with its model, and the trials' traces show the finger
  pushed by the drag (its device moved at least 3 cm along x);
- the questionnaire table has both blocks' answers as given, with Raw TLX their mean;
- no condition's name (god_object, god_finger, model) was ever on the page, and neither
  /scene.json, /state.json nor the `state` command names a model, setting, SGO count or contact;
- `set`, `record` and `snapshot` are refused during a trial;
- Submit refuses a questionnaire whose scales were not all touched.

Usage: experiment_test.py GODFINGER OUT_DIR
Writes OUT_DIR/experiment-trial.png and OUT_DIR/experiment-questionnaire.png, the logs, and the
experiment's folder OUT_DIR/experiment/. With GF_EXPERIMENT_SCREENSHOT=PATH the trial's
screenshot is also copied to PATH. Every wait has a generous timeout as a guard.
"""
from __future__ import annotations

import csv
import json
import os
import shutil
from pathlib import Path

from cdp import Browser, Page, poll
from served import Served, script, verdict

ROOT = Path(__file__).resolve().parents[2]
PILOT = ROOT / "tests" / "browser" / "experiment" / "pilot.toml"
HIDDEN = ["god_object", "god_finger", "model"]  # the condition: never on the participant's page
ANSWERS = [  # per block: the six TLX scales and realism, as the test sets them
    {"mental_demand": 35, "physical_demand": 20, "temporal_demand": 55, "performance": 10, "effort": 40,
     "frustration": 5, "realism": 6},
    {"mental_demand": 60, "physical_demand": 45, "temporal_demand": 30, "performance": 25, "effort": 70,
     "frustration": 15, "realism": 3},
]


def read_tsv(path: Path) -> list[dict[str, str]]:
    """The rows of a TSV table, by column name."""
    with open(path, newline="") as f:
        return list(csv.DictReader(f, delimiter="\t"))


def page_text(page: Page) -> str:
    """Everything the page shows as text."""
    return page.evaluate("document.body.innerText")


def assert_nothing_hidden(page: Page, where: str, seen: list[str]) -> None:
    """No condition's name in the page's text."""
    text = page_text(page)
    seen.append(text)
    for word in HIDDEN:
        assert word not in text, f"{where}: the page shows {word!r}:\n{text}"


def run_trial(page: Page, served: Served, block: int, out_dir: Path) -> None:
    """Clicks Start on the ready panel and drags the hand along +x across the box; checks what the
    server refuses and hides during the trial."""
    page.wait_for(f"window.gf.panel && (window.gf.panel.id || '').startsWith('ready-{block}-')", f"the ready panel of block {block}")
    page.click(page.centre("#start"))
    page.wait_for("window.gf.panel.phase === 'trial' && !!window.gf.hand.anchor", f"trial {block} with the hand placed")
    # The trial is the participant's, in real time (4 s): what the server refuses during it is
    # asked at once (three short requests), then the drag; the checks after the drag take a
    # while on a loaded machine (a screenshot), and may come after the trial's end.
    for line in ("set fingers.index.n_sgo=0", "record start", "snapshot x"):
        answer = served.command(line)
        assert answer.startswith("error:") and "experiment" in answer, f"{line!r} during a trial answered {answer!r}"
    # The drag starts on the picture once the picture has a frame (a slow first frame leaves the
    # image without a size, and the pointer lands beside it).
    page.wait_for("document.querySelector('#frame').naturalWidth > 0", f"trial {block}'s first frame")
    anchor = page.evaluate("window.gf.hand.anchor")
    start = page.evaluate(f"window.gf.project({json.dumps(anchor)})")
    end = page.evaluate(f"window.gf.project({json.dumps([anchor[0] + 0.06, anchor[1], anchor[2]])})")
    hit = page.evaluate(f"(document.elementFromPoint({start[0]}, {start[1]}) || {{}}).id")
    assert hit == "frame", f"trial {block}: the hand's point on the page is on #{hit}, not on the picture"
    page.drag((start[0], start[1]), (end[0], end[1]), steps=40)
    # The device follows the drag while the trial's view lasts; on a loaded machine the drag may
    # end the trial (the task done) before this looks, and /state.json is {} once the trial's
    # view is gone. The trace shows the move either way (check_outputs).
    def followed_or_over() -> bool:
        fingers = served.state().get("fingers")
        return not fingers or fingers[0]["device"][0] - anchor[0] > 0.03
    poll(followed_or_over, f"trial {block}: the device to follow the drag")
    if block == 1:
        page.screenshot(out_dir / "experiment-trial.png")
    live = served.state()
    if not live.get("fingers"):
        return  # the trial ended first: what a trial serves is checked when it outlasts the drag
    # What the page may read: no model, setting, SGO count or contact (each tells the condition).
    state_answer = served.command("state")
    assert state_answer.startswith("ok "), state_answer
    for text in (served.get("/scene.json").text(), json.dumps(live), state_answer):
        for word in [*HIDDEN, "n_sgo", "sgos", "settings", "contacts", "radius"]:
            assert word not in text, f"the page can read {word!r}: {text[:400]}"
    for f in live["fingers"]:
        assert set(f) <= {"name", "proxy", "device", "force_n"}, f"/state.json's finger: {sorted(f)}"


def answer_questionnaire(page: Page, block: int, out_dir: Path) -> None:
    """Sets the sliders (value and an input event, as dragging one does) and clicks the realism
    rating and Submit with the mouse."""
    page.wait_for(f"(window.gf.panel.id || '').startsWith('questionnaire-{block}-')", f"the questionnaire after block {block}")
    answers = ANSWERS[block - 1]
    # Untouched scales are not answers: Submit says so and sends nothing.
    page.click(page.centre(f"input[name=realism][value='{answers['realism']}']"))
    page.click(page.centre("#questionnaire button[type=submit]"))
    page.wait_for("document.querySelector('#questionnaire .result').textContent.includes('Please answer every scale')",
                  "Submit to refuse untouched scales")
    for key, value in answers.items():
        if key == "realism":
            continue
        page.evaluate(f"""(() => {{ const e = document.querySelector('input[name={key}]');
            e.value = {value}; e.dispatchEvent(new Event('input', {{bubbles: true}})); }})()""")
    page.click(page.centre(f"input[name=realism][value='{answers['realism']}']"))
    if block == 1:
        page.screenshot(out_dir / "experiment-questionnaire.png")
    page.click(page.centre("#questionnaire button[type=submit]"))
    page.wait_for("document.querySelector('#panel h2').textContent.startsWith('Thank you')", "the thanks after submitting")


def check_outputs(data: Path) -> None:
    """The trial and questionnaire tables, and the drag in the traces."""
    beh = data / "sub-01" / "beh"
    trials = read_tsv(beh / "sub-01_task-browserpilot_beh.tsv")
    assert [t["model"] for t in trials] == ["god_object", "god_finger"], f"the trials' models: {trials}"
    for t in trials:
        assert t["success"] in ("0", "1"), f"trial {t['trial']}: success {t['success']!r}"
        with open(beh / t["run"].removeprefix("beh/") / "trace.csv") as f:
            rows = list(csv.DictReader(f))
        xs = [float(r["index.dx"]) for r in rows]
        assert max(xs) - xs[0] > 0.03, f"trial {t['trial']}: the device moved {max(xs) - xs[0]:.4f} m along x"
    answers = read_tsv(beh / "sub-01_task-browserpilot_questionnaire.tsv")
    assert [a["block"] for a in answers] == ["1", "2"], answers
    for row, given in zip(answers, ANSWERS):
        for key, value in given.items():
            assert int(row[key]) == value, f"block {row['block']}: {key} {row[key]}, the page set {value}"
        tlx = sum(given[k] for k in given if k != "realism") / 6
        assert abs(float(row["raw_tlx"]) - tlx) < 0.01, f"raw_tlx {row['raw_tlx']}, want {tlx}"
    assert answers[0]["model"] == "god_object" and answers[1]["model"] == "god_finger", answers
    report = (data / "report.md").read_text()
    assert "## Questionnaire" in report, "report.md has no questionnaire section"


def run_block(page: Page, served: Served, block: int, out_dir: Path, want_exit: int) -> None:
    """One block on the page (a trial, its questionnaire), after which the experiment exits `want_exit`."""
    seen: list[str] = []
    run_trial(page, served, block, out_dir)
    assert_nothing_hidden(page, f"trial {block}", seen)
    answer_questionnaire(page, block, out_dir)
    assert_nothing_hidden(page, f"questionnaire {block}", seen)
    poll(lambda: served.process.poll() is not None, f"the experiment to exit after block {block}")
    code = served.process.returncode
    assert code == want_exit, f"godfinger experiment exited {code}, want {want_exit}:\n{served.log_tail()}"


def main(binary: Path, out_dir: Path) -> int:
    out_dir.mkdir(parents=True, exist_ok=True)
    data = out_dir / "experiment"
    shutil.rmtree(data, ignore_errors=True)
    command = [str(binary), "experiment", str(PILOT), "--participant", "1", "--serve", "127.0.0.1:0", "--out", str(data)]
    # The first session stops after its first trial (as a participant who leaves would): the
    # block's questionnaire is asked, then it exits 130 with both written.
    served = Served.start([*command, "--stop-after", "1"], out_dir / "godfinger-experiment-1.log")
    browser = None

    def check() -> str:
        nonlocal served, browser
        browser = Browser.launch(out_dir / "chromium-experiment.log")
        page = browser.new_page(width=1600, height=900)
        page.navigate(served.url("/"), until="Page.domContentEventFired")
        run_block(page, served, 1, out_dir, 130)
        beh = data / "sub-01" / "beh"
        first = read_tsv(beh / "sub-01_task-browserpilot_beh.tsv")
        assert len(first) == 1 and len(read_tsv(beh / "sub-01_task-browserpilot_questionnaire.tsv")) == 1, first
        # The same command again, on the same port, resumes: its first phase is the second trial's,
        # and the page left open follows it there (a resumed phase is a new one to it).
        served.stop()
        again = [*command[:command.index("--serve") + 1], f"127.0.0.1:{served.port}", *command[command.index("--serve") + 2:]]
        served = Served.start(again, out_dir / "godfinger-experiment-2.log")
        run_block(page, served, 2, out_dir, 0)
        assert read_tsv(beh / "sub-01_task-browserpilot_beh.tsv")[0] == first[0], "the first session's trial changed"
        check_outputs(data)
        if os.environ.get("GF_EXPERIMENT_SCREENSHOT"):
            shutil.copyfile(out_dir / "experiment-trial.png", os.environ["GF_EXPERIMENT_SCREENSHOT"])
        return "a participant ran both blocks with the mouse; tables and questionnaire written; no condition shown"

    try:
        return verdict(check, lambda: served.log_tail())
    finally:
        if browser:
            browser.close()
        served.stop()


if __name__ == "__main__":
    script(main, __doc__)
