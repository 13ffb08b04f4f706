#!/usr/bin/env python3
"""The Python module in a few lines: a run read back as numpy arrays, a world stepped and pressed.

Run from the repository's root after scripts/demo or scripts/test:

    python3 examples/python/quickstart.py

It uses an installed module (PYTHONPATH, or <prefix>/lib/python3/dist-packages) if there is one,
else the release build's build/release/python. See docs/python.md."""
import os
import sys

try:
    import godfinger
except ImportError:
    root = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    sys.path.insert(0, os.path.join(root, "build", "release", "python"))
    import godfinger

# The paper's Fig. 8 pinch for 4.5 s: trace.csv's columns as numpy arrays, contacts as dicts.
run = godfinger.run("fig8-pinch-oscillation", duration=4.5)
lift = run.trace["cylinder.py"][-1] - run.trace["cylinder.py"][0]
print(f"{run.steps} steps; the cylinder rose {lift * 1000:.1f} mm; left finger's force "
      f"{run.trace['left.fx'][-1]:.2f} N; contact snapshots {', '.join(run.contacts)}")

# A live world: the finger presses the box, and each SGO's load is an array.
world = godfinger.World("press-box")
world.move("index", [0.0, 0.035, 0.0], 0.5)
world.step(600)
contact = world.snapshot()["fingers"][0]["contacts"][0]
print(f"t = {world.t:.3f} s: {len(contact['sgos'])} SGOs on the {contact['body']}, normal loads (N):",
      " ".join(f"{n:.3f}" for n in contact["normal_loads"]))
