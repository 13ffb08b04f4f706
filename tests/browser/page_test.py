#!/usr/bin/env python3
"""Browser tests of `godfinger run --realtime --serve` (issue 34): the page in headless Chromium,
driven over the DevTools pipe (cdp.py), against the server's contract of issue 34:

- the page shows /stream.mjpg (1280 × 720, asked for at the width it shows it) in img#frame,
  with a row and settings controls per finger, and the stream is multipart/x-mixed-replace of
  JPEG parts;
- a pointer drag (and wheel, for depth) on the image presses the web finger `index` onto the
  cylinder of the scene live-view: /state.json then shows its contact;
- the page's n_sgo control sets the finger's setting; /command answers `ok`/`error:`;
- the page times its own moves to the frames that show them (the parts' X-Moves-* headers);
- with --token, every request without the token gets 401.

Usage: page_test.py GODFINGER OUT_DIR
Writes OUT_DIR/live-view.png (the screenshot of the press), godfinger's and Chromium's logs.
With GF_BROWSER_SCREENSHOT=PATH the screenshot is also copied to PATH (the README's picture).
Every wait has a generous timeout as a guard; nothing waits for a fixed time.
"""
from __future__ import annotations

import hashlib
import json
import math
import os
import shutil
import time
import tomllib
import traceback
from contextlib import closing
from dataclasses import dataclass
from pathlib import Path
from typing import Callable

from cdp import Browser, Page, poll
from served import Served, is_jpeg, mjpeg_parts, request, script

ROOT = Path(__file__).resolve().parents[2]
SCENE = ROOT / "assets" / "scenes" / "live-view.toml"
FIELDS = ["n_sgo", "r_max", "alpha", "tau_a", "friction"]
FINGERS = ["index", "thumb"]
Vec = list[float]


@dataclass
class Context:
    """What every test gets: the server, a tab on its page, and the output folder."""
    served: Served
    page: Page
    out_dir: Path


def serve_command(binary: Path, out_dir: Path, serve: str, *extra: str) -> list[str]:
    """The godfinger command line of the tests: live-view in real time, served at `serve`."""
    return [str(binary), "run", "live-view", "--realtime", "--serve", serve, "--out", str(out_dir),
            "--set", "duration=600", "--no-fifo", *extra]


# Vectors and the state ------------------------------------------------------------------------

def add(a: Vec, b: Vec, scale: float = 1.0) -> Vec:
    """a + scale · b."""
    return [x + scale * y for x, y in zip(a, b)]


def dot(a: Vec, b: Vec) -> float:
    """a · b."""
    return sum(x * y for x, y in zip(a, b))


def finger(state: dict, name: str) -> dict:
    """The finger `name` of a /state.json."""
    found = [f for f in state["fingers"] if f["name"] == name]
    assert found, f"no finger {name!r} in /state.json: {[f['name'] for f in state['fingers']]}"
    return found[0]


def body(state: dict, name: str) -> dict:
    """The dynamic body `name` of a /state.json."""
    found = [b for b in state["bodies"] if b["name"] == name]
    assert found, f"no body {name!r} in /state.json: {[b['name'] for b in state['bodies']]}"
    return found[0]


def proxy(served: Served, name: str) -> Vec:
    """The finger's proxy position now, m."""
    return finger(served.state(), name)["proxy"]


def wait_settled(served: Served, name: str, what: str, tolerance_m: float = 1e-4) -> Vec:
    """The proxy of `name` once it moves less than `tolerance_m` between three polls in a row."""
    history: list[Vec] = []

    def settled() -> Vec | None:
        history.append(proxy(served, name))
        recent = history[-3:]
        if len(recent) == 3 and all(math.dist(p, recent[-1]) < tolerance_m for p in recent):
            return recent[-1]
        return None

    return poll(settled, f"{name}'s proxy to settle {what}", interval_s=0.1)


# The page -----------------------------------------------------------------------------------

