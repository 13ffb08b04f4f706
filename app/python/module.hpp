// The Python module `godfinger` (pybind11): run(), World, study() and InputError. See
// docs/python.md for the API; module.cpp holds the module's definition.
#pragma once

#include <pybind11/pybind11.h>

namespace gf::app::python {

/// Adds godfinger.World (world.cpp).
void bindWorld(pybind11::module_& m);

}  // namespace gf::app::python
