"""The godfinger web server (`--serve`) as the browser tests see it: start it, find the address it
prints, ask it over HTTP on the loopback, read its MJPEG stream, stop it.

Standard library only. Requests never go through a proxy, whatever the environment says.
"""
from __future__ import annotations

import json
import os
import re
import signal
import subprocess
import sys
import traceback
import urllib.error
import urllib.request
from dataclasses import dataclass
from pathlib import Path
from typing import Callable, Iterator

from cdp import TIMEOUT_S, poll

# The line the server prints on stderr once it listens: the bound port, and the token if any.
SERVING = re.compile(r"serving http://(?P<host>[^\s/]+):(?P<port>\d+)/(?:\?token=(?P<token>\S+))?")
# Loopback only, and no proxy even if http_proxy is set.
_OPENER = urllib.request.build_opener(urllib.request.ProxyHandler({}))


@dataclass
class Reply:
    """One HTTP answer: status code, headers (names lower case) and body."""
    status: int
    headers: dict[str, str]
    body: bytes

    def text(self) -> str:
        """The body as UTF-8 text."""
        return self.body.decode("utf-8", errors="replace")


def request(url: str, data: bytes | None = None, headers: dict[str, str] | None = None,
            timeout_s: float = TIMEOUT_S) -> Reply:
    """GET (or POST with `data`) `url`; an HTTP error status is returned, not raised."""
    req = urllib.request.Request(url, data=data, headers=headers or {})
    try:
        with _OPENER.open(req, timeout=timeout_s) as response:
            return Reply(response.status, {k.lower(): v for k, v in response.headers.items()}, response.read())
    except urllib.error.HTTPError as error:
        return Reply(error.code, {k.lower(): v for k, v in error.headers.items()}, error.read())


class Served:
    """A godfinger process serving its page; killed (with its process group) by stop()."""

    def __init__(self, process: subprocess.Popen, log_path: Path) -> None:
        self.process = process
        self.log_path = log_path
        self.port = 0
        self.token: str | None = None

    @classmethod
    def start(cls, command: list[str], log_path: Path, timeout_s: float = TIMEOUT_S) -> Served:
        """Runs `command` (a godfinger command line with --serve) with stderr into `log_path`, and
        waits for its `serving http://HOST:PORT/` line."""
        log_path.parent.mkdir(parents=True, exist_ok=True)
        with open(log_path, "wb") as log:
            process = subprocess.Popen(command, stdin=subprocess.DEVNULL, stdout=log, stderr=subprocess.STDOUT,
                                       start_new_session=True)
        served = cls(process, log_path)
        try:
            match = poll(served._serving_line, f"'serving http://HOST:PORT/' from {' '.join(command)}", timeout_s)
        except Exception as error:
            served.stop()
            raise AssertionError(f"{error}\ngodfinger's output:\n{served.log_tail()}") from None
        served.port = int(match["port"])
        served.token = match["token"]
        return served

    def _serving_line(self) -> re.Match | None:
        """The serving line if printed yet; AssertionError if the process has ended without it."""
        match = SERVING.search(self.log_path.read_text(errors="replace"))
        if not match and self.process.poll() is not None:
            raise AssertionError(f"godfinger exited with {self.process.returncode} before serving")
        return match

    def log_tail(self, lines: int = 30) -> str:
        """The last lines of godfinger's stdout and stderr."""
        return "\n".join(self.log_path.read_text(errors="replace").splitlines()[-lines:])

    def url(self, path: str = "/", token: str | None = None) -> str:
        """http://127.0.0.1:PORT/path, with ?token= if `token` is given."""
        query = f"?token={token}" if token else ""
        return f"http://127.0.0.1:{self.port}{path}{query}"

    def get(self, path: str, token: str | None = None, headers: dict[str, str] | None = None) -> Reply:
        """GET one path of the server."""
        return request(self.url(path, token), headers=headers)

    def status(self, path: str, token: str | None = None, headers: dict[str, str] | None = None) -> int:
        """The status of a GET of `path`; the body is not read (the stream never ends)."""
        req = urllib.request.Request(self.url(path, token), headers=headers or {})
        try:
            with _OPENER.open(req, timeout=TIMEOUT_S) as response:
                return response.status
        except urllib.error.HTTPError as error:
            error.close()
            return error.code

    def state(self) -> dict:
        """/state.json, parsed; AssertionError unless 200."""
        reply = self.get("/state.json", self.token)
        assert reply.status == 200, f"GET /state.json: {reply.status} {reply.text()[:200]}"
        return json.loads(reply.body)

    def command(self, line: str) -> str:
        """POSTs one `live` command line to /command; returns the answer's text (`ok ...` or `error: ...`).

        The server answers 200 with `ok ...` and 400 with `error: ...`; anything else fails."""
        reply = request(self.url("/command", self.token), data=line.encode(), headers={"Content-Type": "text/plain"})
        text = reply.text().strip()
        want = 200 if text.startswith("ok") else 400
        assert reply.status == want and (text.startswith("ok") or text.startswith("error: ")), \
            f"POST /command {line!r}: {reply.status} {text[:200]}"
        return text

    def stop(self, timeout_s: float = 10.0) -> None:
        """SIGTERM, then SIGKILL to the whole process group after `timeout_s`. Safe to call twice."""
        if self.process.poll() is None:
            os.killpg(self.process.pid, signal.SIGTERM)
            try:
                self.process.wait(timeout=timeout_s)
            except subprocess.TimeoutExpired:
                pass
        try:
            os.killpg(self.process.pid, signal.SIGKILL)
        except ProcessLookupError:
            pass
        self.process.wait()


