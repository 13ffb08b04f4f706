"""Misuse of the module: every case raises a Python exception of the expected kind, and none crashes.

The cases run in a child process (this file run as a script), one after the other, each printing
its outcome as a JSON line: a crash (a segfault, an abort) ends the child with a signal, which
fails the test naming the case that was running. Cases that need a file get one in a folder the
test gives the child."""
import copy
import json
import math
import os
import pathlib
import pickle
import subprocess
import sys
import threading

# At least this many cases (issue 50: "100 misuse cases give Python exceptions and 0 crashes").
MIN_CASES = 100

NAN, INF = math.nan, math.inf
# The steps the World the cases use has taken before them; none of them may step it.
STEPS_BEFORE = 20


def lifetime_cases(g, saved):
    """An uninitialised World (World.__new__ alone), a closed one, __init__ twice, subclasses."""
    class Twice(g.World):
        def __init__(self):
            g.World.__init__(self, "press-box")
            g.World.__init__(self, "press-box")

    bare = g.World.__new__(g.World)
    closed = g.World("press-box")
    closed.close()
    calls = {
        "step": lambda w: w.step(1), "state": lambda w: w.state(), "arrays": lambda w: w.arrays(),
        "snapshot": lambda w: w.snapshot(), "contacts": lambda w: w.contacts(),
        "move": lambda w: w.move("index", [0, 0, 0]), "set": lambda w: w.set("fingers.index.n_sgo", 2),
        "reset": lambda w: w.reset(), "save": lambda w: w.save(), "restore": lambda w: w.restore(saved),
        "t": lambda w: w.t, "fingers": lambda w: w.fingers, "bodies": lambda w: w.bodies,
        "enter": lambda w: w.__enter__(),
    }
    cases = []
    for name, call in calls.items():
        cases.append((f"uninitialised World: {name}", lambda call=call: call(bare), RuntimeError))
        cases.append((f"closed World: {name}", lambda call=call: call(closed), RuntimeError))
    cases += [
        ("uninitialised World: close", bare.close, RuntimeError),
        ("uninitialised World: closed", lambda: bare.closed, RuntimeError),
        ("uninitialised World: __exit__", lambda: bare.__exit__(None, None, None), RuntimeError),
        ("__init__ twice", lambda: g.World("press-box").__init__("press-box"), RuntimeError),
        ("World.__init__ on a made World", lambda: g.World.__init__(g.World("press-box"), "fig8-pinch-oscillation"),
         RuntimeError),
        ("a subclass that skips __init__", lambda: type("Sub", (g.World,), {"__init__": lambda self: None})(),
         TypeError),
        ("a subclass that calls __init__ twice", Twice, RuntimeError),
        ("a method with another self", lambda: g.World.step(3, 1), TypeError),
        ("__repr__ with another self", lambda: g.World.__repr__("world"), TypeError),
        ("a method with no self", lambda: g.World.arrays(), TypeError),
    ]
    return cases


