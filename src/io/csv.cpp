// CSV writer (flushed per row, resumable) and reader.
#include "particula/io/csv.hpp"

#include <fmt/format.h>

#include <cerrno>
#include <charconv>
#include <cstring>
#include <iterator>
#include <stdexcept>

#include "particula/io/atomic_file.hpp"

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
    if (c.empty() || c.find_first_of(",\"\r\n") != std::string::npos)
      throw std::invalid_argument(fmt::format("CsvWriter: invalid column name '{}'", c));
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

CsvWriter::CsvWriter(std::filesystem::path path, std::vector<std::string> columns, const char* mode)
    : path_(std::move(path)), columns_(std::move(columns)) {
  check_columns(columns_);
  file_.reset(std::fopen(path_.c_str(), mode));
  if (!file_)
    throw WriteError(fmt::format("cannot open '{}' for writing: {}", path_.string(), std::strerror(errno)));
}

CsvWriter::CsvWriter(const std::filesystem::path& path, std::vector<std::string> columns)
    : CsvWriter(path, std::move(columns), "wb") {
  put(join(columns_) + "\n");
}

CsvWriter CsvWriter::append(const std::filesystem::path& path, std::vector<std::string> expected_header,
                            double drop_after) {
  check_columns(expected_header);
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) return CsvWriter(path, std::move(expected_header));
  const std::string text = read_file(path);
  const std::size_t keep = kept_length(path, text, join(expected_header), drop_after);
  if (keep == std::string::npos) return CsvWriter(path, std::move(expected_header));  // no header yet
  if (keep < text.size()) {
    std::filesystem::resize_file(path, keep, ec);
    if (ec) throw WriteError(fmt::format("cannot truncate '{}': {}", path.string(), ec.message()));
  }
  return CsvWriter(path, std::move(expected_header), "ab");
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
  fmt::memory_buffer text;
  for (std::size_t r = 0; r * nc < values.size(); ++r) {
    if (stop && r % kRowsPerPoll == 0 && stop()) throw Cancelled();
    for (std::size_t i = 0; i < nc; ++i) fmt::format_to(std::back_inserter(text), "{}{}", i ? "," : "", values[r * nc + i]);
    text.push_back('\n');
  }
  put(std::string_view(text.data(), text.size()));
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
    if (skipped(line)) continue;
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
