"""A minimal Chrome DevTools Protocol client over a pipe, for the browser tests (tests/browser/).

Chromium runs headless with --remote-debugging-pipe: it reads NUL-terminated JSON messages on
fd 3 and writes its replies and events on fd 4. Python's standard library only: no npm, no
puppeteer, no websocket. One thread: replies are read with select() while waiting for them.
Every wait has a timeout, a guard against hangs rather than a measurement, and fails with a
message naming what it waited for.

    with Browser.launch() as browser:
        page = browser.new_page(width=1600, height=1200)
        page.navigate("http://127.0.0.1:8000/")
        page.evaluate("document.title")
        page.drag((100, 100), (300, 200))
        page.screenshot(Path("shot.png"))
"""
from __future__ import annotations

import base64
import fcntl
import json
import os
import select
import shutil
import signal
import tempfile
import time
from pathlib import Path
from typing import Any, Callable, TypeVar

# The browser: Debian's chromium package (GF_PACKAGES), or GF_CHROMIUM.
CHROMIUM = os.environ.get("GF_CHROMIUM", "/usr/bin/chromium")
# Default guard of every wait, s: generous, since the machine may be busy with other builds.
TIMEOUT_S = 60.0
# Headless, no sandbox (we run as root), and nothing that reaches for the network on its own.
LAUNCH_FLAGS = [
    "--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
    "--disable-background-networking", "--disable-component-update", "--disable-sync",
    "--disable-default-apps", "--mute-audio", "--hide-scrollbars", "--no-proxy-server",
]
# The pipe's fds in the browser's process, fixed by --remote-debugging-pipe.
BROWSER_READ_FD, BROWSER_WRITE_FD = 3, 4

T = TypeVar("T")


class CdpError(RuntimeError):
    """A DevTools call that failed, was refused or timed out; the message says which."""


def poll(check: Callable[[], T], what: str, timeout_s: float = TIMEOUT_S, interval_s: float = 0.05) -> T:
    """Calls `check` until it returns a truthy value and returns that value.

    Raises TimeoutError naming `what` (and the last value seen) after `timeout_s`. The sleep
    between calls only paces the polling; the condition is what synchronises.
    """
    deadline = time.monotonic() + timeout_s
    while True:
        value = check()
        if value:
            return value
        if time.monotonic() > deadline:
            raise TimeoutError(f"timed out after {timeout_s:.0f} s waiting for {what} (last: {value!r})")
        time.sleep(interval_s)


def _pipe_above(low_fd: int) -> tuple[int, int]:
    """A pipe whose two fds are at least `low_fd`, close-on-exec."""
    read_fd, write_fd = os.pipe()
    high = (fcntl.fcntl(read_fd, fcntl.F_DUPFD_CLOEXEC, low_fd), fcntl.fcntl(write_fd, fcntl.F_DUPFD_CLOEXEC, low_fd))
    os.close(read_fd)
    os.close(write_fd)
    return high


