#include "particula/run/run_dir.hpp"

#include <fmt/format.h>
#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <charconv>

#include "particula/io/atomic_file.hpp"

namespace particula {

namespace fs = std::filesystem;

namespace {

/// Whether process `pid` may still be running (then its temporary files are left alone).
bool process_running(long pid) {
  if (pid <= 0) return false;
  if (pid == static_cast<long>(::getpid())) return true;
  return ::kill(static_cast<pid_t>(pid), 0) == 0 || errno == EPERM;
}

bool starts_with(std::string_view s, std::string_view prefix) { return s.substr(0, prefix.size()) == prefix; }
bool ends_with(std::string_view s, std::string_view suffix) {
  return s.size() >= suffix.size() && s.substr(s.size() - suffix.size()) == suffix;
}
bool all_digits(std::string_view s) {
  return !s.empty() && std::all_of(s.begin(), s.end(), [](char c) { return c >= '0' && c <= '9'; });
}

/// A file name particula writes at the top of a run directory (or of its .resume scratch).
bool top_file(std::string_view name) {
  for (const char* known : {kRunMarker, "case.toml", "summary.json", "log.txt", "bodies.csv", "walls.csv",
                            "coefficients.csv", "open_boundaries.csv", "particles.pvd"})
    if (name == known) return true;
  return (starts_with(name, "probe_") && ends_with(name, ".csv") && name.size() > 10) ||
         (starts_with(name, "flow_") && ends_with(name, ".csv") && name.size() > 9);
}

std::string hex(std::uint64_t v) { return fmt::format("{:016x}", v); }

/// `path` as shown in messages.
std::string shown(const fs::path& p) { return p.string(); }

/// `dir` without a trailing separator ("runs/x/" -> "runs/x").
fs::path normalized(const fs::path& dir) {
  fs::path d = dir.lexically_normal();
  if (!d.has_filename() && d.has_parent_path() && d != d.root_path()) d = d.parent_path();
  return d;
}

/// Whether `dir` (existing) is the working directory or one of its parents.
bool holds_working_directory(const fs::path& dir) {
  std::error_code ec;
  const fs::path d = fs::canonical(dir, ec);
  if (ec) return true;  // cannot tell: refuse
  const fs::path cwd = fs::canonical(fs::current_path(ec), ec);
  if (ec) return true;
  auto a = d.begin(), b = cwd.begin();
  for (; a != d.end() && b != cwd.end(); ++a, ++b)
    if (*a != *b) return false;
  return a == d.end();
}

/// The directories `create_directories(dir)` would create, innermost first.
std::vector<fs::path> missing_directories(const fs::path& dir) {
  std::vector<fs::path> missing;
  std::error_code ec;
  for (fs::path p = dir; !p.empty() && !fs::exists(fs::symlink_status(p, ec)); p = p.parent_path()) {
    missing.push_back(p);
    if (p == p.parent_path()) break;
  }
  return missing;
}

}  // namespace

// ---- marker ------------------------------------------------------------------------------------

void write_marker(const fs::path& dir, const RunMarker& m) {
  std::string text =
      "# Written by particula: this directory was created by particula. `particula run --overwrite`\n"
      "# replaces only directories holding this file, and `particula resume` continues only a\n"
      "# checkpoint of the case identified here.\n";
  text += fmt::format("format = {}\n", kRunMarkerFormat);
  text += fmt::format("kind = \"{}\"\n", m.kind == MarkedKind::Run ? "run" : "validation");
  if (m.kind == MarkedKind::Run) text += fmt::format("case_hash = \"{}\"\n", hex(m.case_hash));
  io::write_file_atomic(dir / kRunMarker, text);
}

std::optional<RunMarker> read_marker(const fs::path& dir) {
  const fs::path file = dir / kRunMarker;
  std::error_code ec;
  const auto st = fs::symlink_status(file, ec);
  if (!fs::exists(st)) return std::nullopt;
  auto fail = [&](const std::string& why) -> std::optional<RunMarker> {
    throw io::IoError(fmt::format("marker '{}': {}", shown(file), why));
  };
  if (!fs::is_regular_file(st)) return fail("not a regular file");
  const std::string text = io::read_file(file);
  RunMarker m;
  bool have_format = false, have_kind = false, have_hash = false;
  for (std::size_t start = 0; start < text.size();) {
    std::size_t nl = text.find('\n', start);
    if (nl == std::string::npos) nl = text.size();
    const std::string_view line = std::string_view(text).substr(start, nl - start);
    start = nl + 1;
    if (line.empty() || line.front() == '#') continue;
    const std::size_t eq = line.find(" = ");
    if (eq == std::string_view::npos) return fail(fmt::format("unreadable line '{}'", line));
    const std::string_view key = line.substr(0, eq), value = line.substr(eq + 3);
    if (key == "format") {
      if (value != std::to_string(kRunMarkerFormat))
        return fail(fmt::format("format {}, but this particula reads format {}", value, kRunMarkerFormat));
      have_format = true;
    } else if (key == "kind") {
      if (value == "\"run\"") m.kind = MarkedKind::Run;
      else if (value == "\"validation\"") m.kind = MarkedKind::Validation;
      else return fail(fmt::format("unknown kind {}", value));
      have_kind = true;
    } else if (key == "case_hash") {
      const std::string_view digits = value.size() == 18 ? value.substr(1, 16) : std::string_view();
      const auto [end, err] = std::from_chars(digits.data(), digits.data() + digits.size(), m.case_hash, 16);
      if (digits.empty() || err != std::errc() || end != digits.data() + digits.size() || value.front() != '"' ||
          value.back() != '"')
        return fail(fmt::format("unreadable case_hash {}", value));
      have_hash = true;
    } else {
      return fail(fmt::format("unknown key '{}'", key));
    }
  }
  if (!have_format || !have_kind || (m.kind == MarkedKind::Run && !have_hash))
    return fail("incomplete (format, kind and, for a run, case_hash are needed)");
  return m;
}

// ---- what particula writes ---------------------------------------------------------------------

bool particula_run_entry(const fs::path& rel, bool directory) {
  std::vector<std::string> parts;
  for (const auto& c : rel) parts.push_back(c.string());
  if (!parts.empty() && parts.front() == ".resume") {  // the scratch of a resumed run mirrors a run directory
    if (parts.size() == 1) return directory;
    parts.erase(parts.begin());
  }
  if (parts.empty()) return false;
  std::string name = parts.back();
  if (!directory)
    if (const auto temp = io::atomic_temp_target(name)) name = temp->target;
  if (parts.size() == 1) {
    if (directory) return name == "particles" || name == "checkpoint" || name == "plots";
    return top_file(name);
  }
  if (parts.size() != 2 || directory) return false;
  const std::string_view n = name;
  if (parts[0] == "particles")
    return starts_with(n, "step_") && ends_with(n, ".vtp") && all_digits(n.substr(5, n.size() - 9));
  if (parts[0] == "checkpoint") return n == "state.bin" || n == "failure.bin";
  if (parts[0] == "plots") return ends_with(n, ".png") && n.size() > 4;
  return false;
}

std::optional<std::string> why_not_replaceable(const fs::path& dir_in) {
  const fs::path dir = normalized(dir_in);
  std::error_code ec;
  const auto st = fs::symlink_status(dir, ec);
  if (ec || !fs::exists(st)) return "it does not exist";
  if (fs::is_symlink(st))
    return "it is a symbolic link (particula never removes what a link points to; remove the link yourself)";
  if (fs::is_regular_file(st)) return "it is a file, not a run directory";
  if (!fs::is_directory(st)) return "it is not a directory";
  if (holds_working_directory(dir)) return "it is the working directory or one of its parents";
  std::optional<RunMarker> marker;
  try {
    marker = read_marker(dir);
  } catch (const io::IoError& e) {
    return fmt::format("its marker is unreadable ({})", e.what());
  }
  if (!marker)
    return fmt::format("it is not a particula run directory (it has no {} marker); particula replaces only "
                       "directories it created: remove it yourself or choose another --out",
                       kRunMarker);
  if (marker->kind != MarkedKind::Run) return "it is a validation directory, not a run directory";
  // Everything in it must be something particula writes.
  std::vector<std::string> foreign;
  std::size_t n_foreign = 0;
  fs::recursive_directory_iterator it(dir, fs::directory_options::none, ec), end;
  if (ec) return fmt::format("it cannot be listed ({})", ec.message());
  for (; it != end; it.increment(ec)) {
    if (ec) return fmt::format("it cannot be listed ({})", ec.message());
    const fs::path rel = it->path().lexically_relative(dir);
    const auto est = it->symlink_status(ec);
    const bool is_dir = fs::is_directory(est);
    const bool ours = !fs::is_symlink(est) && (is_dir || fs::is_regular_file(est)) && particula_run_entry(rel, is_dir);
    if (!ours) {
      if (is_dir) it.disable_recursion_pending();
      if (++n_foreign <= 5) foreign.push_back(rel.string() + (is_dir ? "/" : fs::is_symlink(est) ? " (a link)" : ""));
    }
  }
  if (n_foreign > 0) {
    std::string list;
    for (const auto& f : foreign) list += (list.empty() ? "" : ", ") + f;
    if (n_foreign > foreign.size()) list += fmt::format(" and {} more", n_foreign - foreign.size());
    return fmt::format("it holds files particula did not write ({}): move them out first", list);
  }
  return std::nullopt;
}

// ---- RunDirectory ------------------------------------------------------------------------------

RunDirectory::RunDirectory(fs::path dir_in, bool overwrite, const RunMarker& marker) : dir_(normalized(dir_in)) {
  std::error_code ec;
  const fs::path parent = dir_.has_parent_path() ? dir_.parent_path() : fs::path();  // empty: the working directory
  // Old runs left aside by a particula killed while replacing them.
  const std::string aside_prefix = fmt::format(".{}.old.", dir_.filename().string());
  const fs::path listed = parent.empty() ? fs::path(".") : parent;
  if (fs::is_directory(listed, ec))
    for (const auto& e : fs::directory_iterator(listed, ec)) {
      const std::string name = e.path().filename().string();
      if (!starts_with(name, aside_prefix)) continue;
      std::string_view rest = std::string_view(name).substr(aside_prefix.size());
      rest = rest.substr(0, rest.find('.'));
      long pid = 0;
      std::from_chars(rest.data(), rest.data() + rest.size(), pid);
      if (all_digits(rest) && !process_running(pid))
        notes_.push_back(fmt::format("note: '{}' holds a run directory that an earlier 'particula run --overwrite' was "
                                     "replacing when it was killed; it is left as it is (move it back or delete it)",
                                     shown(parent / e.path().filename())));
    }

  if (fs::exists(fs::symlink_status(dir_, ec))) {
    const auto why = why_not_replaceable(dir_);
    if (!overwrite) {
      if (why)
        throw RunDirRefused(fmt::format("'{}' already exists, and --overwrite would not replace it either: {}",
                                        shown(dir_), *why));
      throw RunDirRefused(
          fmt::format("run directory '{}' already exists (use --overwrite to replace it)", shown(dir_)));
    }
    if (why) throw RunDirRefused(fmt::format("--overwrite: not replacing '{}': {}", shown(dir_), *why));
    fs::path aside = parent / fmt::format("{}{}", aside_prefix, static_cast<long>(::getpid()));
    for (int k = 1; fs::exists(fs::symlink_status(aside, ec)); ++k)
      aside = parent / fmt::format("{}{}.{}", aside_prefix, static_cast<long>(::getpid()), k);
    fs::rename(dir_, aside, ec);
    if (ec)
      throw io::WriteError(fmt::format("cannot move the old run directory '{}' aside to '{}': {}", shown(dir_),
                                       shown(aside), ec.message()));
    aside_ = aside;
  } else {
    created_ = missing_directories(dir_);
  }
  fs::create_directories(dir_, ec);
  if (ec) {
    const std::string why = ec.message();
    rollback();
    throw io::WriteError(fmt::format("cannot create run directory '{}': {}", shown(dir_), why));
  }
  if (created_.empty() && aside_.empty()) created_.push_back(dir_);  // created by someone else meanwhile: ours now
  if (!aside_.empty()) created_ = {dir_};
  try {
    write_marker(dir_, marker);
  } catch (...) {
    rollback();
    throw;
  }
}

RunDirectory::~RunDirectory() {
  if (!committed_ && !rolled_back_) (void)rollback();
}

std::optional<std::string> RunDirectory::commit() {
  if (committed_ || rolled_back_) return std::nullopt;
  committed_ = true;
  if (aside_.empty()) return std::nullopt;
  std::error_code ec;
  fs::remove_all(aside_, ec);
  if (ec)
    return fmt::format("could not delete the old run directory moved aside to '{}': {}; delete it yourself",
                       shown(aside_), ec.message());
  return std::nullopt;
}

std::optional<std::string> RunDirectory::rollback() {
  if (committed_ || rolled_back_) return std::nullopt;
  rolled_back_ = true;
  std::error_code ec;
  // The new directory holds only what this run wrote; the parents it created are left empty.
  if (!created_.empty()) fs::remove_all(created_.front(), ec);
  for (std::size_t k = 1; k < created_.size(); ++k) fs::remove(created_[k], ec);  // only if empty
  if (aside_.empty()) return std::nullopt;
  fs::rename(aside_, dir_, ec);
  if (ec)
    return fmt::format("could not put the old run directory back from '{}' to '{}': {}", shown(aside_), shown(dir_),
                       ec.message());
  return std::nullopt;
}

// ---- temporary files ---------------------------------------------------------------------------

std::vector<fs::path> remove_stale_temp_files(const fs::path& dir) {
  std::vector<fs::path> removed;
  for (const char* sub_name : {"", "checkpoint", "particles", "plots"}) {
    const fs::path sub(sub_name);
    std::error_code ec;
    const fs::path where = sub.empty() ? dir : dir / sub;
    if (!fs::is_directory(fs::symlink_status(where, ec))) continue;
    std::vector<fs::path> stale;
    for (const auto& e : fs::directory_iterator(where, ec)) {
      const std::string name = e.path().filename().string();
      const auto temp = io::atomic_temp_target(name);
      if (!temp || !fs::is_regular_file(e.symlink_status(ec))) continue;
      if (!particula_run_entry(sub / temp->target, false) || process_running(temp->pid)) continue;
      stale.push_back(e.path());
    }
    for (const auto& p : stale)
      if (fs::remove(p, ec)) removed.push_back(p);
  }
  return removed;
}

// ---- validation directory ----------------------------------------------------------------------

void prepare_validation_dir(const fs::path& dir_in) {
  const fs::path dir = normalized(dir_in);
  std::error_code ec;
  const auto st = fs::status(dir, ec);
  if (!fs::exists(st)) {
    fs::create_directories(dir, ec);
    if (ec) throw io::WriteError(fmt::format("cannot create the validation directory '{}': {}", shown(dir), ec.message()));
    write_marker(dir, RunMarker{MarkedKind::Validation, 0});
    return;
  }
  if (!fs::is_directory(st)) throw RunDirRefused(fmt::format("--out '{}' is not a directory", shown(dir)));
  std::optional<RunMarker> marker;
  try {
    marker = read_marker(dir);
  } catch (const io::IoError& e) {
    throw RunDirRefused(fmt::format("--out '{}': {}", shown(dir), e.what()));
  }
  if (marker && marker->kind == MarkedKind::Validation) return;
  if (marker)
    throw RunDirRefused(fmt::format("--out '{}' is a run directory, not a validation directory: choose another --out",
                                    shown(dir)));
  if (!fs::is_empty(dir, ec) || ec)
    throw RunDirRefused(fmt::format("--out '{}' exists and is not a particula validation directory (it has no {} "
                                    "marker and is not empty); validate writes run directories and report.md "
                                    "into it: choose another --out",
                                    shown(dir), kRunMarker));
  write_marker(dir, RunMarker{MarkedKind::Validation, 0});
}

}  // namespace particula
