// Bad input (scene files, study files, meshes, command-line values): an exception naming the
// file, line, column and field, so every reader reports errors the same way.
#pragma once

#include <stdexcept>
#include <string>

namespace gf::app {

/// Bad input: what() reads "FILE:LINE:COLUMN: FIELD: reason" (line and column when known).
class InputError : public std::runtime_error {
 public:
  InputError(const std::string& file, int line, int column, const std::string& field,
             const std::string& reason);
  const std::string& file() const { return file_; }
  int line() const { return line_; }
  const std::string& field() const { return field_; }
  int column() const { return column_; }
  const std::string& reason() const { return reason_; }

 private:
  static std::string message(const std::string& file, int line, int column, const std::string& field,
                             const std::string& reason);
  std::string file_;
  int line_;
  int column_;
  std::string field_;
  std::string reason_;
};

/// Bad input given on the command line: what() reads "command line: OPTION: reason".
InputError commandLineError(const std::string& option, const std::string& reason);

}  // namespace gf::app
