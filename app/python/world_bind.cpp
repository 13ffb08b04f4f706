// godfinger.World and godfinger.State bound to Python (world.hpp). Every method reaches its World
// through `initialised`: an object made by World.__new__ alone raises instead of crashing, and a
// second __init__ raises instead of being ignored (pybind11 ignores it, leaving the first world).
// pybind11 would hand such an object's method uninitialised memory (it allocates the C++ object
// lazily, and constructs it only in __init__), so `self` is checked for a constructed holder
// before it is cast.
#include <pybind11/stl.h>

#include <stdexcept>
#include <utility>

#include "app/python/convert.hpp"
#include "app/python/module.hpp"
#include "app/python/world.hpp"

namespace gf::app::python {
namespace {

using namespace pybind11::literals;

// `self`, a World or a subclass's object, has run __init__ (its holder, and so the World, constructed).
bool isInitialised(const py::handle& self) {
  auto* instance = reinterpret_cast<py::detail::instance*>(self.ptr());
  return instance->get_value_and_holder(py::detail::get_type_info(typeid(World))).holder_constructed();
}

// The World of a method's `self`: TypeError for another type, RuntimeError when uninitialised.
World& initialised(const py::handle& self) {
  if (!py::isinstance<World>(self)) {
    throw py::type_error("expected a godfinger.World, got " + py::str(py::type::of(self).attr("__name__")).cast<std::string>());
  }
  if (!isInitialised(self)) throw std::runtime_error("godfinger.World: not initialised (made by World.__new__ without __init__)");
  return self.cast<World&>();
}

// A member function of World as a Python method whose `self` may be uninitialised.
template <typename R, typename... A>
auto method(R (World::*f)(A...)) {
  return [f](const py::handle& self, A... a) -> R { return (initialised(self).*f)(std::forward<A>(a)...); };
}

// Replaces pybind11's __init__ by one that refuses an initialised `self`, then calls it. Named
// otherwise than __init__ for pybind11, which would take it for a constructor and skip it, as it
// does pybind11's own, for a `self` already made.
void refuseSecondInit(py::class_<World>& cls) {
  py::object construct = cls.attr("__init__");
  cls.attr("__init__") = py::cpp_function(
      [construct](const py::handle& self, const py::args& args, const py::kwargs& kwargs) {
        if (py::isinstance<World>(self) && isInitialised(self)) {
          throw std::runtime_error("godfinger.World: already initialised (a second __init__; make a new World)");
        }
        construct(self, *args, **kwargs);
      },
      py::name("init_once"), py::is_method(cls),
      "World(scene, *, set={}): loads a scene (a bundled scene's name, or a file as str or os.PathLike) with "
      "set={field: value} as --set");
}

void bindState(py::module_& m) {
  py::class_<SavedState>(m, "State", "A World's point in time (World.save()), for World.restore(); not picklable")
      .def_readonly("t", &SavedState::time, "Simulated time when saved (s)")
      .def_readonly("step", &SavedState::step, "Haptic steps from the scene's start when saved")
      .def("__repr__", [](const SavedState& s) {
        return "<godfinger.State " + s.origin->start.scene.name + " at t=" + shortestNumber(s.time) + " s>";
      });
}

void bindLifetime(py::class_<World>& cls) {
  cls.def("close", method(&World::close), "Ends the session and frees its world; closing again does nothing")
      .def_property_readonly("closed", [](const py::handle& self) { return initialised(self).closed(); }, "close() has run")
      .def("__enter__", [](const py::object& self) {
        initialised(self).requireOpen();
        return self;
      })
      .def("__exit__", [](const py::handle& self, const py::args&) {
        initialised(self).close();
        return false;
      })
      .def("reset", method(&World::reset), "Back to the scene's start, with the settings the World was made with")
      .def("save", method(&World::save), "The world's point in time, as a godfinger.State for restore()")
      .def("restore", method(&World::restore), "state"_a,
           "Back to a State this World saved: later steps are bit for bit those after save()");
}

void bindSteering(py::class_<World>& cls) {
  cls.def("step", method(&World::step), "n"_a = 1,
          "n haptic steps (1 / haptic_rate_hz each); Ctrl-C interrupts it at a whole step")
      .def("state", method(&World::state), "The live `state` answer as a dict")
      .def("arrays", method(&World::arrays),
           "The state as numpy arrays: body_position (B, 3), body_orientation (B, 4: x y z w), body_velocity, "
           "body_angular_velocity, finger_proxy (F, 3), finger_device, finger_force, finger_feedback, finger_n_sgo (F,), "
           "t, step")
      .def("move", method(&World::move), "finger"_a, "xyz"_a, "seconds"_a = 0.0,
           "The finger's device to xyz (m), straight, over `seconds`; returns the answer")
      .def("set", method(&World::set), "field"_a, "value"_a, "A live finger setting: set('fingers.NAME.FIELD', value)")
      .def("snapshot", method(&World::snapshot), "The world now, with each contact's SGOs and loads as numpy arrays")
      .def("contacts", method(&World::contacts), "The contacts JSON of `live`'s snapshot command, as Python objects");
}

}  // namespace

void bindWorld(py::module_& m) {
  bindState(m);
  py::class_<World> cls(m, "World", "A scene's world, stepped and steered as `godfinger live` does");
  cls.def(py::init<const py::object&, const py::dict&>(), "scene"_a, py::kw_only(), "set"_a = py::dict());
  refuseSecondInit(cls);
  bindLifetime(cls);
  bindSteering(cls);
  cls.def_property_readonly("t", method(&World::time), "Simulated time (s)")
      .def_property_readonly("fingers", [](const py::handle& self) { return initialised(self).names(true); }, "The fingers' names")
      .def_property_readonly("bodies", [](const py::handle& self) { return initialised(self).names(false); }, "The bodies' names")
      .def("__repr__", [](const py::handle& self) {
        if (py::isinstance<World>(self) && !isInitialised(self)) return std::string("<godfinger.World (not initialised)>");
        return initialised(self).repr();
      });
}

}  // namespace gf::app::python
