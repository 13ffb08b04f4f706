#include "app/runs/run_reader.hpp"

#include <algorithm>
#include <charconv>
#include <fstream>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "app/runs/run_folder.hpp"
#include "app/scene/input_error.hpp"

namespace gf::app {

std::vector<std::string_view> splitCells(std::string_view line, char separator) {
  if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
  std::vector<std::string_view> cells;
  for (std::size_t a = 0;;) {
    const std::size_t b = line.find(separator, a);
    cells.push_back(line.substr(a, b == std::string_view::npos ? std::string_view::npos : b - a));
    if (b == std::string_view::npos) return cells;
    a = b + 1;
  }
}

namespace {

namespace fs = std::filesystem;

// The cells of one CSV line.
std::vector<std::string_view> splitRow(std::string_view line) { return splitCells(line, ','); }

// A cell as a number: an empty or missing cell is a gap (NaN). Throws InputError naming it.
double cellValue(const CsvTable& t, const std::vector<std::string_view>& cells, std::size_t c, int row) {
  std::string_view cell = c < cells.size() ? cells[c] : std::string_view();
  while (!cell.empty() && (cell.front() == ' ' || cell.front() == '\t')) cell.remove_prefix(1);
  while (!cell.empty() && (cell.back() == ' ' || cell.back() == '\t')) cell.remove_suffix(1);
  if (cell.empty()) return std::numeric_limits<double>::quiet_NaN();
  const char* begin = cell.data() + (cell.front() == '+' ? 1 : 0);
  double v = 0.0;
  const auto [end, ec] = std::from_chars(begin, cell.data() + cell.size(), v);
  if (ec != std::errc() || end != cell.data() + cell.size()) {
    throw InputError(t.path, row, static_cast<int>(c) + 1, t.names[c], "expected a number, got '" + std::string(cell) + "'");
  }
  return v;
}

// The index of column `name` in `names`. Throws InputError naming the file and the columns it has.
std::size_t columnIndex(const std::string& path, const std::vector<std::string>& names, const std::string& name) {
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (names[i] == name) return i;
  }
  std::string known;
  for (const std::string& n : names) known.append(known.empty() ? "" : ", ").append(n);
  throw InputError(path, 1, 0, name, "no such column (the file has: " + known + ")");
}

std::string readText(const fs::path& path, const std::string& missing) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error(path.string() + ": " + missing);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// The cells of one CSV line with quoting: a cell in double quotes may hold commas and doubled
// quotes (a trailing carriage return dropped).
std::vector<std::string> quotedCells(std::string_view line) {
  if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
  std::vector<std::string> cells(1);
  bool quoted = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quoted && c == '"' && i + 1 < line.size() && line[i + 1] == '"') {
      cells.back() += '"';
      ++i;
    } else if (c == '"') {
      quoted = !quoted;
    } else if (c == ',' && !quoted) {
      cells.emplace_back();
    } else {
      cells.back() += c;
    }
  }
  return cells;
}

// The open file at `path` and its header line. Throws InputError naming the file.
std::ifstream openCsv(const std::string& path, std::string& header) {
  if (fs::is_directory(path)) throw InputError(path, 0, 0, "file", "is a folder; give a CSV file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, 0, 0, "file", "cannot read");
  if (!std::getline(in, header)) throw InputError(path, 1, 0, "header", "empty file: expected a header row");
  return in;
}

nlohmann::json parseJson(const fs::path& path) {
  const std::string text = readText(path, "missing (did the run finish?)");
  try {
    return nlohmann::json::parse(text);
  } catch (const nlohmann::json::exception& e) {
    throw std::runtime_error(path.string() + ": " + e.what());
  }
}

}  // namespace

const std::vector<double>& CsvTable::column(const std::string& name) const {
  return columns[columnIndex(path, names, name)];
}

CsvTable readCsv(const std::string& path, const std::vector<std::string>& only) {
  std::string line;
  std::ifstream in = openCsv(path, line);
  CsvTable header{path, {}, {}};
  for (std::string_view name : splitRow(line)) header.names.emplace_back(name);
  for (const std::string& name : only) columnIndex(path, header.names, name);  // fails naming the ones there are
  // The columns read: their file positions, and the table with only those.
  CsvTable t{path, {}, {}};
  std::vector<std::size_t> read;
  for (std::size_t c = 0; c < header.names.size(); ++c) {
    if (!only.empty() && std::find(only.begin(), only.end(), header.names[c]) == only.end()) continue;
    read.push_back(c);
    t.names.push_back(header.names[c]);
  }
  t.columns.resize(read.size());
  for (int row = 2; std::getline(in, line); ++row) {
    if (line.empty() || line == "\r") continue;
    const std::vector<std::string_view> cells = splitRow(line);
    for (std::size_t k = 0; k < read.size(); ++k) t.columns[k].push_back(cellValue(header, cells, read[k], row));
  }
  return t;
}

std::vector<std::vector<double>> readCsvColumns(const std::string& path, const std::vector<std::string>& names) {
  const CsvTable t = readCsv(path, names);
  std::vector<std::vector<double>> out;
  for (const std::string& n : names) out.push_back(t.column(n));  // a column may be asked for twice
  return out;
}

CsvText readCsvText(const std::string& path) {
  std::string line;
  std::ifstream in = openCsv(path, line);
  CsvText t{path, quotedCells(line), {}};
  for (int row = 2; std::getline(in, line); ++row) {
    if (line.empty() || line == "\r") continue;
    t.rows.push_back(quotedCells(line));
    if (t.rows.back().size() != t.names.size()) {
      throw InputError(path, row, 0, "row", "expected " + std::to_string(t.names.size()) + " cells, got " +
                                               std::to_string(t.rows.back().size()));
    }
  }
  return t;
}

CsvTable readTrace(const fs::path& dir) { return readCsv((dir / kTraceFile).string()); }

nlohmann::json readSummary(const fs::path& dir) {
  try {
    return requireSummary(dir);
  } catch (const std::runtime_error&) {
    return nullptr;
  }
}

nlohmann::json requireSummary(const fs::path& dir) { return parseJson(dir / kSummaryFile); }

nlohmann::json readContacts(const fs::path& dir, double t) {
  return parseJson(dir / kContactsFolder / (contactStem(t) + ".json"));
}

std::vector<fs::path> contactFiles(const fs::path& dir) {
  std::vector<fs::path> files;
  if (!fs::is_directory(dir / kContactsFolder)) return files;
  for (const fs::directory_entry& e : fs::directory_iterator(dir / kContactsFolder)) {
    if (e.path().extension() == ".json") files.push_back(e.path());
  }
  std::sort(files.begin(), files.end());
  return files;
}

nlohmann::json readJsonFile(const fs::path& path) { return parseJson(path); }

std::string lastLogLine(const fs::path& dir) {
  std::ifstream in(dir / kRunLogFile);
  std::string line, last;
  while (std::getline(in, line)) {
    // Progress lines end in carriage returns: keep the text after the last one.
    const std::size_t cr = line.find_last_of('\r');
    const std::string text = cr == std::string::npos ? line : line.substr(cr + 1);
    if (!text.empty()) last = text;
  }
  return last;
}

}  // namespace gf::app
