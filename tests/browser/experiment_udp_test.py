#!/usr/bin/env python3
"""A UDP participant (device = "udp", app/experiment/web_participant.hpp): a device program on
loopback drives both trials of the browser test's pilot while the test plays the participant at
the page's HTTP interface (no browser needed: Start and the questionnaire are the page's own
commands, `ready` and `answers ...`).

The device program sends a GFD1 packet about every millisecond on channel 0: the finger held at
its start until the trial's first reply after the test clicks Start, then pushed 6 cm along x in
2 s, then pressed into the table (about 14 N) until the trial ends. It keeps every reply.
Checked:

- the experiment exits 0 with both trials and both questionnaires in its tables, and each trial's
  trace shows the device's push (at least 3 cm along x);
- the device is never left pushing: each trial's replies end with its force faded to zero from
  the press (over 1 N), the
  fade flagged `ending` (bit 4) and never faster than the ramp (max_force / force_ramp per
  second: 0.4 N a 1 ms step at the defaults), and each trial's first reply starts from zero.

Usage: experiment_udp_test.py GODFINGER OUT_DIR
"""
from __future__ import annotations

import csv
import json
import math
import shutil
import socket
import struct
import threading
import time
from pathlib import Path

from cdp import poll
from experiment_test import read_tsv
from served import Served, script, verdict

ROOT = Path(__file__).resolve().parents[2]
PACKET = struct.Struct("<IIIId3d")    # GFD1: magic, seq, channel, buttons, time, x, y, z
REPLY = struct.Struct("<IIIId3ddIf")  # GFR1: magic, seq, channel, flags, time, fx, fy, fz, radius, n_sgo, gain
PACKET_MAGIC, REPLY_MAGIC = 0x31444647, 0x31524647
ENDING = 1 << 4
START = (-0.04, 0.01, 0.015)  # turn-to-target's finger starts here
STEP_LIMIT_N = 40.0 * 0.001 / 0.1 + 1e-6  # max_force x dt / force_ramp at the defaults
ANSWERS = "answers mental_demand=30 physical_demand=40 temporal_demand=20 performance=15 effort=35 frustration=10 realism=5"


class DeviceProgram:
    """Sends the finger's position about every millisecond; keeps every reply (sim time, flags, |F|)."""

    def __init__(self, port: int) -> None:
        self.sock = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
        self.sock.setblocking(False)
        self.target = ("127.0.0.1", port)
        self.replies: list[tuple[float, int, float]] = []
        self.armed = False  # Start clicked: the push begins with the trial's first reply
        self.push_started: float | None = None  # wall time of that reply
        self.running = True
        self.thread = threading.Thread(target=self.loop, daemon=True)

    def position(self) -> tuple[float, float, float]:
        """At the start until the trial answers (a slow machine starts it late); then 6 cm along x
        in 2 s (the push), then 2 cm down in 0.5 s and held there, pressing the table (about 14 N)
        until the trial ends."""
        if self.push_started is None:
            return START
        s = time.monotonic() - self.push_started
        u, v = min(1.0, s / 2.0), min(1.0, max(0.0, s - 2.0) / 0.5)
        return (START[0] + 0.06 * u, START[1] - 0.02 * v, START[2])

    def loop(self) -> None:
        seq = 0
        while self.running:
            seq += 1
            self.sock.sendto(PACKET.pack(PACKET_MAGIC, seq, 0, 0, time.monotonic(), *self.position()), self.target)
            while True:
                try:
                    data = self.sock.recv(256)
                except BlockingIOError:
                    break
                if len(data) == REPLY.size:
                    magic, _, _, flags, t, fx, fy, fz, _, _, _ = REPLY.unpack(data)
                    if magic == REPLY_MAGIC:
                        self.replies.append((t, flags, math.sqrt(fx * fx + fy * fy + fz * fz)))
                        if self.armed and self.push_started is None:
                            self.push_started = time.monotonic()
            time.sleep(0.001)  # a device program's own pace, not a wait of the test

    def stop(self) -> None:
        self.running = False
        self.thread.join(5)
        self.sock.close()