def project(page: Page, point: Vec) -> tuple[float, float]:
    """Where the scene point (m) is shown, in viewport CSS px (the page's window.gf.project)."""
    px = page.evaluate(f"window.gf.project({json.dumps(point)})")
    assert isinstance(px, list) and len(px) == 2, f"gf.project({point}) = {px!r}, want [px, py]"
    return px[0], px[1]


def set_control(page: Page, selector: str, value: str) -> None:
    """Sets an input's or select's value and dispatches `change`, as a user's edit would."""
    page.evaluate(f"""(() => {{ const e = document.querySelector({json.dumps(selector)});
        if (!e) throw new Error('no element ' + {json.dumps(selector)});
        e.value = {json.dumps(value)}; e.dispatchEvent(new Event('change', {{bubbles: true}})); }})()""")


def drag_finger_to(ctx: Context, name: str, target: Vec) -> Vec:
    """Drags the finger from its shown proxy to where `target` is shown; waits until its proxy is
    shown under the pointer (3 px) and settled; returns the proxy."""
    start, end = project(ctx.page, proxy(ctx.served, name)), project(ctx.page, target)
    ctx.page.drag(start, end, steps=20)

    def under_pointer() -> bool:
        return math.dist(project(ctx.page, proxy(ctx.served, name)), end) < 3.0

    poll(under_pointer, f"{name} to be shown under the pointer at {end} after a drag from {start} (does the"
         " page stop the image's native drag-and-drop: draggable=false, preventDefault on pointerdown?)")
    return wait_settled(ctx.served, name, "after the drag")


def wheel_finger(ctx: Context, name: str, notches: int, expected_m: float) -> Vec:
    """Turns the wheel `notches` times (deltaY -100 each; negative: +100) over the shown finger;
    waits until it has moved at least `expected_m` and settled."""
    before = proxy(ctx.served, name)
    at = project(ctx.page, before)
    for _ in range(abs(notches)):
        ctx.page.wheel(at, -100.0 if notches > 0 else 100.0)
    poll(lambda: math.dist(proxy(ctx.served, name), before) >= expected_m,
         f"{notches} wheel notch(es) over {name} to move it {expected_m * 1000:.1f} mm")
    return wait_settled(ctx.served, name, "after the wheel")


def place_finger(ctx: Context, name: str, target: Vec, tolerance_m: float = 0.004) -> Vec:
    """Brings the finger to `target` with the pointer alone: the wheel matches its depth (one
    notch measured first: the view direction), a drag puts it under the target; repeated until
    within `tolerance_m` (or 0.6 notch)."""
    before = proxy(ctx.served, name)
    position = wheel_finger(ctx, name, 1, 2e-4)
    notch = add(position, before, -1.0)
    notch_m = math.sqrt(dot(notch, notch))
    for _ in range(4):
        notches = max(-40, min(40, round(dot(add(target, position, -1.0), notch) / notch_m**2)))
        if notches:
            wheel_finger(ctx, name, notches, 0.5 * abs(notches) * notch_m)
        position = drag_finger_to(ctx, name, target)
        if math.dist(position, target) < max(tolerance_m, 0.6 * notch_m):
            return position
    raise AssertionError(f"{name} at {position}, not within {tolerance_m} m of {target} after 4 rounds")


def save_screenshot(ctx: Context, name: str) -> Path:
    """The viewport into OUT_DIR/`name`, and to $GF_BROWSER_SCREENSHOT if set."""
    shot = ctx.page.screenshot(ctx.out_dir / name)
    if os.environ.get("GF_BROWSER_SCREENSHOT"):
        shutil.copyfile(shot, os.environ["GF_BROWSER_SCREENSHOT"])
    return shot


# The tests ----------------------------------------------------------------------------------