def construction_cases(g, folder):
    """World(scene, set=...) with bad scenes, paths and settings."""
    scene_cases = {
        "no scene": lambda: g.World(), "None": lambda: g.World(None), "an int": lambda: g.World(3),
        "a float": lambda: g.World(3.5), "a list": lambda: g.World(["press-box"]),
        "a dict": lambda: g.World({"scene": "press-box"}), "two positional arguments": lambda: g.World("press-box", {}),
        "an unknown keyword": lambda: g.World("press-box", sett={}),
    }
    cases = [(f"World scene: {name}", call, TypeError) for name, call in scene_cases.items()]
    bad_files = {"empty.toml": b"", "garbage.toml": b"[[[ = =\n", "binary.toml": bytes(range(256)),
                 "nul.toml": b"name = \"a\0b\"\n", "huge-number.toml": b"[world]\nhaptic_rate_hz = 1e999\n"}
    for name, content in bad_files.items():
        (folder / name).write_bytes(content)
    value_cases = {
        "empty": "", "unknown": "no-such-scene", "a NUL byte": "press\0box", "a newline": "press-box\n",
        "escape codes": "\x1b[31mred", "a folder": "/", "a missing path": pathlib.Path("/nonexistent/x.toml"),
        "bytes not UTF-8": b"\xff\xfe.toml", "a very long name": "x" * 100000,
        **{f"the file {name}": folder / name for name in bad_files},
    }
    cases += [(f"World scene: {name}", lambda s=scene: g.World(s), ValueError) for name, scene in value_cases.items()]
    bad_sets = {
        "None": ({"fingers.index.n_sgo": None}, ValueError), "NaN": ({"fingers.index.n_sgo": NAN}, ValueError),
        "inf": ({"fingers.index.d0": INF}, ValueError), "-inf": ({"fingers.index.d0": -INF}, ValueError),
        "out of range": ({"fingers.index.d0": -1}, ValueError), "unknown field": ({"no.such.field": 1}, ValueError),
        "an int key": ({3: 1}, ValueError), "an object": ({"fingers.index.n_sgo": object()}, ValueError),
        "a huge int": ({"fingers.index.n_sgo": 10 ** 100}, ValueError),
        "a dict value": ({"fingers.index.n_sgo": {"a": 1}}, ValueError), "an empty key": ({"": 1}, ValueError),
        "a bad finger": ({"fingers.thumb.n_sgo": 2}, ValueError),
        "set=None": (None, TypeError), "set=a list": ([("fingers.index.n_sgo", 2)], TypeError),
    }
    cases += [(f"World set: {name}", lambda s=s: g.World("press-box", set=s), kind) for name, (s, kind) in bad_sets.items()]
    return cases


def step_cases(w):
    """step(n) with counts out of range or of another type."""
    values = {"0": (0, ValueError), "-1": (-1, ValueError), "-10^6": (-10 ** 6, ValueError),
              "10^7 + 1": (10 ** 7 + 1, ValueError), "2^62": (2 ** 62, ValueError), "10^30": (10 ** 30, TypeError),
              "1.5": (1.5, TypeError), "NaN": (NAN, TypeError), "inf": (INF, TypeError), "'10'": ("10", TypeError),
              "None": (None, TypeError), "[1]": ([1], TypeError), "a complex": (1j, TypeError)}
    cases = [(f"step({name})", lambda n=n: w.step(n), kind) for name, (n, kind) in values.items()]
    cases += [("step(n=-5)", lambda: w.step(n=-5), ValueError), ("step(m=1)", lambda: w.step(m=1), TypeError),
              ("step(1, 2)", lambda: w.step(1, 2), TypeError)]
    return cases


def move_cases(w):
    """move(finger, xyz, seconds) with bad fingers, vectors and durations."""
    args = {
        "an unknown finger": (("thumb", [0, 0, 0]), ValueError), "an empty finger": (("", [0, 0, 0]), ValueError),
        "finger None": ((None, [0, 0, 0]), TypeError), "xyz None": (("index", None), TypeError),
        "2 coordinates": (("index", [0, 0]), ValueError), "4 coordinates": (("index", [0, 0, 0, 0]), ValueError),
        "no coordinates": (("index", []), ValueError), "x NaN": (("index", [NAN, 0, 0]), ValueError),
        "z inf": (("index", [0, 0, INF]), ValueError), "seconds NaN": (("index", [0, 0, 0], NAN), ValueError),
        "seconds -1": (("index", [0, 0, 0], -1), ValueError), "seconds inf": (("index", [0, 0, 0], INF), ValueError),
        "seconds 1e300": (("index", [0, 0, 0], 1e300), ValueError), "seconds '1'": (("index", [0, 0, 0], "1"), TypeError),
        "seconds None": (("index", [0, 0, 0], None), TypeError), "a str coordinate": (("index", ["a", 0, 0]), TypeError),
        "xyz a str": (("index", "abc"), TypeError), "xyz a dict": (("index", {"x": 0}), TypeError),
        "a newline in the finger": (("index\n", [0, 0, 0]), ValueError),
        "a NUL in the finger": (("ind\0ex", [0, 0, 0]), ValueError),
        "a command in the finger": (("index 0 0 0 0\nstep", [0, 0, 0]), ValueError),
        "spaces in the finger": (("index 1 2 3", [0, 0, 0]), ValueError),
        "a tab in the finger": (("index\t", [0, 0, 0]), ValueError),
    }
    return [(f"move: {name}", lambda a=a: w.move(*a), kind) for name, (a, kind) in args.items()]


