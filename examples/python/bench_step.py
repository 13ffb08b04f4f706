#!/usr/bin/env python3
"""What a Python World step costs against the C++ loop's step (docs/python.md, "What a step costs").

    python3 examples/python/bench_step.py [--n-sgo N] [--steps 1000] [--rounds 25]

The Fig. 8 pinch (as gf_bench's BM_PinchStep) is stepped to 3.5 s, into the hold, then in
alternating rounds: `world.step(steps)` (one call: the steps run in C++'s loop, no Python between
them) and `steps` calls of `world.step()` (one Python call per step). Prints the time per step of
each way, the fastest round's and the median round's, and their ratios: the fastest rounds are
the ones the machine's other work disturbed least. A benchmark, not a test: wall-clock times."""
import argparse
import statistics
import sys
import time

from godfinger_guard import import_godfinger

godfinger = import_godfinger()


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--scene", default="fig8-pinch-oscillation")
    parser.add_argument("--n-sgo", type=int, default=8, help="SGOs per finger (0: god-objects)")
    parser.add_argument("--steps", type=int, default=1000, help="steps per round")
    parser.add_argument("--rounds", type=int, default=25)
    args = parser.parse_args()
    world = godfinger.World(args.scene, set={f"fingers.{f}.n_sgo": args.n_sgo for f in ("left", "right")})
    world.step(3500)
    step = world.step
    in_cpp, per_call = [], []
    for _ in range(args.rounds):
        start = time.perf_counter()
        step(args.steps)
        in_cpp.append((time.perf_counter() - start) / args.steps * 1e6)
        start = time.perf_counter()
        for _ in range(args.steps):
            step()
        per_call.append((time.perf_counter() - start) / args.steps * 1e6)
    fastest = min(per_call) / min(in_cpp)
    median = statistics.median(per_call) / statistics.median(in_cpp)
    print(f"{args.scene}, n_sgo {args.n_sgo}, {args.rounds} rounds of {args.steps} steps: C++ loop "
          f"{min(in_cpp):.2f} us fastest / {statistics.median(in_cpp):.2f} us median per step, Python calls "
          f"{min(per_call):.2f} / {statistics.median(per_call):.2f} us: ratio {fastest:.3f} fastest, "
          f"{median:.3f} median (t = {world.t:.1f} s)")


if __name__ == "__main__":
    main()
