"""godfinger.World as a session: its lifetime (close, with, uninitialised and twice-initialised
objects), reset, save and restore bit for bit, paths as os.PathLike, and the state as arrays."""
import json
import os
import pathlib
import pickle
import threading

import numpy as np
import pytest

import godfinger


def bundled_scene(name):
    """A bundled scene's file, found the way the module finds it ($GODFINGER_DATA, set at import)."""
    return pathlib.Path(os.environ["GF_BINARY_DIR"]) / "share" / "godfinger" / "scenes" / f"{name}.toml"


def same(a, b):
    """Two arrays() answers equal bit for bit (every array's bytes, and t and step)."""
    assert a.keys() == b.keys()
    for key in a:
        if isinstance(a[key], np.ndarray):
            assert a[key].dtype == b[key].dtype and a[key].tobytes() == b[key].tobytes(), key
        else:
            assert a[key] == b[key], key


def test_a_world_made_by_new_alone_raises_instead_of_crashing():
    world = godfinger.World.__new__(godfinger.World)
    for call in (lambda: world.step(1), world.state, world.arrays, world.close, world.save, lambda: world.t):
        with pytest.raises(RuntimeError, match="not initialised"):
            call()
    assert repr(world) == "<godfinger.World (not initialised)>"
    godfinger.World.__init__(world, "press-box")  # a late __init__ makes it whole
    world.step(3)
    assert world.arrays()["step"] == 3


def test_a_second_init_raises_and_leaves_the_world_as_it_was():
    world = godfinger.World("press-box")
    world.step(5)
    with pytest.raises(RuntimeError, match="already initialised"):
        world.__init__("fig8-pinch-oscillation")
    assert world.bodies == godfinger.World("press-box").bodies
    assert world.arrays()["step"] == 5


def test_close_is_idempotent_and_every_method_then_raises():
    world = godfinger.World("press-box")
    world.close()
    world.close()
    assert world.closed and repr(world) == "<godfinger.World press-box (closed)>"
    for call in (lambda: world.step(), world.state, world.arrays, world.snapshot, world.contacts, world.reset,
                 world.save, lambda: world.move("index", [0, 0, 0]), lambda: world.set("fingers.index.n_sgo", 2),
                 lambda: world.t, lambda: world.fingers, lambda: world.__enter__()):
        with pytest.raises(RuntimeError, match="closed"):
            call()


def test_with_closes_the_world_also_when_the_block_raises():
    with godfinger.World("press-box") as world:
        world.step(2)
        assert not world.closed
    assert world.closed
    with pytest.raises(KeyError):
        with godfinger.World("press-box") as other:
            raise KeyError("inside")
    assert other.closed


def test_another_thread_is_refused():
    world = godfinger.World("press-box")
    raised = []
    thread = threading.Thread(target=lambda: raised.append(pytest.raises(RuntimeError, world.step, 1)))
    thread.start()
    thread.join()
    assert "another thread" in str(raised[0].value)
    world.step(1)
    assert world.arrays()["step"] == 1


def test_reset_is_the_start_with_the_same_settings():
    fresh = godfinger.World("press-box", set={"fingers.index.n_sgo": 4})
    fresh.step(300)
    world = godfinger.World("press-box", set={"fingers.index.n_sgo": 4})
    world.move("index", [0.01, 0.05, 0.0], 0.1)
    world.set("fingers.index.n_sgo", 6)
    world.step(250)
    world.reset()
    assert world.t == 0.0 and world.state()["fingers"][0]["settings"]["n_sgo"] == 4
    world.step(300)
    same(world.arrays(), fresh.arrays())
    assert world.state() == fresh.state()


def test_steps_after_restore_are_the_steps_after_save_bit_for_bit():
    world = godfinger.World("fig8-pinch-oscillation")
    world.step(1200)
    world.set("fingers.left.n_sgo", 4)
    world.step(300)
    saved = world.save()
    assert (saved.step, saved.t) == (1500, world.t)
    world.step(700)
    after_save = world.arrays()
    contacts_after_save = world.contacts()
    world.move("left", [0.0, 0.1, 0.0], 0.2)
    world.step(50)
    world.restore(saved)
    assert world.arrays()["step"] == 1500 and world.state()["fingers"][0]["settings"]["n_sgo"] == 4
    world.step(700)
    same(world.arrays(), after_save)
    assert world.contacts() == contacts_after_save
    world.restore(saved)  # a State restores as often as asked
    world.step(700)
    same(world.arrays(), after_save)


def test_a_state_restores_after_reset_but_not_into_another_world():
    world = godfinger.World("press-box")
    world.step(40)
    saved = world.save()
    expected = world.arrays()
    world.reset()
    world.restore(saved)
    same(world.arrays(), expected)
    with pytest.raises(ValueError, match="another World"):
        godfinger.World("press-box").restore(saved)
    with pytest.raises(TypeError):
        pickle.dumps(saved)


def test_paths_are_taken_as_os_pathlike():
    path = bundled_scene("press-box")
    assert path.exists()
    world = godfinger.World(path)
    world.step(5)
    by_name = godfinger.World("press-box")
    by_name.step(5)
    same(world.arrays(), by_name.arrays())
    assert godfinger.World(os.fsencode(path)).bodies == world.bodies


def test_run_takes_paths_for_the_scene_and_the_folder(tmp_path):
    run = godfinger.run(bundled_scene("press-box"), duration=0.01, out=tmp_path / "kept")
    assert run.out == str(tmp_path / "kept")
    assert (tmp_path / "kept" / "trace.csv").exists() and run.steps == 10


def test_a_path_of_another_type_or_with_a_nul_byte_is_refused():
    with pytest.raises(TypeError, match="os.PathLike, got int"):
        godfinger.World(3)
    with pytest.raises(ValueError, match="null byte"):
        godfinger.World("press\0box")
    with pytest.raises(TypeError, match="run: out"):
        godfinger.run("press-box", out=3.5)


def test_arrays_are_the_snapshots_values():
    world = godfinger.World("fig8-pinch-oscillation")
    world.step(2000)
    arrays, snap = world.arrays(), world.snapshot()
    n_bodies, n_fingers = len(world.bodies), len(world.fingers)
    assert arrays["body_position"].shape == (n_bodies, 3) and arrays["body_orientation"].shape == (n_bodies, 4)
    assert arrays["finger_proxy"].shape == (n_fingers, 3) and arrays["finger_n_sgo"].shape == (n_fingers,)
    assert (arrays["t"], arrays["step"]) == (snap["t"], snap["step"])
    for i, body in enumerate(snap["bodies"]):
        for key, column in [("position", "body_position"), ("orientation", "body_orientation"),
                            ("velocity", "body_velocity"), ("angular_velocity", "body_angular_velocity")]:
            assert arrays[column][i].tobytes() == body[key].tobytes(), (body["name"], key)
    for i, finger in enumerate(snap["fingers"]):
        for key, column in [("proxy", "finger_proxy"), ("device", "finger_device"), ("force", "finger_force"),
                            ("feedback", "finger_feedback")]:
            assert arrays[column][i].tobytes() == finger[key].tobytes(), (finger["name"], key)
        assert arrays["finger_n_sgo"][i] == finger["n_sgo"] == 8
    assert np.linalg.norm(arrays["finger_force"], axis=1).min() > 0.1  # both fingers pinch


def test_state_is_the_json_answer_without_a_round_trip(cli):
    done = cli("live", "press-box", stdin="step 900\nstate\n")
    expected = json.loads(done.stdout.splitlines()[-1][len("ok "):])
    world = godfinger.World("press-box")
    world.step(900)
    assert world.state() == expected