def free_udp_port() -> int:
    with socket.socket(socket.AF_INET, socket.SOCK_DGRAM) as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def phase(served: Served) -> str:
    """The id of the page's phase now ("" between two phases' servers)."""
    try:
        return json.loads(served.get("/scene.json").text())["participant"]["id"]
    except Exception:  # noqa: BLE001 - no server between two phases
        return ""


def trials_of(replies: list[tuple[float, int, float]]) -> list[list[tuple[float, int, float]]]:
    """The replies split into runs: a run's simulated time starts again from zero."""
    runs: list[list[tuple[float, int, float]]] = []
    for r in replies:
        if not runs or r[0] < runs[-1][-1][0]:
            runs.append([])
        runs[-1].append(r)
    return runs


def main(binary: Path, out_dir: Path) -> int:
    out_dir.mkdir(parents=True, exist_ok=True)
    data = out_dir / "experiment-udp"
    shutil.rmtree(data, ignore_errors=True)
    port = free_udp_port()
    pilot = (ROOT / "tests" / "browser" / "experiment" / "pilot.toml").read_text()
    experiment = out_dir / "udp-pilot.toml"
    experiment.write_text(pilot.replace('name = "browser-pilot"', 'name = "udp-pilot"')
                          .replace('device = "web"', f'device = "udp"\nudp = "127.0.0.1:{port}"'))
    served = Served.start([str(binary), "experiment", str(experiment), "--participant", "1", "--serve", "127.0.0.1:0",
                           "--out", str(data)], out_dir / "godfinger-experiment-udp.log")
    device = DeviceProgram(port)
    device.thread.start()

    def check() -> str:
        for block in (1, 2):
            poll(lambda: phase(served).startswith(f"ready-{block}-"), f"the ready phase of block {block}")
            panel = json.loads(served.get("/scene.json").text())["participant"]
            assert panel["device"] == "udp", panel
            assert served.command("ready").startswith("ok")
            device.armed = True
            poll(lambda: phase(served).startswith(f"questionnaire-{block}-"), f"the questionnaire after block {block}")
            device.armed, device.push_started = False, None
            assert served.command(ANSWERS).startswith("ok")
        poll(lambda: served.process.poll() is not None, "the experiment to exit")
        assert served.process.returncode == 0, f"exit {served.process.returncode}:\n{served.log_tail()}"
        device.stop()
        runs = trials_of(device.replies)
        assert len(runs) == 2, f"{len(runs)} runs of replies, want the 2 trials'"
        for k, run in enumerate(runs, 1):
            forces = [f for _, _, f in run]
            assert forces[0] <= STEP_LIMIT_N, f"trial {k} starts telling {forces[0]:.3f} N"
            assert forces[-1] == 0.0, f"trial {k} ends telling {forces[-1]:.3f} N: the device is left pushing"
            ending = [i for i, (_, flags, _) in enumerate(run) if flags & ENDING]
            assert ending, f"trial {k}: no reply flagged ending"
            fade = forces[ending[0] - 1:]
            assert fade[0] > 1.0, f"trial {k}: the finger pressed {fade[0]:.2f} N when the trial ended, want a press to fade"
            steps = [abs(b - a) for a, b in zip(fade, fade[1:])]
            assert max(steps) <= STEP_LIMIT_N, f"trial {k}: the fade steps {max(steps):.3f} N at once"
            print(f"  trial {k}: {len(run)} replies, peak {max(forces):.2f} N, fade over {len(fade) - 1} replies from "
                  f"{fade[0]:.2f} N, largest fade step {max(steps):.3f} N")
        beh = data / "sub-01" / "beh"
        rows = read_tsv(beh / "sub-01_task-udppilot_beh.tsv")
        assert len(rows) == 2, rows
        for row in rows:
            with open(beh / row["run"].removeprefix("beh/") / "trace.csv") as f:
                xs = [float(r["index.dx"]) for r in csv.DictReader(f)]
            assert max(xs) - xs[0] > 0.03, f"trial {row['trial']}: the device moved {max(xs) - xs[0]:.4f} m"
        assert len(read_tsv(beh / "sub-01_task-udppilot_questionnaire.tsv")) == 2
        return "a UDP participant ran both blocks; the device's force faded out at each trial's end"

    try:
        return verdict(check, served.log_tail)
    finally:
        device.running = False
        served.stop()


if __name__ == "__main__":
    script(main, __doc__)
