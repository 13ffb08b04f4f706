// The Python module's conversions: keyword arguments into the command line's forms, a run's
// files and a world's snapshots into Python objects (dicts, lists, numpy arrays).
#pragma once

#include <pybind11/pybind11.h>

#include <string>
#include <vector>

#include "app/runs/run_reader.hpp"
#include "sim/scene/scene_desc.hpp"
#include "sim/scene/snapshot.hpp"

namespace gf::app::python {

namespace py = pybind11;

/// `set={"fingers.left.n_sgo": 0, ...}` as --set texts ("fingers.left.n_sgo=0"): numbers in
/// their shortest round-trip form, booleans as true/false, strings as given (--set reads a value
/// that is not TOML as a string), lists and tuples as TOML arrays. Throws InputError naming the
/// key for a value of another type.
std::vector<std::string> overridesFromDict(const py::dict& set);

/// A path argument (`what` names it in errors) as text: a str, bytes or os.PathLike (pathlib.Path),
/// as os.fsencode gives its bytes. Throws TypeError for another type, ValueError for a NUL byte.
std::string pathText(const py::handle& value, const std::string& what);

/// The shortest decimal that reads back as exactly `x`.
std::string shortestNumber(double x);

/// A CSV file of numbers (trace.csv) as {column: float64 numpy array}, in the file's order.
py::dict columnsDict(const CsvTable& table);

/// A CSV file with text (a study's results.csv) as {column: numpy array}, in the file's order: a
/// column whose cells all read as numbers becomes float64 (read back exactly: the files hold
/// shortest round-trip decimals), any other an array of str.
py::dict columnsDict(const CsvText& table);

/// A JSON value (summary.json, a contact snapshot) as Python objects: what json.loads gives for
/// its dump (a number that is not finite, which dump writes as null, as None), without the text.
py::object jsonObject(const nlohmann::json& value);

/// A world's snapshot with per-SGO arrays: time, step; per finger its device, proxy, forces, SGO
/// count and contacts, each contact's SGO positions (N x 3), the solver's loads on them (normal
/// N, tangential N x 3, slipping N) and its whole force; per body its pose and velocities.
py::dict snapshotDict(const sim::Snapshot& snapshot, const sim::SceneDesc& scene);

}  // namespace gf::app::python
