"""The type stubs (app/python/godfinger.pyi, installed beside the module) in step with the module:
every public name of the module, and of each of its classes, has a stub entry, and every stub
entry names something the module has."""
import ast
import inspect
import os

import godfinger

STUBS = os.path.join(os.path.dirname(godfinger.__file__), "godfinger.pyi")
# The stub's own helpers: type aliases that are not the module's names.
ALIASES = {"StrPath", "SetValue"}


def public(names):
    return {n for n in names if not n.startswith("_")}


def stub_tree():
    with open(STUBS, encoding="utf-8") as f:
        return ast.parse(f.read())


def stub_names(body):
    """The names a stub body defines: classes, functions, annotated and assigned names."""
    names = set()
    for node in body:
        if isinstance(node, (ast.ClassDef, ast.FunctionDef)):
            names.add(node.name)
        elif isinstance(node, ast.AnnAssign):
            names.add(node.target.id)
        elif isinstance(node, ast.Assign):
            names.update(t.id for t in node.targets)
    return names


def module_names():
    return public(n for n in dir(godfinger) if not inspect.ismodule(getattr(godfinger, n)))


def test_the_stubs_are_installed_beside_the_module():
    assert os.path.isfile(STUBS), STUBS


def test_every_public_name_of_the_module_has_a_stub_and_no_stub_is_left_over():
    stubs = public(stub_names(stub_tree().body)) - ALIASES
    assert module_names() == stubs


def test_every_public_member_of_each_class_has_a_stub_and_no_stub_is_left_over():
    classes = {node.name: node for node in stub_tree().body if isinstance(node, ast.ClassDef)}
    for name, node in classes.items():
        cls = getattr(godfinger, name)
        if issubclass(cls, BaseException):
            continue  # InputError: a ValueError and nothing more
        members = public(n for n in vars(cls))
        assert members == public(stub_names(node.body)), name


def test_each_stub_method_takes_the_parameters_the_module_documents():
    """The keyword names a stub gives are the module's: a call by keyword as the stub says works."""
    world = godfinger.World(scene="press-box", set={})
    world.step(n=2)
    assert world.move(finger="index", xyz=[0, 0.05, 0], seconds=0.0).startswith("index to")
    world.set(field="fingers.index.n_sgo", value=4)
    world.restore(state=world.save())
    run = godfinger.run(scene="press-box", duration=0.01, set={}, out=None, close_ups=False)
    assert run.steps == 10