class Child:
    """A process started by posix_spawn in a session of its own (so its helpers can be killed as
    a group). posix_spawn, unlike subprocess with preexec_fn, can place the pipe at fds 3 and 4
    safely while other threads run (an HTTP server of a test, say)."""

    def __init__(self, argv: list[str], log_path: Path, fds: dict[int, int]) -> None:
        """Starts `argv` with stdin from /dev/null, stdout and stderr into `log_path`, and each
        fd of `fds` (child fd: our fd) in place."""
        log_fd = os.open(log_path, os.O_WRONLY | os.O_CREAT | os.O_TRUNC | os.O_CLOEXEC, 0o644)
        # Standard streams first: the pipe's dup2 onto 3 and 4 may then replace log_fd.
        actions = [(os.POSIX_SPAWN_OPEN, 0, "/dev/null", os.O_RDONLY, 0),
                   (os.POSIX_SPAWN_DUP2, log_fd, 1), (os.POSIX_SPAWN_DUP2, log_fd, 2)]
        actions += [(os.POSIX_SPAWN_DUP2, ours, theirs) for theirs, ours in fds.items()]
        try:
            self.pid = os.posix_spawnp(argv[0], argv, os.environ, file_actions=actions,
                                        setsid=True, setsigdef=(signal.SIGPIPE,))
        finally:
            os.close(log_fd)
        self.returncode: int | None = None

    def poll(self) -> int | None:
        """The exit code if the process has ended (reaped then), else None."""
        if self.returncode is None:
            pid, status = os.waitpid(self.pid, os.WNOHANG)
            if pid:
                self.returncode = os.waitstatus_to_exitcode(status)
        return self.returncode

    def wait(self, timeout_s: float) -> bool:
        """Whether the process ended within `timeout_s`."""
        try:
            poll(lambda: self.poll() is not None, f"process {self.pid} to exit", timeout_s, interval_s=0.02)
            return True
        except TimeoutError:
            return False

    def kill_group(self, timeout_s: float = 10.0) -> None:
        """SIGKILL to the process's whole group (it leads its own session), reaps it, and waits
        until no process of the group is left (helpers that outlived it are reaped by init)."""
        try:
            os.killpg(self.pid, signal.SIGKILL)
        except ProcessLookupError:
            pass
        if self.returncode is None:
            self.returncode = os.waitstatus_to_exitcode(os.waitpid(self.pid, 0)[1])
        poll(lambda: not self.group_alive(), f"the processes of group {self.pid} to go", timeout_s)

    def group_alive(self) -> bool:
        """Whether any process (a zombie included) of the group is still there."""
        try:
            os.killpg(self.pid, 0)
            return True
        except ProcessLookupError:
            return False


