#!/usr/bin/env python3
"""A device program for godfinger's UDP device protocol (docs/device-protocol.md).

It stands in for a real device: it replays the keyframe tracks of a scene's fingers (the Fig. 8
pinch by default), sending each finger's position on its own channel at --rate packets per second,
and reads godfinger's replies (the force to render). At the end it prints one JSON line:
sent, answered (packets whose seq came back), rtt_us_p50 / rtt_us_p99 (from sending a packet to
the first reply echoing it), max_force_n, and a few more counts.

    godfinger run device-udp --realtime --out udp-run &
    python3 examples/device-udp/client.py --port 47001 --seconds 8 --rate 1000

To drive godfinger from a real device, keep send_packet() and read_replies() and replace the
track with the device SDK's position reading and force command. Python 3.11+ standard library
only (tomllib reads the scene whose keyframes are replayed).
"""

import argparse
import collections
import json
import math
import os
import select
import socket
import struct
import sys
import time

PACKET = struct.Struct("<IIIId3d")       # magic, seq, channel, buttons, time, x, y, z (48 bytes)
ORIENTED = struct.Struct("<IIIId3d4f")   # the same, then the orientation w, x, y, z as f32 (64 bytes)
REPLY = struct.Struct("<IIIId3ddIf")     # magic, seq, channel, flags, time, fx, fy, fz, radius, n_sgo, gain (64 bytes)
PACKET_MAGIC = 0x31444647                # "GFD1"
ORIENTED_MAGIC = 0x32444647              # "GFD2"
REPLY_MAGIC = 0x31524647                 # "GFR1"
STALE, TOUCHING, RAMPING = 1, 2, 4

HERE = os.path.dirname(os.path.abspath(__file__))
# The Fig. 8 scene in the source tree (examples/device-udp/), or installed: this file in
# <prefix>/share/doc/godfinger/examples/device-udp/, the scenes in <prefix>/share/godfinger/scenes/.
SCENE_PLACES = [os.path.join(HERE, "..", "..", "assets", "scenes"),
                os.path.join(HERE, "..", "..", "..", "..", "godfinger", "scenes")]
DEFAULT_SCENE = next((p for p in (os.path.join(d, "fig8-pinch-oscillation.toml") for d in SCENE_PLACES)
                      if os.path.exists(p)), os.path.join(SCENE_PLACES[0], "fig8-pinch-oscillation.toml"))


def load_tracks(path):
    """Each finger's (interpolation, [(t, (x, y, z), (w, x, y, z)), ...]) in the scene file's order
    (the orientation is the keyframe's q, identity when it gives none)."""
    import tomllib  # Python 3.11+
    with open(path, "rb") as f:
        scene = tomllib.load(f)
    tracks = []
    for name, finger in scene.get("fingers", {}).items():
        device = finger.get("device", {})
        if "keyframes" not in device:
            sys.exit(f"{path}: fingers.{name}.device has no keyframes to replay")
        frames = [(float(k["t"]), tuple(float(v) for v in k["p"]), tuple(float(v) for v in k.get("q", (1, 0, 0, 0))))
                  for k in device["keyframes"]]
        tracks.append((device.get("interpolation", "smooth"), frames))
    if not tracks:
        sys.exit(f"{path}: no fingers")
    return tracks


def slerp(q0, q1, u):
    """Unit quaternions (w, x, y, z) q0 to q1 by u in [0, 1], the shorter way round."""
    n0, n1 = (math.sqrt(sum(c * c for c in q)) for q in (q0, q1))
    q0, q1 = tuple(c / n0 for c in q0), tuple(c / n1 for c in q1)
    dot = sum(a * b for a, b in zip(q0, q1))
    if dot < 0.0:
        q1, dot = tuple(-c for c in q1), -dot
    if dot > 0.9995:  # nearly parallel: a normalised straight line
        q = tuple(a + u * (b - a) for a, b in zip(q0, q1))
    else:
        angle = math.acos(dot)
        w0, w1 = math.sin((1.0 - u) * angle), math.sin(u * angle)
        q = tuple(w0 * a + w1 * b for a, b in zip(q0, q1))
    n = math.sqrt(sum(c * c for c in q))
    return tuple(c / n for c in q)


def pose(track, t):
    """The track's position and orientation at time t, as godfinger plays keyframes back (held
    at both ends)."""
    interpolation, frames = track
    if t <= frames[0][0]:
        return frames[0][1], slerp(frames[0][2], frames[0][2], 0.0)
    if t >= frames[-1][0]:
        return frames[-1][1], slerp(frames[-1][2], frames[-1][2], 0.0)
    for (t0, p0, q0), (t1, p1, q1) in zip(frames, frames[1:]):
        if t < t1:
            u = (t - t0) / (t1 - t0)
            if interpolation == "smooth":
                u = u * u * (3.0 - 2.0 * u)
            return tuple(a + u * (b - a) for a, b in zip(p0, p1)), slerp(q0, q1, u)
    return frames[-1][1], slerp(frames[-1][2], frames[-1][2], 0.0)


