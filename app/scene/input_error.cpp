#include "app/scene/input_error.hpp"

namespace gf::app {
std::string InputError::message(const std::string& file, int line, int column,
                                const std::string& field, const std::string& reason) {
  std::string m = file;
  if (line > 0) {
    m.append(":").append(std::to_string(line));
    if (column > 0) m.append(":").append(std::to_string(column));
  }
  m.append(": ");
  if (!field.empty()) m.append(field).append(": ");
  m.append(reason);
  return m;
}

InputError::InputError(const std::string& file, int line, int column, const std::string& field,
                       const std::string& reason)
    : std::runtime_error(message(file, line, column, field, reason)),
      file_(file),
      line_(line),
      column_(column),
      field_(field),
      reason_(reason) {}

InputError commandLineError(const std::string& option, const std::string& reason) {
  return InputError("command line", 0, 0, option, reason);
}

}  // namespace gf::app