class Browser:
    """One headless Chromium with its own temporary profile, driven over the DevTools pipe.

    Not thread-safe: one thread sends and reads. Use as a context manager, or call close().
    """

    def __init__(self, process: Child, to_browser: int, from_browser: int, profile: Path,
                 log_path: Path) -> None:
        self.process = process
        self.log_path = log_path
        self._to_browser = to_browser
        self._from_browser = from_browser
        self._profile = profile
        self._buffer = b""
        self._next_id = 1
        self._replies: dict[int, dict] = {}
        self.events: list[dict] = []  # every event received, in order: {method, params, sessionId?}

    @classmethod
    def launch(cls, log_path: Path | None = None, chromium: str = CHROMIUM) -> Browser:
        """Starts Chromium on a new temporary profile; its stdout and stderr go to `log_path`.

        Without `log_path` the log is kept in the profile folder and removed with it.
        """
        profile = Path(tempfile.mkdtemp(prefix="gf-chromium-"))
        log_path = log_path or profile / "chromium.log"
        # The pipe ends go to fds 3 and 4 of the child; ours stay above them, close-on-exec.
        to_read, to_write = _pipe_above(10)
        from_read, from_write = _pipe_above(10)
        argv = [chromium, *LAUNCH_FLAGS, "--remote-debugging-pipe", f"--user-data-dir={profile}", "about:blank"]
        process = Child(argv, log_path, {BROWSER_READ_FD: to_read, BROWSER_WRITE_FD: from_write})
        os.close(to_read)
        os.close(from_write)
        browser = cls(process, to_write, from_read, profile, log_path)
        try:
            browser.call("Browser.getVersion", timeout_s=TIMEOUT_S)
        except Exception:
            browser.close()
            raise
        return browser

    def __enter__(self) -> Browser:
        return self

    def __exit__(self, *exc_info: object) -> None:
        self.close()

    def log_tail(self, lines: int = 20) -> str:
        """The last lines of Chromium's own output, for failure messages."""
        try:
            return "\n".join(self.log_path.read_text(errors="replace").splitlines()[-lines:])
        except OSError:
            return "(no chromium log)"

    def send(self, method: str, params: dict | None = None, session_id: str | None = None) -> int:
        """Sends one command without waiting; returns its id."""
        message: dict[str, Any] = {"id": self._next_id, "method": method, "params": params or {}}
        if session_id:
            message["sessionId"] = session_id
        self._next_id += 1
        data = json.dumps(message).encode() + b"\0"
        try:
            while data:
                data = data[os.write(self._to_browser, data):]
        except OSError as error:
            raise CdpError(f"{method}: cannot write to chromium ({error}); its log:\n{self.log_tail()}") from error
        return message["id"]

    def call(self, method: str, params: dict | None = None, session_id: str | None = None,
             timeout_s: float = TIMEOUT_S) -> dict:
        """Sends one command and returns its result; CdpError on an error reply or a timeout."""
        message_id = self.send(method, params, session_id)
        deadline = time.monotonic() + timeout_s
        while message_id not in self._replies:
            self._read_some(deadline, f"the reply to {method}")
        reply = self._replies.pop(message_id)
        if "error" in reply:
            raise CdpError(f"{method} {json.dumps(params or {})[:200]}: {reply['error'].get('message')}"
                           f" {reply['error'].get('data', '')}".rstrip())
        return reply.get("result", {})

    def wait_event(self, method: str, session_id: str | None = None, since: int = 0,
                   timeout_s: float = TIMEOUT_S) -> dict:
        """The first event `method` (of `session_id`, if given) at index `since` or later of events."""
        deadline = time.monotonic() + timeout_s
        index = since
        while True:
            for index in range(index, len(self.events)):
                event = self.events[index]
                if event["method"] == method and (session_id is None or event.get("sessionId") == session_id):
                    return event
            index = len(self.events)
            self._read_some(deadline, f"the event {method}")

    def _read_some(self, deadline: float, what: str) -> None:
        """Reads what Chromium has written and files it as replies or events; waits until `deadline`."""
        remaining = deadline - time.monotonic()
        if remaining <= 0:
            raise CdpError(f"timed out waiting for {what}; chromium's log:\n{self.log_tail()}")
        ready, _, _ = select.select([self._from_browser], [], [], remaining)
        if not ready:
            return
        chunk = os.read(self._from_browser, 1 << 20)
        if not chunk:
            raise CdpError(f"chromium closed the pipe (exit code {self.process.poll()}) while waiting for {what};"
                           f" its log:\n{self.log_tail()}")
        self._buffer += chunk
        *messages, self._buffer = self._buffer.split(b"\0")
        for raw in messages:
            message = json.loads(raw)
            if "id" in message:
                self._replies[message["id"]] = message
            else:
                self.events.append(message)

    def new_page(self, width: int = 1600, height: int = 1200) -> Page:
        """A new tab of `width` × `height` CSS px (scale 1), attached in flat mode, Page and Runtime enabled."""
        target_id = self.call("Target.createTarget", {"url": "about:blank"})["targetId"]
        session_id = self.call("Target.attachToTarget", {"targetId": target_id, "flatten": True})["sessionId"]
        page = Page(self, session_id)
        page.call("Page.enable")
        page.call("Runtime.enable")
        page.call("Emulation.setDeviceMetricsOverride",
                  {"width": width, "height": height, "deviceScaleFactor": 1, "mobile": False})
        return page

    def close(self, timeout_s: float = 10.0) -> None:
        """Browser.close, then SIGKILL to the whole process group if it is still there after
        `timeout_s`; the temporary profile is removed. Safe to call twice."""
        if self.process.poll() is None and self._to_browser >= 0:
            try:
                self.send("Browser.close")
            except CdpError:
                pass
            self.process.wait(timeout_s)
        # Helpers (renderer, GPU, zygote) share the browser's process group: none is left behind.
        self.process.kill_group()
        for fd in (self._to_browser, self._from_browser):
            try:
                os.close(fd)
            except OSError:
                pass
        self._to_browser = self._from_browser = -1
        shutil.rmtree(self._profile, ignore_errors=True)


