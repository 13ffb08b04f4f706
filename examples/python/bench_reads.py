#!/usr/bin/env python3
"""What reading a World's state costs (docs/python.md, "What a read costs").

    python3 examples/python/bench_reads.py [--steps 1000] [--calls 20000]

Each bundled scene is stepped `steps` haptic steps (1 s at 1 kHz), then each read is timed with
timeit: arrays() (numpy arrays read from the world), state() (the live answer as a dict) and
snapshot() (with each contact's SGO arrays). Prints the fastest of five rounds per call, in µs.
A benchmark, not a test: wall-clock times."""
import argparse
import os
import timeit

from godfinger_guard import import_godfinger

godfinger = import_godfinger()


def fastest_us(call, calls):
    return min(timeit.repeat(call, number=calls, repeat=5)) / calls * 1e6


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--steps", type=int, default=1000, help="steps before the reads")
    parser.add_argument("--calls", type=int, default=20000, help="calls per round of arrays()")
    args = parser.parse_args()
    # The bundled scenes: $GODFINGER_DATA's, else a build tree's beside the module.
    data = os.environ.get("GODFINGER_DATA") or os.path.join(os.path.dirname(godfinger.__file__), "..", "share", "godfinger")
    scenes = os.path.join(data, "scenes")
    print(f"{'scene':32} bodies fingers  arrays() us  state() us  snapshot() us")
    for name in sorted(f[:-5] for f in os.listdir(scenes) if f.endswith(".toml")):
        try:
            world = godfinger.World(name)
        except godfinger.InputError:
            continue  # a scene live cannot step (a UDP device)
        world.step(args.steps)
        few = max(args.calls // 20, 1)
        print(f"{name:32} {len(world.bodies):6} {len(world.fingers):7} {fastest_us(world.arrays, args.calls):12.2f} "
              f"{fastest_us(world.state, few):11.2f} {fastest_us(world.snapshot, few):14.2f}")


if __name__ == "__main__":
    main()
