#include "app/python/convert.hpp"

#include <pybind11/numpy.h>

#include <charconv>
#include <cmath>
#include <cstdint>
#include <stdexcept>

#include "app/runs/files.hpp"
#include "app/scene/input_error.hpp"

namespace gf::app::python {

using namespace pybind11::literals;

namespace {

// One --set value in TOML syntax (the scene reader takes text that is not TOML as a string).
std::string tomlValue(const py::handle& value, const std::string& key, bool in_array) {
  if (py::isinstance<py::bool_>(value)) return value.cast<bool>() ? "true" : "false";
  if (py::isinstance<py::int_>(value)) return py::str(value).cast<std::string>();
  if (py::isinstance<py::float_>(value)) return shortestNumber(value.cast<double>());
  // numpy's scalars: its integers have __index__, its floats __float__.
  if (py::hasattr(value, "__index__")) return py::str(value.attr("__index__")()).cast<std::string>();
  if (py::hasattr(value, "__float__") && !py::isinstance<py::str>(value)) {
    return shortestNumber(value.attr("__float__")().cast<double>());
  }
  if (py::isinstance<py::str>(value)) {
    const std::string text = value.cast<std::string>();
    // Inside an array a string needs its quotes; JSON's escapes are TOML's basic string's.
    return in_array ? py::module_::import("json").attr("dumps")(text).cast<std::string>() : text;
  }
  if (py::isinstance<py::list>(value) || py::isinstance<py::tuple>(value)) {
    std::string out = "[";
    for (const py::handle item : value) out += (out.size() > 1 ? ", " : "") + tomlValue(item, key, true);
    return out + "]";
  }
  throw InputError("set", 0, 0, key,
                   "expected a number, a boolean, a string or a list, got " +
                       py::str(py::type::of(value).attr("__name__")).cast<std::string>());
}

bool readNumber(const std::string& text, double& x) {
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), x);
  return ec == std::errc() && end == text.data() + text.size() && !text.empty();
}

// One column as float64 when every cell is a number, else as str.
py::object columnArray(const std::vector<std::vector<std::string>>& rows, std::size_t c) {
  py::array_t<double> numbers(static_cast<py::ssize_t>(rows.size()));
  double* x = numbers.mutable_data();
  for (std::size_t r = 0; r < rows.size(); ++r) {
    if (!readNumber(rows[r][c], x[r])) {
      py::list cells;
      for (const std::vector<std::string>& row : rows) cells.append(row[c]);
      return py::module_::import("numpy").attr("array")(cells, "dtype"_a = "str");
    }
  }
  return numbers;
}

py::array_t<double> vec3(const sim::Vec3& v) {
  py::array_t<double> a(3);
  for (int i = 0; i < 3; ++i) a.mutable_data()[i] = v[i];
  return a;
}

py::array_t<double> points(const std::vector<sim::Vec3>& v) {
  py::array_t<double> a({static_cast<py::ssize_t>(v.size()), py::ssize_t{3}});
  double* x = a.mutable_data();
  for (const sim::Vec3& p : v) {
    for (int i = 0; i < 3; ++i) *x++ = p[i];
  }
  return a;
}

py::dict loadDict(const sim::PointLoad& load) {
  return py::dict("normal"_a = load.normal, "tangential"_a = vec3(load.tangential), "slipping"_a = load.slipping);
}

py::dict contactDict(const sim::ContactSnapshot& c, const sim::SceneDesc& scene) {
  const auto n = static_cast<py::ssize_t>(c.loads.size());
  py::array_t<double> normal(n), tangential({n, py::ssize_t{3}});
  py::array_t<bool> slipping(n);
  for (py::ssize_t k = 0; k < n; ++k) {
    const sim::PointLoad& l = c.loads[static_cast<std::size_t>(k)];
    normal.mutable_data()[k] = l.normal;
    slipping.mutable_data()[k] = l.slipping;
    for (int i = 0; i < 3; ++i) tangential.mutable_data()[3 * k + i] = l.tangential[i];
  }
  return py::dict("body"_a = scene.bodies[static_cast<std::size_t>(c.body)].name, "point"_a = vec3(c.point_world),
                  "outward_normal"_a = vec3(c.outward_normal_world), "separation"_a = c.separation,
                  "press_depth"_a = c.press_depth, "radius"_a = c.radius, "sgos"_a = points(c.sgos_world),
                  "normal_loads"_a = normal, "tangential_loads"_a = tangential, "slipping"_a = slipping,
                  "force"_a = vec3(c.force), "point_load"_a = loadDict(c.point_load),
                  "rolling_moment"_a = vec3(c.rolling_moment),
                  "torsion_moment"_a = vec3(c.torsion_moment), "sliding"_a = c.sliding);
}

}  // namespace

