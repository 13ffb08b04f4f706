#!/usr/bin/env python3
"""What a Python World step costs against the C++ loop's step (docs/python.md, "What a step costs").

    python3 examples/python/bench_step.py [--n-sgo N] [--steps 2000] [--rounds 7]

The Fig. 8 pinch (as gf_bench's BM_PinchStep) is stepped to 1.5 s, into the hold, then in
alternating rounds: `world.step(steps)` (one call: the steps run in C++'s loop, no Python between
them) and `steps` calls of `world.step()` (one Python call per step). Prints each round's time
per step and the median ratio. A benchmark, not a test: wall-clock times on a shared machine."""
import argparse
import os
import statistics
import sys
import time

try:
    import godfinger
except ImportError:
    root = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    sys.path.insert(0, os.path.join(root, "build", "release", "python"))
    import godfinger


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--scene", default="fig8-pinch-oscillation")
    parser.add_argument("--n-sgo", type=int, default=8, help="SGOs per finger (0: god-objects)")
    parser.add_argument("--steps", type=int, default=2000, help="steps per round")
    parser.add_argument("--rounds", type=int, default=7)
    args = parser.parse_args()
    world = godfinger.World(args.scene, set={f"fingers.{f}.n_sgo": args.n_sgo for f in ("left", "right")})
    world.step(1500)
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
        print(f"C++ loop {in_cpp[-1]:.2f} us/step, Python calls {per_call[-1]:.2f} us/step, "
              f"ratio {per_call[-1] / in_cpp[-1]:.3f}")
    ratios = [p / c for p, c in zip(per_call, in_cpp)]
    print(f"{args.scene}, n_sgo {args.n_sgo}: median C++ {statistics.median(in_cpp):.2f} us, Python "
          f"{statistics.median(per_call):.2f} us per step, ratio {statistics.median(ratios):.3f} "
          f"(range {min(ratios):.3f}-{max(ratios):.3f}); t = {world.t:.2f} s")


if __name__ == "__main__":
    main()
