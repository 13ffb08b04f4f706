"""Ctrl-C during a long World.step: KeyboardInterrupt within a few milliseconds' steps, the world
left at a whole step, still stepping as a world that took those steps.

A child process (this file run as a script) steps a world 10^7 times; the test sends it SIGINT
once the child has said it is about to step. No sleep and no clock: should the signal land
before the call has begun (KeyboardInterrupt at step 0), the child says so and steps again, and
the test sends another."""
import json
import os
import signal
import subprocess
import sys

import godfinger

SCENE = "press-box"
REQUESTED = 10_000_000
AFTER = 10


def child():
    """Steps until interrupted mid-call; prints the steps taken and whether the world went on
    exactly as a fresh one given the same steps."""
    world = godfinger.World(SCENE)
    while True:
        try:
            print("stepping", flush=True)
            world.step(REQUESTED)
            print(json.dumps({"finished": True}), flush=True)
            return
        except KeyboardInterrupt:
            taken = int(world.arrays()["step"])
            if taken > 0:
                break
    world.step(AFTER)
    fresh = godfinger.World(SCENE)
    fresh.step(taken + AFTER)
    a, b = world.arrays(), fresh.arrays()
    same = all(a[k].tobytes() == b[k].tobytes() for k in a if hasattr(a[k], "tobytes")) and a["t"] == b["t"]
    print(json.dumps({"taken": taken, "step": int(a["step"]), "same": same}), flush=True)


def test_ctrl_c_interrupts_a_long_step_at_a_whole_step():
    proc = subprocess.Popen([sys.executable, __file__], stdout=subprocess.PIPE, text=True)
    signals, result = 0, None
    for line in proc.stdout:
        if line == "stepping\n":
            os.kill(proc.pid, signal.SIGINT)
            signals += 1
            continue
        result = json.loads(line)
        break
    proc.stdout.close()
    assert proc.wait() == 0 and result is not None
    assert "finished" not in result, "the step ran to its end: the interrupt was not taken"
    assert 0 < result["taken"] < REQUESTED
    # Signals are checked between blocks of 64 steps: the call stops at a block's end.
    assert result["taken"] % 64 == 0
    assert result["step"] == result["taken"] + AFTER
    assert result["same"], "after the interrupt the world did not step as one that took the same steps"
    assert signals >= 1


if __name__ == "__main__":
    child()