class Page:
    """One tab: navigation, JavaScript, pointer input and screenshots, in viewport CSS px."""

    def __init__(self, browser: Browser, session_id: str) -> None:
        self.browser = browser
        self.session_id = session_id

    def call(self, method: str, params: dict | None = None, timeout_s: float = TIMEOUT_S) -> dict:
        """One command to this tab's session."""
        return self.browser.call(method, params, self.session_id, timeout_s)

    def navigate(self, url: str, until: str = "Page.loadEventFired", timeout_s: float = TIMEOUT_S) -> None:
        """Loads `url` and waits for the event `until` (Page.loadEventFired or Page.domContentEventFired)."""
        since = len(self.browser.events)
        result = self.call("Page.navigate", {"url": url}, timeout_s)
        if result.get("errorText"):
            raise CdpError(f"navigating to {url}: {result['errorText']}")
        self.browser.wait_event(until, self.session_id, since, timeout_s)

    def evaluate(self, expression: str, timeout_s: float = TIMEOUT_S) -> Any:
        """The value of a JavaScript expression (a promise is awaited), as JSON; CdpError if it throws."""
        result = self.call("Runtime.evaluate", {"expression": expression, "returnByValue": True,
                                                "awaitPromise": True}, timeout_s)
        if "exceptionDetails" in result:
            details = result["exceptionDetails"]
            text = details.get("exception", {}).get("description") or details.get("text")
            raise CdpError(f"JavaScript threw evaluating {expression[:200]!r}: {text}")
        return result["result"].get("value")

    def wait_for(self, expression: str, what: str, timeout_s: float = TIMEOUT_S) -> Any:
        """Polls a JavaScript expression until it is truthy; returns its value."""
        return poll(lambda: self.evaluate(expression), what, timeout_s)

    def _mouse(self, kind: str, x: float, y: float, buttons: int, **extra: Any) -> None:
        """One Input.dispatchMouseEvent of the left button at (x, y)."""
        button = "none" if kind == "mouseMoved" and not buttons else "left"
        self.call("Input.dispatchMouseEvent",
                  {"type": kind, "x": x, "y": y, "button": button, "buttons": buttons, **extra})

    def drag(self, start: tuple[float, float], end: tuple[float, float], steps: int = 10) -> None:
        """Moves to `start`, presses the left button, moves to `end` in `steps` straight steps, releases."""
        self._mouse("mouseMoved", *start, buttons=0)
        self._mouse("mousePressed", *start, buttons=1, clickCount=1)
        for step in range(1, steps + 1):
            f = step / steps
            self._mouse("mouseMoved", start[0] + f * (end[0] - start[0]), start[1] + f * (end[1] - start[1]),
                        buttons=1)
        self._mouse("mouseReleased", *end, buttons=0, clickCount=1)

    def click(self, at: tuple[float, float]) -> None:
        """Moves to `at` and clicks the left button there."""
        self._mouse("mouseMoved", *at, buttons=0)
        self._mouse("mousePressed", *at, buttons=1, clickCount=1)
        self._mouse("mouseReleased", *at, buttons=0, clickCount=1)

    def centre(self, selector: str) -> tuple[float, float]:
        """The centre of the element `selector` in viewport CSS px (scrolled into view first)."""
        box = self.evaluate(f"""(() => {{ const e = document.querySelector({json.dumps(selector)});
            if (!e) return null; e.scrollIntoView({{block: 'center'}}); const r = e.getBoundingClientRect();
            return [r.left + r.width / 2, r.top + r.height / 2]; }})()""")
        if not box:
            raise CdpError(f"no element {selector} on the page")
        return box[0], box[1]

    def wheel(self, at: tuple[float, float], delta_y: float, delta_x: float = 0.0) -> None:
        """One wheel event at `at`; positive `delta_y` scrolls down (turns the wheel towards the user)."""
        self.call("Input.dispatchMouseEvent", {"type": "mouseWheel", "x": at[0], "y": at[1],
                                               "deltaX": delta_x, "deltaY": delta_y})

    def screenshot(self, path: Path, image_format: str = "png") -> Path:
        """Captures the viewport into `path` (png or jpeg); returns `path`."""
        data = self.call("Page.captureScreenshot", {"format": image_format})["data"]
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_bytes(base64.b64decode(data))
        return path