def set_cases(w):
    """set(field, value) with bad fields, values and control characters."""
    args = {
        "an unknown field": (("fingers.index.no_such", 1), ValueError),
        "a negative d0": (("fingers.index.d0", -1), ValueError), "None": (("fingers.index.n_sgo", None), ValueError),
        "NaN": (("fingers.index.r_max", NAN), ValueError), "inf": (("fingers.index.friction", INF), ValueError),
        "-1 SGOs": (("fingers.index.n_sgo", -1), ValueError), "10^9 SGOs": (("fingers.index.n_sgo", 10 ** 9), ValueError),
        "a word": (("fingers.index.n_sgo", "many"), ValueError), "a list": (("fingers.index.friction", [1, 2]), ValueError),
        "a bool": (("fingers.index.friction", True), ValueError), "bytes": (("fingers.index.n_sgo", b"4"), ValueError),
        "a dict": (("fingers.index.n_sgo", {"a": 1}), ValueError), "an object": (("fingers.index.n_sgo", object()), ValueError),
        "an unknown finger": (("fingers.thumb.n_sgo", 2), ValueError), "an empty field": (("", 1), ValueError),
        "a scene field": (("duration", 1), ValueError), "field None": ((None, 1), TypeError),
        "a newline in the field": (("fingers.index.n_sgo\nstep 5", 1), ValueError),
        "a newline in the value": (("fingers.index.n_sgo", "4\nstep 100"), ValueError),
        "a carriage return in the value": (("fingers.index.n_sgo", "4\r"), ValueError),
        "an escape in the value": (("fingers.index.n_sgo", "\x1b[2J"), ValueError),
        "DEL in the field": (("fingers.index.n_sgo\x7f", 1), ValueError),
    }
    return [(f"set: {name}", lambda a=a: w.set(*a), kind) for name, (a, kind) in args.items()]


def state_cases(g, w, foreign):
    """restore, State and pickling."""
    return [
        ("restore(None)", lambda: w.restore(None), TypeError), ("restore('state')", lambda: w.restore("state"), TypeError),
        ("restore(a World)", lambda: w.restore(w), TypeError),
        ("restore(another World's State)", lambda: w.restore(foreign), ValueError),
        ("State()", lambda: g.State(), TypeError), ("Run()", lambda: g.Run(), TypeError),
        ("pickle a State", lambda: pickle.dumps(foreign), TypeError), ("pickle a World", lambda: pickle.dumps(w), TypeError),
        ("copy a World", lambda: copy.copy(w), TypeError), ("deepcopy a World", lambda: copy.deepcopy(w), TypeError),
        ("assign t", lambda: setattr(w, "t", 1.0), AttributeError),
        ("assign bodies", lambda: setattr(w, "bodies", []), AttributeError),
        ("assign a State's step", lambda: setattr(foreign, "step", 0), AttributeError),
        ("an unknown method", lambda: w.no_such_method(), AttributeError),
    ]


def thread_cases(w):
    """A World used from another thread than its own."""
    def from_thread(call):
        outcome = []

        def target():
            try:
                call()
            except BaseException as error:  # noqa: B902 (carried to the calling thread)
                outcome.append(error)
        thread = threading.Thread(target=target)
        thread.start()
        thread.join()
        if outcome:
            raise outcome[0]
    return [(f"another thread: {name}", lambda c=c: from_thread(c), RuntimeError)
            for name, c in {"step": lambda: w.step(1), "arrays": w.arrays, "close": w.close, "reset": w.reset}.items()]


