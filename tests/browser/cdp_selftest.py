#!/usr/bin/env python3
"""Checks the browser harness (cdp.py, served.py) on its own, without godfinger: a page served by
Python's http.server on 127.0.0.1 is loaded in headless Chromium, evaluated, dragged over and
wheeled on, captured; an MJPEG stream made of the browser's own JPEG captures is shown in an
<img> and read back by served.mjpeg_parts; Chromium closes with no process of it left.

Usage: cdp_selftest.py OUT_DIR      (writes OUT_DIR/selftest.png and OUT_DIR/chromium.log)
"""
from __future__ import annotations

import hashlib
import http.server
import sys
import threading
import time
from pathlib import Path

from cdp import Browser, Page
from served import is_jpeg, mjpeg_parts, request

# A canvas that records its pointer and wheel events in window.events and draws the drag.
CANVAS_PAGE = b"""<!doctype html><title>cdp self-test</title>
<body style="margin:0;background:#eee">
<canvas id="pad" width="400" height="300" style="position:absolute;left:50px;top:50px;background:#fff"></canvas>
<script>
window.events = [];
const pad = document.getElementById('pad'), ctx = pad.getContext('2d');
ctx.font = '20px sans-serif'; ctx.fillText('drag here', 150, 150);
ctx.lineWidth = 6; ctx.strokeStyle = '#c40';
for (const type of ['pointerdown', 'pointermove', 'pointerup'])
  pad.addEventListener(type, e => {
    window.events.push({type, x: e.clientX, y: e.clientY, buttons: e.buttons});
    if (type === 'pointerdown') { ctx.beginPath(); ctx.moveTo(e.offsetX, e.offsetY); }
    else if (e.buttons & 1) { ctx.lineTo(e.offsetX, e.offsetY); ctx.stroke(); }
  });
pad.addEventListener('wheel', e => { e.preventDefault(); window.events.push({type: 'wheel', deltaY: e.deltaY}); });
</script>"""
STREAM_PAGE = b"""<!doctype html><title>stream</title><body style="margin:0">
<img id="frame" src="/stream.mjpg"></body>"""
BOUNDARY = "gfframe"


class Handler(http.server.BaseHTTPRequestHandler):
    """/ (the canvas), /stream.html and /stream.mjpg (the server's `frames`, cycled at 10 Hz)."""

    def do_GET(self) -> None:
        """One page, or the endless MJPEG stream until the client goes away."""
        if self.path == "/stream.mjpg":
            self._stream()
            return
        body = {"/": CANVAS_PAGE, "/stream.html": STREAM_PAGE}.get(self.path)
        self.send_response(200 if body else 404)
        self.send_header("Content-Type", "text/html")
        self.send_header("Content-Length", str(len(body or b"")))
        self.end_headers()
        self.wfile.write(body or b"")

    def _stream(self) -> None:
        """multipart/x-mixed-replace of JPEG parts, each with Content-Type and Content-Length."""
        self.send_response(200)
        self.send_header("Content-Type", f"multipart/x-mixed-replace; boundary={BOUNDARY}")
        self.end_headers()
        frames: list[bytes] = self.server.frames  # type: ignore[attr-defined]
        try:
            for count in range(100000):
                jpeg = frames[count % len(frames)]
                self.wfile.write(f"--{BOUNDARY}\r\nContent-Type: image/jpeg\r\nContent-Length: {len(jpeg)}\r\n\r\n"
                                 .encode() + jpeg + b"\r\n")
                self.wfile.flush()
                time.sleep(0.1)  # the fake camera's frame period, not a synchronisation
        except (BrokenPipeError, ConnectionResetError):
            pass

    def log_message(self, *args: object) -> None:
        """Quiet."""


def check_drag_and_wheel(page: Page) -> None:
    """A drag over the canvas arrives as pointerdown, moves with the button held, pointerup; a
    wheel event with its deltaY."""
    page.drag((100, 100), (400, 300), steps=12)
    page.wheel((250, 200), -100)
    events = page.evaluate("window.events")
    kinds = [e["type"] for e in events]
    down = events[kinds.index("pointerdown")] if "pointerdown" in kinds else None
    assert down and (down["x"], down["y"], down["buttons"]) == (100, 100, 1), events[:3]
    held = [e for e in events if e["type"] == "pointermove" and e["buttons"] == 1]
    assert len(held) >= 10, f"{len(held)} pointermove events with the button held, want >= 10"
    up = [e for e in events if e["type"] == "pointerup"]
    assert len(up) == 1 and (up[0]["x"], up[0]["y"]) == (400, 300), up
    assert kinds[-1] == "wheel" and events[-1]["deltaY"] == -100, events[-1]
    print(f"  drag: {len(events)} events, {len(held)} moves with the button held; wheel deltaY -100")


def check_stream(page: Page, base_url: str) -> None:
    """The <img> shows the MJPEG stream; mjpeg_parts reads three distinct JPEG parts of it."""
    page.navigate(base_url + "/stream.html", until="Page.domContentEventFired")
    width = page.wait_for("document.getElementById('frame').naturalWidth", "the stream's first frame in the img")
    assert width == 1600, f"img naturalWidth {width}, want 1600"
    seen: set[str] = set()
    for headers, body in mjpeg_parts(base_url + "/stream.mjpg"):
        assert headers.get("content-type") == "image/jpeg" and is_jpeg(body), headers
        seen.add(hashlib.sha256(body).hexdigest())
        if len(seen) == 3:
            break
    print(f"  stream: img {width} px wide, 3 distinct JPEG parts read")


def main(out_dir: Path) -> int:
    """Runs the self-test; 0 when every check passes."""
    out_dir.mkdir(parents=True, exist_ok=True)
    server = http.server.ThreadingHTTPServer(("127.0.0.1", 0), Handler)
    server.daemon_threads = True
    threading.Thread(target=server.serve_forever, daemon=True).start()
    base_url = f"http://127.0.0.1:{server.server_address[1]}"
    browser = Browser.launch(out_dir / "chromium.log")
    try:
        page = browser.new_page(width=1600, height=900)
        page.navigate(base_url + "/")
        assert page.evaluate("document.title") == "cdp self-test"
        assert page.evaluate("new Promise(r => setTimeout(() => r(6 * 7), 10))") == 42
        check_drag_and_wheel(page)
        shot = page.screenshot(out_dir / "selftest.png")
        server.frames = []  # type: ignore[attr-defined]
        for label in ("one", "two", "three"):
            page.evaluate(f"document.getElementById('pad').getContext('2d').fillText('{label}', 60, 60 + 30 * "
                          f"{len(server.frames)})")  # type: ignore[attr-defined]
            jpeg = out_dir / f"frame-{label}.jpg"
            server.frames.append(page.screenshot(jpeg, "jpeg").read_bytes())  # type: ignore[attr-defined]
            jpeg.unlink()
        check_stream(page, base_url)
        assert request(base_url + "/nothing").status == 404
    finally:
        browser.close()
        server.shutdown()
    # The browser led its own process group: nothing of it may remain.
    assert not browser.process.group_alive(), f"chromium processes of group {browser.process.pid} outlived close()"
    print(f"cdp self-test passed; screenshot {shot}")
    return 0


if __name__ == "__main__":
    sys.exit(main(Path(sys.argv[1] if len(sys.argv) > 1 else "browser-selftest")))