def test_page_shows_the_stream(ctx: Context) -> None:
    """(a) The page loads with its controls, img#frame shows the 1280 × 720 frames (asked of the
    stream at the width it shows them, `width=`: shrunk by the largest whole factor that keeps
    them at least that wide), and the stream delivers three distinct JPEG parts (the thumb moves
    meanwhile, so frames differ)."""
    ctx.page.navigate(ctx.served.url("/"), until="Page.domContentEventFired")
    ctx.page.wait_for("document.querySelector('img#frame')?.naturalWidth", "img#frame's first frame")
    # The first frame may be one encoded before the page's width was asked for.
    shown = ctx.page.wait_for(
        "(() => { const i = document.querySelector('img#frame'), w = Math.ceil(i.clientWidth * devicePixelRatio);"
        " const k = Math.max(1, Math.floor(1280 / gf.stream.width));"
        " return Math.abs(w - gf.stream.width) <= 1 && i.naturalWidth === Math.ceil(1280 / k)"
        " && i.naturalHeight === Math.ceil(720 / k) && [i.naturalWidth, i.clientWidth]; })()",
        "img#frame's frames at the width it shows them")
    assert shown[0] >= shown[1], f"img#frame is {shown[0]} px wide, shown at {shown[1]}"
    for name in FINGERS:
        for selector in [f"#fingers tr[data-finger={name}]", f"input[data-finger={name}][data-field=god_finger]",
                         *(f"input[data-finger={name}][data-field={field}]" for field in FIELDS),
                         f"select#web-finger option[value={name}]"]:
            # The finger rows come with the first state the page reads: waited for, as every control.
            ctx.page.wait_for(f"!!document.querySelector('{selector}')", f"{selector} on the page")
    assert ctx.page.evaluate("!!document.querySelector('button#record')"), "no button#record on the page"
    with closing(mjpeg_parts(ctx.served.url("/stream.mjpg"))) as parts:
        seen = {part_digest(next(parts))}
        # The thumb rises 2 cm in 2 s from now: the frames differ.
        answer = ctx.served.command("move thumb {} {} {} 2".format(*add(proxy(ctx.served, "thumb"), [0, 0.02, 0])))
        assert answer.startswith("ok"), f"move thumb: {answer}"
        while len(seen) < 3:
            seen.add(part_digest(next(parts)))


def part_digest(part: tuple[dict[str, str], bytes]) -> str:
    """The SHA-256 of a stream part, checked to be a JPEG labelled image/jpeg."""
    headers, body = part
    assert headers.get("content-type") == "image/jpeg" and is_jpeg(body), f"a stream part {headers}, not a JPEG"
    return hashlib.sha256(body).hexdigest()


# Pixels of a fresh frame (/frame.jpg, decoded by the page's browser) in its right half that are
# light blue: the patch highlight in `index`'s inset (the insets stand there, a column clear of
# the bodies in the middle, render/overlay/layout.hpp; the blue cylinder and fingers stand in the
# left half; the inset's blue frame alone is about 1 700).
BLUE_IN_INSETS_JS = """(async () => {
  const bitmap = await createImageBitmap(await (await fetch(withToken("frame.jpg"))).blob());
  const canvas = new OffscreenCanvas(bitmap.width, bitmap.height), g = canvas.getContext("2d");
  g.drawImage(bitmap, 0, 0);
  const d = g.getImageData(bitmap.width / 2, 0, bitmap.width / 2, bitmap.height).data;
  let n = 0;
  for (let i = 0; i < d.length; i += 4) n += d[i + 2] > 150 && d[i + 2] - d[i] > 40;
  return n;
})()"""


def test_a_narrower_page_reads_smaller_frames(ctx: Context) -> None:
    """(a') The same page made 1000 × 700 CSS px (its view about 640 px wide): it reads the
    stream again at its new width and gets the frames halved, 640 × 360; back at 1600 × 900, the
    frames as drawn again."""
    def resize(width: int, height: int) -> None:
        ctx.page.call("Emulation.setDeviceMetricsOverride",
                      {"width": width, "height": height, "deviceScaleFactor": 1, "mobile": False})
    frames = ("(() => { const i = document.querySelector('img#frame');"
              " return gf.stream.width === Math.ceil(i.clientWidth) && [i.naturalWidth, i.naturalHeight, gf.stream.width]; })()")
    resize(1000, 700)
    try:
        # naturalWidth is 0 while the stream at the new width is opening: wait for its first frame.
        narrow = ctx.page.wait_for("document.querySelector('img#frame').naturalWidth > 0 && "
                                   "document.querySelector('img#frame').naturalWidth < 1280 && " + frames,
                                   "the narrower page's frames")
        assert 427 <= narrow[2] <= 640 and narrow[:2] == [640, 360], f"frames {narrow}, want 640 x 360 for a view 427..640 wide"
    finally:
        resize(1600, 900)
    wide = ctx.page.wait_for("document.querySelector('img#frame').naturalWidth === 1280 && " + frames,
                             "the page's frames as drawn again")
    print(f"  view {narrow[2]} px: frames {narrow[0]} x {narrow[1]}; view {wide[2]} px: frames {wide[0]} x {wide[1]}")