std::string shortestNumber(double x) {
  std::string s;
  appendNumber(s, x);
  return s;
}

std::vector<std::string> overridesFromDict(const py::dict& set) {
  std::vector<std::string> out;
  for (const auto& [key, value] : set) {
    const std::string field = py::str(key).cast<std::string>();
    out.push_back(field + "=" + tomlValue(value, field, false));
  }
  return out;
}

py::dict columnsDict(const CsvTable& table) {
  py::dict out;
  for (std::size_t c = 0; c < table.names.size(); ++c) {
    const std::vector<double>& column = table.columns[c];
    out[py::str(table.names[c])] = py::array_t<double>(static_cast<py::ssize_t>(column.size()), column.data());
  }
  return out;
}

py::dict columnsDict(const CsvText& table) {
  py::dict out;
  for (std::size_t c = 0; c < table.names.size(); ++c) out[py::str(table.names[c])] = columnArray(table.rows, c);
  return out;
}

std::string pathText(const py::handle& value, const std::string& what) {
  const py::module_ os = py::module_::import("os");
  if (!py::isinstance<py::str>(value) && !py::isinstance<py::bytes>(value) && !py::isinstance(value, os.attr("PathLike"))) {
    throw py::type_error(what + ": expected a str or an os.PathLike, got " +
                         py::str(py::type::of(value).attr("__name__")).cast<std::string>());
  }
  const std::string text = os.attr("fsencode")(value).cast<std::string>();
  if (text.find('\0') != std::string::npos) throw py::value_error(what + ": embedded null byte");
  return text;
}

py::object jsonObject(const nlohmann::json& value) {
  switch (value.type()) {
    case nlohmann::json::value_t::object: {
      py::dict out;
      for (const auto& [key, item] : value.items()) out[py::str(key)] = jsonObject(item);
      return out;
    }
    case nlohmann::json::value_t::array: {
      py::list out(value.size());
      for (std::size_t i = 0; i < value.size(); ++i) out[i] = jsonObject(value[i]);
      return out;
    }
    case nlohmann::json::value_t::string: return py::str(value.get_ref<const std::string&>());
    case nlohmann::json::value_t::boolean: return py::bool_(value.get<bool>());
    case nlohmann::json::value_t::number_integer: return py::int_(value.get<std::int64_t>());
    case nlohmann::json::value_t::number_unsigned: return py::int_(value.get<std::uint64_t>());
    case nlohmann::json::value_t::number_float: {
      const double x = value.get<double>();
      return std::isfinite(x) ? py::object(py::float_(x)) : py::object(py::none());
    }
    default: return py::none();  // null, and what JSON text cannot hold
  }
}

py::dict snapshotDict(const sim::Snapshot& snap, const sim::SceneDesc& scene) {
  py::list fingers;
  for (std::size_t i = 0; i < snap.fingers.size() && i < scene.fingers.size(); ++i) {
    const sim::FingerSnapshot& f = snap.fingers[i];
    py::list contacts;
    for (const sim::ContactSnapshot& c : f.contacts) contacts.append(contactDict(c, scene));
    fingers.append(py::dict("name"_a = scene.fingers[i].name, "device"_a = vec3(f.device), "proxy"_a = vec3(f.proxy),
                            "force"_a = vec3(f.coupling_force), "feedback"_a = vec3(f.feedback_force),
                            "n_sgo"_a = f.sgo_count, "contacts"_a = contacts));
  }
  py::list bodies;
  for (std::size_t i = 0; i < scene.bodies.size() && i < snap.bodies.size(); ++i) {
    const sim::Pose& p = snap.bodies[i];
    const sim::Quat& q = p.orientation;
    py::array_t<double> orientation(4);
    for (int k = 0; k < 4; ++k) orientation.mutable_data()[k] = k == 0 ? q.x() : k == 1 ? q.y() : k == 2 ? q.z() : q.w();
    const bool moving = i < snap.body_velocities.size();
    bodies.append(py::dict("name"_a = scene.bodies[i].name, "position"_a = vec3(p.position),
                           "orientation"_a = orientation,
                           "velocity"_a = vec3(moving ? snap.body_velocities[i].first : sim::Vec3::Zero()),
                           "angular_velocity"_a = vec3(moving ? snap.body_velocities[i].second : sim::Vec3::Zero())));
  }
  return py::dict("t"_a = snap.time, "step"_a = snap.step, "fingers"_a = fingers, "bodies"_a = bodies);
}

}  // namespace gf::app::python
