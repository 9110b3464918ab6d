// CSV output for time series (bodies.csv, probe_<name>.csv) and a small reader for tests
// and validation. Numbers are written in their shortest round-trip form (io/number.hpp), so a
// CSV round trip is bitwise. A file may carry its units as a comment line after the header,
//   time,x,vx
//   # units: time [s], x [m], vx [m/s]
// which numpy (genfromtxt names=True, loadtxt skiprows=1) and pandas (comment="#") skip.
#pragma once

#include <cstdio>
#include <filesystem>
#include <initializer_list>
#include <limits>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "particula/io/atomic_file.hpp"
#include "particula/io/error.hpp"

namespace particula::io {

/// Writes a CSV file row by row, flushing each row to the OS so that a killed run keeps
/// every complete row. Throws WriteError (an IoError naming the file and the OS reason) on
/// write failures (disk full, ...).
class CsvWriter {
 public:
  /// Creates (or truncates) `path` and writes the header line and, when `units` is given (one
  /// per column), the units comment line. Column names and units must be non-empty and free of
  /// ',', '"', '[', ']' and line breaks (std::invalid_argument otherwise).
  CsvWriter(const std::filesystem::path& path, std::vector<std::string> columns,
            std::vector<std::string> units = {});

  /// Reopens `path` for a resumed run. The file's header must equal `expected_header`
  /// (IoError naming the file otherwise). A partial last line (no '\n', from a killed run)
  /// is cut off, and so is every row from the first whose first column is > `drop_after`
  /// (rows written after the checkpoint being resumed). A missing or empty file is created
  /// with the header (and the units line when `units` is given). Comment lines are kept.
  static CsvWriter append(const std::filesystem::path& path, std::vector<std::string> expected_header,
                          double drop_after = std::numeric_limits<double>::infinity(),
                          std::vector<std::string> units = {});

  /// Writes one row; it must have one value per column (std::invalid_argument otherwise).
  void row(std::initializer_list<double> values) {
    row(std::span<const double>(values.begin(), values.size()));
  }
  void row(const std::vector<double>& values) { row(std::span<const double>(values)); }
  void row(std::span<const double> values);
  /// Writes several rows at once (values.size() a multiple of the column count), in one write
  /// and one flush. With `stop`, polled every few thousand rows while formatting: when it
  /// returns true nothing is written and io::Cancelled is thrown.
  void rows(std::span<const double> values, const StopCheck& stop = {});

  const std::filesystem::path& path() const { return path_; }
  const std::vector<std::string>& columns() const { return columns_; }
  const std::vector<std::string>& units() const { return units_; }

 private:
  struct FileCloser {
    void operator()(std::FILE* f) const { std::fclose(f); }
  };
  CsvWriter(std::filesystem::path path, std::vector<std::string> columns, std::vector<std::string> units,
            const char* mode);
  void put(std::string_view text);

  std::filesystem::path path_;
  std::vector<std::string> columns_, units_;
  std::unique_ptr<std::FILE, FileCloser> file_;
};

/// A CSV file read back: header names and numeric rows.
struct CsvTable {
  std::filesystem::path source;
  std::vector<std::string> header;
  std::vector<std::string> units;  ///< one per column from a "# units:" line, or empty
  std::vector<std::vector<double>> rows;

  std::size_t size() const { return rows.size(); }
  /// Index of a column; throws IoError naming the file and the column when absent.
  std::size_t column_index(std::string_view name) const;
  /// All values of a column, in row order; throws IoError when the column is absent.
  std::vector<double> column(std::string_view name) const;
};

/// The units comment line of `columns` ("# units: time [s], x [m]"), without a line break.
std::string units_comment(const std::vector<std::string>& columns, const std::vector<std::string>& units);

/// Reads a numeric CSV file: lines starting with '#' and blank lines are skipped (a
/// "# units:" line naming every column in order fills CsvTable::units), the first
/// other line is the header, every cell after it must be a number (inf and nan accepted)
/// and every row must have as many cells as the header. Throws IoError naming the file and
/// line otherwise.
CsvTable read_csv(const std::filesystem::path& path);

}  // namespace particula::io