def mjpeg_parts(url: str, timeout_s: float = TIMEOUT_S) -> Iterator[tuple[dict[str, str], bytes]]:
    """The parts (headers with lower-case names, body) of a multipart/x-mixed-replace stream, as
    they arrive. Checks the framing: a boundary in the Content-Type, each part opened by the
    line `--BOUNDARY` and carrying a Content-Length. The caller stops reading when it has enough;
    TimeoutError if no part comes for `timeout_s`."""
    response = _OPENER.open(urllib.request.Request(url), timeout=timeout_s)
    with response:
        content_type = response.headers.get("Content-Type", "")
        boundary = re.search(r'boundary="?([^";]+)"?', content_type)
        assert content_type.startswith("multipart/x-mixed-replace") and boundary, \
            f"GET {url}: Content-Type {content_type!r}, want multipart/x-mixed-replace; boundary=..."
        delimiter = b"--" + boundary.group(1).encode()
        while True:
            yield _read_part(response, delimiter, url)


def _read_part(response, delimiter: bytes, url: str) -> tuple[dict[str, str], bytes]:
    """One part: skips to the delimiter line, reads the headers, then Content-Length bytes."""
    skipped = 0
    while (line := response.readline()).strip() != delimiter:
        assert line, f"{url}: the stream ended"
        skipped += len(line)
        assert skipped < 1 << 16, f"{url}: no {delimiter!r} line in 64 KiB"
    headers: dict[str, str] = {}
    while (line := response.readline().strip()):
        name, _, value = line.decode("latin-1").partition(":")
        headers[name.strip().lower()] = value.strip()
    assert "content-length" in headers, f"{url}: a part without Content-Length: {headers}"
    body = response.read(int(headers["content-length"]))
    return headers, body


def is_jpeg(data: bytes) -> bool:
    """A JPEG's start (SOI) and end (EOI) markers."""
    return data[:2] == b"\xff\xd8" and data.rstrip(b"\r\n")[-2:] == b"\xff\xd9"


def verdict(check: Callable[[], str], log_tail: Callable[[], str]) -> int:
    """Runs a test's `check`: PASS and the line it returns, 0; or, on any exception, its trace and
    godfinger's last output (`log_tail`), FAIL, 1."""
    try:
        print(f"PASS  {check()}")
        return 0
    except Exception:  # noqa: BLE001 - report any failure with its trace and godfinger's output
        traceback.print_exc()
        print(f"FAIL  godfinger's output:\n{log_tail()}")
        return 1


def script(main: Callable[[Path, Path], int], usage: str) -> None:
    """A test script's entry: `main(GODFINGER, OUT_DIR)` from the command line, or `usage`."""
    if len(sys.argv) != 3:
        sys.exit(usage)
    sys.exit(main(Path(sys.argv[1]), Path(sys.argv[2])))
