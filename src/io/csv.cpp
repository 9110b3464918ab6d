// CSV writer (flushed per row, resumable) and reader.
#include "particula/io/csv.hpp"

#include <fmt/format.h>

#include <cerrno>
#include <charconv>
#include <cstring>
#include <iterator>
#include <stdexcept>

#include "particula/io/atomic_file.hpp"
#include "particula/io/number.hpp"

namespace particula::io {
namespace {

std::string join(const std::vector<std::string>& cells) {
  std::string s;
  for (std::size_t i = 0; i < cells.size(); ++i) {
    if (i > 0) s += ',';
    s += cells[i];
  }
  return s;
}

void check_columns(const std::vector<std::string>& columns) {
  if (columns.empty()) throw std::invalid_argument("CsvWriter: no columns");
  for (const auto& c : columns)
    if (c.empty() || c.find_first_of(",\"[]\r\n") != std::string::npos)
      throw std::invalid_argument(fmt::format("CsvWriter: invalid column name '{}'", c));
}

/// Units are optional (empty), else one per column, each non-empty and free of separators.
void check_units(const std::vector<std::string>& columns, const std::vector<std::string>& units) {
  if (units.empty()) return;
  if (units.size() != columns.size())
    throw std::invalid_argument(
        fmt::format("CsvWriter: {} units for {} columns", units.size(), columns.size()));
  for (const auto& u : units)
    if (u.empty() || u.find_first_of(",\"[]\r\n") != std::string::npos)
      throw std::invalid_argument(fmt::format("CsvWriter: invalid unit '{}'", u));
}

/// The header text written to a new file: the column names and, with units, the units line.
std::string header_text(const std::vector<std::string>& columns, const std::vector<std::string>& units) {
  std::string text = join(columns) + "\n";
  if (!units.empty()) text += units_comment(columns, units) + "\n";
  return text;
}

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r')) s.remove_suffix(1);
  return s;
}

/// Splits a line at commas, trimming each cell.
std::vector<std::string_view> split(std::string_view line) {
  std::vector<std::string_view> cells;
  for (std::size_t start = 0;;) {
    const std::size_t comma = line.find(',', start);
    cells.push_back(trim(line.substr(start, comma == std::string_view::npos ? comma : comma - start)));
    if (comma == std::string_view::npos) return cells;
    start = comma + 1;
  }
}

/// Parses a whole cell as a double; false when it is not one number.
bool parse_number(std::string_view s, double& v) {
  if (s.empty()) return false;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  return ec == std::errc() && end == s.data() + s.size();
}

bool skipped(std::string_view line) { return trim(line).empty() || line.front() == '#'; }

/// The units of a "# units: name [unit], ..." comment when it names exactly `header`, else empty.
std::vector<std::string> parse_units_comment(std::string_view line, const std::vector<std::string>& header) {
  constexpr std::string_view kPrefix = "# units:";
  if (!line.starts_with(kPrefix)) return {};
  const auto cells = split(line.substr(kPrefix.size()));
  if (cells.size() != header.size()) return {};
  std::vector<std::string> units;
  for (std::size_t j = 0; j < cells.size(); ++j) {
    const std::size_t open = cells[j].find(" [");
    if (open == std::string_view::npos || cells[j].back() != ']' || cells[j].substr(0, open) != header[j]) return {};
    units.emplace_back(cells[j].substr(open + 2, cells[j].size() - open - 3));
  }
  return units;
}

/// The length to keep of an existing CSV file being appended to, after checking its header:
/// complete lines only, and no row after `drop_after`. npos when the file holds no header line.
std::size_t kept_length(const std::filesystem::path& path, std::string_view text, const std::string& header,
                        double drop_after) {
  bool have_header = false;
  for (std::size_t start = 0; start < text.size();) {
    const std::size_t nl = text.find('\n', start);
    if (nl == std::string_view::npos) return have_header ? start : std::string_view::npos;  // partial line
    const std::string_view line = text.substr(start, nl - start);
    if (!skipped(line) && !have_header) {
      if (trim(line) != header)
        throw IoError(fmt::format("cannot append to '{}': its header '{}' differs from the expected '{}'",
                                  path.string(), trim(line), header));
      have_header = true;
    } else if (!skipped(line)) {
      double first = 0;
      if (parse_number(split(line).front(), first) && first > drop_after) return start;
    }
    start = nl + 1;
  }
  return have_header ? text.size() : std::string_view::npos;
}

}  // namespace

std::string units_comment(const std::vector<std::string>& columns, const std::vector<std::string>& units) {
  std::string text = "# units:";
  for (std::size_t j = 0; j < columns.size() && j < units.size(); ++j)
    text += fmt::format("{} {} [{}]", j ? "," : "", columns[j], units[j]);
  return text;
}