def test_drag_presses_index_on_the_cylinder(ctx: Context) -> None:
    """(b) With the pointer only (drag, wheel for depth), `index` is brought 3 cm above the top of
    the cylinder and dragged 2 cm into it: /state.json shows its contact on the cylinder, and the
    frame its highlighted patch (light blue pixels in the insets' corner, beyond those before)."""
    set_control(ctx.page, "select#web-finger", "index")
    blue_before = ctx.page.evaluate(BLUE_IN_INSETS_JS)
    half_height = tomllib.loads(SCENE.read_text())["bodies"]["cylinder"]["half_height"]
    # The cylinder stands upright (axis y, up): its top is half its height above its centre.
    top = add(body(ctx.served.state(), "cylinder")["position"], [0.0, half_height, 0.0])
    place_finger(ctx, "index", add(top, [0.0, 0.03, 0.0]))
    ctx.page.drag(project(ctx.page, proxy(ctx.served, "index")), project(ctx.page, add(top, [0.0, -0.02, 0.0])),
                  steps=20)

    def touching() -> list[dict]:
        contacts = finger(ctx.served.state(), "index").get("contacts", [])
        return [c for c in contacts if c["body"] == "cylinder" and c["radius_m"] > 0 and c["sgos"] > 0]

    contact = poll(touching, "index's contact on the cylinder")[0]
    blue_after = poll(lambda: (n := ctx.page.evaluate(BLUE_IN_INSETS_JS)) > blue_before + 5000 and n,
                      f"the patch in the frame's inset (light blue pixels before: {blue_before})")
    shot = save_screenshot(ctx, "live-view.png")
    print(f"  contact {contact}; light blue pixels in the insets {blue_before} -> {blue_after}; screenshot {shot}")


def test_page_times_its_moves_to_the_frames(ctx: Context) -> None:
    """(d) The page reads the stream's parts itself and times each of its moves (the drags
    above, and one more posted through it now) to the decoded frame that shows it taken and the
    one that shows it reached: gf.latency holds both per move, each positive, a move reached no
    sooner than taken, and the top bar shows their medians."""
    target = add(proxy(ctx.served, "thumb"), [0.0, 0.01, 0.0])
    moves = ctx.page.evaluate("gf.latency.taken.length")
    answer = ctx.page.evaluate("gf.command('move thumb {} {} {} 0.03')".format(*target))
    assert " move " in answer, f"a move's answer without its number: {answer!r}"
    poll(lambda: ctx.page.evaluate("gf.latency.taken.length") > moves, "the page's timing of its move")
    latency = ctx.page.evaluate("gf.latency")
    assert len(latency["taken"]) == len(latency["arrived"]) > 0, latency
    for taken, arrived in zip(latency["taken"], latency["arrived"]):
        assert 0 < taken <= arrived, f"a move shown taken after {taken} ms and reached after {arrived} ms"
    shown = poll(lambda: (t := ctx.page.evaluate("document.querySelector('#latency').textContent")) and t,
                 "the delay in the top bar")
    assert shown.startswith("move → frame "), shown
    print(f"  {len(latency['taken'])} moves timed by the page; {shown}")