def percentile(values, q):
    if not values:
        return None
    ordered = sorted(values)
    return ordered[min(len(ordered) - 1, int(q * (len(ordered) - 1) + 0.5))]


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--port", type=int, required=True, help="godfinger's UDP port (the scene's udp = ...)")
    parser.add_argument("--host", default="127.0.0.1", help="godfinger's address (default 127.0.0.1)")
    parser.add_argument("--seconds", type=float, default=8.0, help="how long to replay (default 8)")
    parser.add_argument("--rate", type=float, default=1000.0, help="packets per second per finger (default 1000)")
    parser.add_argument("--scene", default=DEFAULT_SCENE,
                        help="scene file whose fingers' keyframes are replayed, finger i on channel i "
                             "(default: the Fig. 8 pinch)")
    parser.add_argument("--gfd2", action="store_true",
                        help="send 64-byte GFD2 packets with each track's orientation (its keyframes' q, "
                             "identity without): a 6-DOF device")
    args = parser.parse_args()
    if not (args.rate > 0 and args.seconds >= 0 and 0 < args.port < 65536):
        parser.error("--rate must be > 0, --seconds >= 0 and --port in 1..65535")
    tracks = load_tracks(args.scene)

    sock = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
    sock.setblocking(False)
    target = (args.host, args.port)
    # Per channel, (seq, send time) of the packets not answered yet, oldest first: a reply echoes
    # the newest seq taken, so the ones before it will never be echoed and are dropped.
    sent_at = [collections.deque() for _ in tracks]
    rtts = []
    counts = {"sent": 0, "answered": 0, "replies": 0, "stale_replies": 0, "bad_replies": 0}
    max_force = 0.0

    def read_replies():
        nonlocal max_force
        while True:
            try:
                data = sock.recv(128)
            except (BlockingIOError, InterruptedError):
                return
            except ConnectionRefusedError:  # nothing listens (yet)
                return
            now = time.perf_counter()
            if len(data) != REPLY.size:
                counts["bad_replies"] += 1
                continue
            magic, seq, channel, flags, _, fx, fy, fz, _, _, _ = REPLY.unpack(data)
            if magic != REPLY_MAGIC or channel >= len(tracks):
                counts["bad_replies"] += 1
                continue
            counts["replies"] += 1
            if flags & STALE:
                counts["stale_replies"] += 1
            max_force = max(max_force, math.sqrt(fx * fx + fy * fy + fz * fz))
            waiting = sent_at[channel]
            while waiting and waiting[0][0] < seq:
                waiting.popleft()
            if waiting and waiting[0][0] == seq:
                counts["answered"] += 1
                rtts.append((now - waiting.popleft()[1]) * 1e6)

    def send_packet(channel, seq, t, pose_now):
        p, q = pose_now
        if args.gfd2:
            sock.sendto(ORIENTED.pack(ORIENTED_MAGIC, seq, channel, 0, t, *p, *q), target)
        else:
            sock.sendto(PACKET.pack(PACKET_MAGIC, seq, channel, 0, t, *p), target)
        sent_at[channel].append((seq, time.perf_counter()))
        counts["sent"] += 1

    period = 1.0 / args.rate
    ticks = int(round(args.seconds * args.rate))
    start = time.perf_counter()
    for k in range(ticks + 1):
        deadline = start + k * period
        while True:  # answer replies until the tick's deadline
            left = deadline - time.perf_counter()
            if left <= 0:
                break
            select.select([sock], [], [], left)
            read_replies()
        t = k * period
        for channel, track in enumerate(tracks):
            send_packet(channel, k, t, pose(track, t))
        read_replies()
    end = time.perf_counter() + 0.05  # the last replies
    while time.perf_counter() < end:
        select.select([sock], [], [], max(0.0, end - time.perf_counter()))
        read_replies()

    p50, p99 = percentile(rtts, 0.5), percentile(rtts, 0.99)
    print(json.dumps({
        "sent": counts["sent"],
        "answered": counts["answered"],
        "rtt_us_p50": round(p50, 1) if p50 is not None else None,
        "rtt_us_p99": round(p99, 1) if p99 is not None else None,
        "max_force_n": round(max_force, 4),
        "replies": counts["replies"],
        "stale_replies": counts["stale_replies"],
        "bad_replies": counts["bad_replies"],
        "channels": len(tracks),
    }))
    return 0 if counts["answered"] > 0 else 1


if __name__ == "__main__":
    sys.exit(main())