CsvWriter::CsvWriter(std::filesystem::path path, std::vector<std::string> columns, std::vector<std::string> units,
                     const char* mode)
    : path_(std::move(path)), columns_(std::move(columns)), units_(std::move(units)) {
  check_columns(columns_);
  check_units(columns_, units_);
  file_.reset(std::fopen(path_.c_str(), mode));
  if (!file_)
    throw WriteError(fmt::format("cannot open '{}' for writing: {}", path_.string(), std::strerror(errno)));
}

CsvWriter::CsvWriter(const std::filesystem::path& path, std::vector<std::string> columns,
                     std::vector<std::string> units)
    : CsvWriter(path, std::move(columns), std::move(units), "wb") {
  put(header_text(columns_, units_));
}

CsvWriter CsvWriter::append(const std::filesystem::path& path, std::vector<std::string> expected_header,
                            double drop_after, std::vector<std::string> units) {
  check_columns(expected_header);
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) return CsvWriter(path, std::move(expected_header), std::move(units));
  const std::string text = read_file(path);
  const std::size_t keep = kept_length(path, text, join(expected_header), drop_after);
  if (keep == std::string::npos)  // no header yet
    return CsvWriter(path, std::move(expected_header), std::move(units));
  if (keep < text.size()) {
    std::filesystem::resize_file(path, keep, ec);
    if (ec) throw WriteError(fmt::format("cannot truncate '{}': {}", path.string(), ec.message()));
  }
  return CsvWriter(path, std::move(expected_header), std::move(units), "ab");
}

void CsvWriter::row(std::span<const double> values) {
  if (values.size() != columns_.size())
    throw std::invalid_argument(fmt::format("CsvWriter '{}': row of {} values for {} columns", path_.string(),
                                            values.size(), columns_.size()));
  rows(values);
}

void CsvWriter::rows(std::span<const double> values, const StopCheck& stop) {
  const std::size_t nc = columns_.size();
  if (values.size() % nc != 0)
    throw std::invalid_argument(fmt::format("CsvWriter '{}': {} values are not whole rows of {} columns",
                                            path_.string(), values.size(), nc));
  constexpr std::size_t kRowsPerPoll = 4096;
  std::string text;
  text.reserve(values.size() * 12);
  for (std::size_t r = 0; r * nc < values.size(); ++r) {
    if (stop && r % kRowsPerPoll == 0 && stop()) throw Cancelled();
    for (std::size_t i = 0; i < nc; ++i) {
      if (i) text.push_back(',');
      append_shortest(text, values[r * nc + i]);
    }
    text.push_back('\n');
  }
  put(text);
}

void CsvWriter::put(std::string_view text) {
  errno = 0;
  if (std::fwrite(text.data(), 1, text.size(), file_.get()) != text.size() || std::fflush(file_.get()) != 0) {
    const int err = errno ? errno : EIO;
    std::clearerr(file_.get());
    throw WriteError(fmt::format("cannot write '{}': {}", path_.string(), std::strerror(err)));
  }
}

std::size_t CsvTable::column_index(std::string_view name) const {
  for (std::size_t i = 0; i < header.size(); ++i)
    if (header[i] == name) return i;
  throw IoError(fmt::format("'{}' has no column '{}'", source.string(), name));
}

std::vector<double> CsvTable::column(std::string_view name) const {
  const std::size_t j = column_index(name);
  std::vector<double> v;
  v.reserve(rows.size());
  for (const auto& r : rows) v.push_back(r[j]);
  return v;
}

CsvTable read_csv(const std::filesystem::path& path) {
  const std::string text = read_file(path);
  CsvTable t;
  t.source = path;
  bool have_header = false;
  std::size_t line_no = 0;
  for (std::size_t start = 0; start < text.size(); ++line_no) {
    std::size_t nl = text.find('\n', start);
    if (nl == std::string::npos) nl = text.size();
    const std::string_view line = std::string_view(text).substr(start, nl - start);
    start = nl + 1;
    if (skipped(line)) {
      if (have_header && t.units.empty()) t.units = parse_units_comment(line, t.header);
      continue;
    }
    const auto cells = split(line);
    if (!have_header) {
      for (const auto c : cells) t.header.emplace_back(c);
      have_header = true;
      continue;
    }
    if (cells.size() != t.header.size())
      throw IoError(fmt::format("'{}' line {}: {} cells, expected {}", path.string(), line_no + 1,
                                cells.size(), t.header.size()));
    auto& row = t.rows.emplace_back(cells.size());
    for (std::size_t j = 0; j < cells.size(); ++j)
      if (!parse_number(cells[j], row[j]))
        throw IoError(fmt::format("'{}' line {}: '{}' in column '{}' is not a number", path.string(),
                                  line_no + 1, cells[j], t.header[j]));
  }
  if (!have_header) throw IoError(fmt::format("'{}' has no header line", path.string()));
  return t;
}

}  // namespace particula::io
