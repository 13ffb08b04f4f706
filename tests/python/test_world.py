"""godfinger.World: a live session from Python, answering as `godfinger live` does."""
import json

import numpy as np
import pytest

import godfinger


def live_answers(cli, scene, lines, *options):
    """`godfinger live SCENE OPTIONS...` fed `lines`: the answers after the ready line."""
    done = cli("live", scene, *options, stdin="".join(line + "\n" for line in lines), check=False)
    return done.stdout.splitlines()[1:]


def test_step_advances_the_world_by_haptic_steps():
    world = godfinger.World("press-box")
    world.step(10)
    world.step()
    state = world.state()
    assert state["step"] == 11
    assert world.t == pytest.approx(0.011, abs=1e-12) and state["t"] == world.t


def test_state_after_commands_is_the_live_commands_answer(cli):
    lines = ["step 200", "move index 0.005 0.04 0 0.1", "set fingers.index.n_sgo=4", "step 300", "state"]
    expected = json.loads(live_answers(cli, "press-box", lines)[-1][len("ok "):])
    world = godfinger.World("press-box")
    world.step(200)
    assert world.move("index", [0.005, 0.04, 0.0], 0.1) == "index to 0.005 0.04 0 by t=0.3"
    world.set("fingers.index.n_sgo", 4)
    world.step(300)
    assert world.state() == expected


def test_moving_a_finger_moves_its_device_and_proxy():
    world = godfinger.World("press-box")
    world.step(100)
    before = world.state()["fingers"][0]
    world.move("index", [0.02, 0.08, 0.01], 0.05)
    world.step(60)
    after = world.state()["fingers"][0]
    assert after["device"] == pytest.approx([0.02, 0.08, 0.01], abs=1e-12)
    assert after["device"] != before["device"]
    assert after["proxy"] != before["proxy"]


def test_set_changes_a_live_setting():
    world = godfinger.World("press-box")
    world.set("fingers.index.n_sgo", 4)
    world.step(700)
    finger = world.state()["fingers"][0]
    assert finger["settings"]["n_sgo"] == 4
    assert finger["n_sgo"] == 4


def test_set_refuses_a_bad_field_with_the_live_commands_message(cli):
    answers = live_answers(cli, "press-box", ["set fingers.index.no_such=1", "set fingers.index.d0=-1"])
    world = godfinger.World("press-box")
    for line, (field, value) in enumerate([("fingers.index.no_such", 1), ("fingers.index.d0", -1)], 1):
        with pytest.raises(ValueError) as raised:
            world.set(field, value)
        assert answers[line - 1] == f"error: <stdin>:{line}: {raised.value}"


def test_move_and_step_refuse_what_live_refuses(cli):
    answers = live_answers(cli, "press-box", ["move thumb 0 0 0", "step 0"])
    world = godfinger.World("press-box")
    with pytest.raises(ValueError) as raised:
        world.move("thumb", [0, 0, 0])
    assert answers[0] == f"error: <stdin>:1: {raised.value}"
    with pytest.raises(ValueError) as raised:
        world.step(0)
    assert answers[1] == f"error: <stdin>:2: {raised.value}"
    assert world.state()["step"] == 0


def test_snapshot_gives_each_sgos_position_and_load_as_arrays():
    world = godfinger.World("press-box")
    world.step(1000)
    snap = world.snapshot()
    assert snap["step"] == 1000
    (contact,) = snap["fingers"][0]["contacts"]
    assert contact["body"] == "box"
    assert contact["sgos"].shape == (8, 3)
    assert contact["normal_loads"].shape == (8,) and contact["tangential_loads"].shape == (8, 3)
    assert contact["slipping"].dtype == np.bool_
    # The SGOs lie on the box's top face (0.02 m above its centre), within the patch's radius (to
    # 0.1 %: the walk starts from the proxy's point, a micrometre from the contact point) of it.
    (box,) = [b for b in snap["bodies"] if b["name"] == "box"]
    assert contact["sgos"][:, 1] == pytest.approx(box["position"][1] + 0.02, abs=1e-6)
    assert np.linalg.norm(contact["sgos"] - contact["point"], axis=1).max() <= contact["radius"] * 1.001
    # The points' loads add up to the contact's force (sim/scene/snapshot.hpp's PointLoad).
    n = contact["outward_normal"]
    total = (-np.outer(contact["normal_loads"], n) + contact["tangential_loads"]).sum(axis=0)
    total += -contact["point_load"]["normal"] * n + contact["point_load"]["tangential"]
    assert total == pytest.approx(contact["force"], abs=1e-9)
    assert contact["force"][1] < -1.0  # the finger presses the box down


def test_contacts_are_the_live_snapshot_commands_json(cli, tmp_path):
    answers = live_answers(cli, "press-box", ["step 700", "snapshot here"], "--out", str(tmp_path))
    world = godfinger.World("press-box")
    world.step(700)
    written = answers[-1][len("ok "):]
    with open(written, encoding="utf-8") as f:
        assert world.contacts() == json.load(f)


def test_an_unknown_scene_raises_input_error():
    with pytest.raises(godfinger.InputError, match="no-such-scene"):
        godfinger.World("no-such-scene")