def run_and_study_cases(g, folder):
    """run() and study() with bad scenes, durations, settings and folders."""
    (folder / "a-file").write_text("not a folder\n")
    return [
        ("run(None)", lambda: g.run(None), TypeError), ("run(3)", lambda: g.run(3), TypeError),
        ("run: unknown scene", lambda: g.run("no-such-scene"), ValueError),
        ("run: NUL in the scene", lambda: g.run("press\0box"), ValueError),
        ("run: duration -1", lambda: g.run("press-box", duration=-1), ValueError),
        ("run: duration NaN", lambda: g.run("press-box", duration=NAN), ValueError),
        ("run: duration inf", lambda: g.run("press-box", duration=INF), ValueError),
        ("run: duration 1e300", lambda: g.run("press-box", duration=1e300), ValueError),
        ("run: duration '1'", lambda: g.run("press-box", duration="1"), TypeError),
        ("run: a bad set", lambda: g.run("press-box", set={"fingers.index.d0": -1}), ValueError),
        ("run: set=None", lambda: g.run("press-box", set=None), TypeError),
        ("run: out=3", lambda: g.run("press-box", out=3), TypeError),
        ("run: NUL in out", lambda: g.run("press-box", duration=0.01, out="bad\0dir"), ValueError),
        ("run: out a file", lambda: g.run("press-box", duration=0.01, out=folder / "a-file"), (RuntimeError, OSError)),
        ("run: close_ups='yes'", lambda: g.run("press-box", close_ups="yes"), TypeError),
        ("run: positional duration", lambda: g.run("press-box", 1.0), TypeError),
        ("study(None)", lambda: g.study(None), TypeError), ("study(3)", lambda: g.study(3), TypeError),
        ("study: unknown", lambda: g.study("no-such-study", quick=True), ValueError),
        ("study: jobs 0", lambda: g.study("rolling", jobs=0), ValueError),
        ("study: jobs -1", lambda: g.study("rolling", jobs=-1), ValueError),
        ("study: jobs 10^20", lambda: g.study("rolling", jobs=10 ** 20), TypeError),
        ("study: jobs 1.5", lambda: g.study("rolling", jobs=1.5), TypeError),
        ("study: out=3", lambda: g.study("rolling", quick=True, out=3), TypeError),
        ("study: a bad set", lambda: g.study("rolling", quick=True, set={"fingers.x": None}), ValueError),
    ]


def all_cases(g, folder, world):
    """Every case: (name, call, expected exception class or classes); `world` is a World of
    press-box, which no case may change."""
    saved = g.World("press-box").save()
    return (lifetime_cases(g, saved) + construction_cases(g, folder) + step_cases(world) + move_cases(world)
            + set_cases(world) + state_cases(g, world, saved) + thread_cases(world) + run_and_study_cases(g, folder))


def child(folder):
    """Runs every case, printing one JSON line each, then steps the World the cases were refused by;
    exits 0 when all ran (whatever they raised)."""
    import godfinger
    world = godfinger.World("press-box")
    world.step(STEPS_BEFORE)
    for name, call, expected in all_cases(godfinger, pathlib.Path(folder), world):
        print(json.dumps({"case": name, "started": True}), flush=True)
        try:
            call()
            raised, message = None, ""
        except BaseException as error:  # noqa: B902 (each case's exception is its outcome)
            raised, message = error, str(error)
        ok = raised is not None and isinstance(raised, expected) and not isinstance(raised, SystemError)
        print(json.dumps({"case": name, "raised": type(raised).__name__, "message": message[:300], "ok": ok}), flush=True)
    world.step(5)
    print(json.dumps({"steps_after": int(world.arrays()["step"])}), flush=True)


def test_misuse_raises_python_exceptions_and_never_crashes(tmp_path):
    done = subprocess.run([sys.executable, __file__, str(tmp_path)], capture_output=True, text=True, env=os.environ)
    lines = [json.loads(line) for line in done.stdout.splitlines()]
    outcomes = [line for line in lines if "ok" in line]
    running = lines[-1].get("case", "(after the cases)") if lines else "(before the first case)"
    assert done.returncode == 0, f"the child ended with {done.returncode} during {running!r}:\n{done.stderr[-3000:]}"
    assert len(outcomes) == len([line for line in lines if "started" in line])
    wrong = [f"{o['case']}: raised {o['raised']}: {o['message']}" for o in outcomes if not o["ok"]]
    assert not wrong, "\n".join(wrong)
    assert len(outcomes) >= MIN_CASES, len(outcomes)
    # The refused commands left the world as it was: it steps on from where it stood.
    assert lines[-1] == {"steps_after": STEPS_BEFORE + 5}
    print(f"{len(outcomes)} misuse cases, each raised its Python exception; no crash")


if __name__ == "__main__":
    child(sys.argv[1])
