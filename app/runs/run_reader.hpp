// Reading a run folder back (app/runs/run_folder.hpp names its files): the one reader of
// trace.csv (and any CSV of numbers with a header row), summary.json, contact snapshots and a
// child run's log, for plot, check, compare and the studies.
#pragma once

#include <nlohmann/json.hpp>

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace gf::app {

/// The cells of one line of a table split at `separator` (',' for CSV, '\t' for TSV), a trailing
/// carriage return dropped. Views into `line`.
std::vector<std::string_view> splitCells(std::string_view line, char separator);

/// A CSV file of numbers under a header row (trace.csv, forces.csv): every column.
struct CsvTable {
  std::string path;
  std::vector<std::string> names;            ///< the header row
  std::vector<std::vector<double>> columns;  ///< one per name, a value per row (an empty cell: NaN)

  /// The column `name`. Throws InputError naming the file and the columns it has.
  const std::vector<double>& column(const std::string& name) const;
};

/// Reads `path`: the columns `only` (in the file's order), or every column when `only` is empty;
/// other columns may hold anything. Throws InputError naming the file (and the line, column and
/// field of a cell that is not a number): a folder, an unreadable or empty file, a column of
/// `only` the header lacks.
CsvTable readCsv(const std::string& path, const std::vector<std::string>& only = {});

/// The columns `names` of the CSV at `path`, in that order. Throws as readCsv and CsvTable::column.
std::vector<std::vector<double>> readCsvColumns(const std::string& path, const std::vector<std::string>& names);

/// A CSV file as text: the header row and every row's cells, for files with text columns (a
/// study's results.csv). A cell in double quotes may hold commas and doubled quotes.
struct CsvText {
  std::string path;
  std::vector<std::string> names;              ///< the header row
  std::vector<std::vector<std::string>> rows;  ///< as many cells as names each
};

/// Reads `path`. Throws InputError naming the file, and the line of a row whose cells do not
/// match the header's count.
CsvText readCsvText(const std::string& path);

/// The trace.csv of the run in `dir`. Throws InputError as readCsv.
CsvTable readTrace(const std::filesystem::path& dir);

/// The summary.json of the run in `dir`, or null when it is missing or not JSON (a run that
/// failed before writing it).
nlohmann::json readSummary(const std::filesystem::path& dir);

/// The summary.json of the run in `dir`. Throws std::runtime_error naming the file when it is
/// missing ("did the run finish?") or not JSON.
nlohmann::json requireSummary(const std::filesystem::path& dir);

/// The contact snapshot the run in `dir` took at `t` seconds (contacts/t0.500.json). Throws
/// std::runtime_error naming the file when it is missing or not JSON.
nlohmann::json readContacts(const std::filesystem::path& dir, double t);

/// The contact snapshots the run in `dir` took (contacts/*.json), sorted by name.
std::vector<std::filesystem::path> contactFiles(const std::filesystem::path& dir);

/// The JSON file at `path`. Throws std::runtime_error naming the file when it is missing or not
/// JSON.
nlohmann::json readJsonFile(const std::filesystem::path& path);

/// The last line a child run wrote into dir/run.log (a progress line's carriage returns
/// dropped), "" when there is none: what to show for a run that failed.
std::string lastLogLine(const std::filesystem::path& dir);

}  // namespace gf::app
