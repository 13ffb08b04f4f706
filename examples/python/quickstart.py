#!/usr/bin/env python3
"""The Python module in a few lines: a run read back as numpy arrays, a world stepped and pressed.

Run from the repository's root after scripts/demo or scripts/test:

    python3 examples/python/quickstart.py

It uses an installed module (PYTHONPATH, or <prefix>/lib/python3/dist-packages) if there is one,
else the release build's build/release/python. The module is built for one interpreter (Debian's
/usr/bin/python3, where Debian's numpy is): under another one this stops with the command to run
instead (godfinger_guard.py). See docs/python.md."""
from godfinger_guard import import_godfinger

godfinger = import_godfinger()

# The paper's Fig. 8 pinch for 4.5 s: trace.csv's columns as numpy arrays, contacts as dicts.
run = godfinger.run("fig8-pinch-oscillation", duration=4.5)
lift = run.trace["cylinder.py"][-1] - run.trace["cylinder.py"][0]
print(f"{run.steps} steps; the cylinder rose {lift * 1000:.1f} mm; left finger's force "
      f"{run.trace['left.fx'][-1]:.2f} N; contact snapshots {', '.join(run.contacts)}")

# A live world: the finger presses the box, and each SGO's load is an array.
with godfinger.World("press-box") as world:
    world.move("index", [0.0, 0.035, 0.0], 0.5)
    world.step(600)
    contact = world.snapshot()["fingers"][0]["contacts"][0]
    print(f"t = {world.t:.3f} s: {len(contact['sgos'])} SGOs on the {contact['body']}, normal loads (N):",
          " ".join(f"{n:.3f}" for n in contact["normal_loads"]))
    # The state as arrays (no JSON), and a point in time to come back to.
    saved = world.save()
    world.step(100)
    box_y = world.arrays()["body_position"][world.bodies.index("box"), 1]
    world.restore(saved)
    world.step(100)
    assert world.arrays()["body_position"][world.bodies.index("box"), 1] == box_y
    print(f"box at y = {box_y * 1000:.3f} mm at t = {world.t:.3f} s, the same again after restore()")