def test_n_sgo_control_sets_the_setting(ctx: Context) -> None:
    """(c) The page's n_sgo input of `index`, changed to 16, sets the finger's n_sgo."""
    set_control(ctx.page, "input[data-finger=index][data-field=n_sgo]", "16")
    poll(lambda: finger(ctx.served.state(), "index")["settings"]["n_sgo"] == 16, "index's settings.n_sgo == 16")


def test_commands_answer_ok_or_error(ctx: Context) -> None:
    """POST /command: a good line is answered `ok`, a bad one `error: ...`."""
    assert ctx.served.command("state").startswith("ok"), "state"
    answer = ctx.served.command("move nosuchfinger 0 0.1 0")
    assert answer.startswith("error:"), f"move of an unknown finger answered {answer!r}"


def test_token_is_required_off_loopback(binary: Path, out_dir: Path, browser: Browser) -> None:
    """(d) Served on 0.0.0.0 with --token, a request without the token gets 401, with it (query or
    Bearer header) 200; the page opened with ?token= shows the stream."""
    served = Served.start(serve_command(binary, out_dir / "token-run", "0.0.0.0:0", "--token", "secret"),
                          out_dir / "godfinger-token.log")
    try:
        assert served.token == "***", f"the serving line shows the token given: {served.token!r}"
        for path in ["/", "/state.json", "/stream.mjpg"]:
            for token, headers, want in [(None, {}, 401), ("wrong", {}, 401), ("secret", {}, 200),
                                         (None, {"Authorization": "Bearer secret"}, 200)]:
                status = served.status(path, token, headers)
                assert status == want, f"GET {path} token={token} headers={headers}: {status}, want {want}"
        assert request(served.url("/command"), data=b"state").status == 401, "POST /command without the token"
        page = browser.new_page()
        page.navigate(served.url("/", "secret"), until="Page.domContentEventFired")
        page.wait_for("document.querySelector('img#frame')?.naturalWidth > 0",
                      "the page opened with ?token= to show the stream")
    finally:
        served.stop()


# Running ------------------------------------------------------------------------------------

def run(name: str, test: Callable[[], None], ctx: Context | None = None) -> bool:
    """Runs one test and prints PASS or FAIL with the reason (and, with a page, a screenshot
    OUT_DIR/failed-NAME.png); whether it passed."""
    started = time.monotonic()
    try:
        test()
    except Exception as error:
        print(f"FAIL {name} ({time.monotonic() - started:.1f} s): {error}")
        traceback.print_exc(limit=4)
        if ctx:
            try:
                ctx.page.screenshot(ctx.out_dir / f"failed-{name}.png")
            except Exception as shot_error:
                print(f"  (no screenshot: {shot_error})")
        return False
    print(f"PASS {name} ({time.monotonic() - started:.1f} s)")
    return True


def main(binary: Path, out_dir: Path) -> int:
    """Runs every test; 0 when all pass. godfinger and Chromium are always stopped."""
    shutil.rmtree(out_dir, ignore_errors=True)
    out_dir.mkdir(parents=True)
    served = browser = None
    try:
        served = Served.start(serve_command(binary, out_dir / "run", "127.0.0.1:0"), out_dir / "godfinger.log")
        browser = Browser.launch(out_dir / "chromium.log")
        ctx = Context(served, browser.new_page(width=1600, height=900), out_dir)
        tests = [test_page_shows_the_stream, test_a_narrower_page_reads_smaller_frames,
                 test_drag_presses_index_on_the_cylinder,
                 test_page_times_its_moves_to_the_frames, test_n_sgo_control_sets_the_setting,
                 test_commands_answer_ok_or_error]
        passed = [run(t.__name__, lambda t=t: t(ctx), ctx) for t in tests]
        served.stop()
        passed.append(run("test_token_is_required_off_loopback",
                          lambda: test_token_is_required_off_loopback(binary, out_dir, browser)))
    finally:
        if browser:
            browser.close()
        if served:
            served.stop()
    if not all(passed):
        print(f"the first godfinger's output ({served.log_path}):\n{served.log_tail()}")
    return 0 if all(passed) else 1


if __name__ == "__main__":
    script(main, __doc__)
