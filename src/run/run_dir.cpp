#include "particula/run/run_dir.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cstdio>
#include <cstring>
#include <toml++/toml.h>

#include "particula/io/atomic_file.hpp"
#include "particula/run/plots.hpp"

namespace particula {

namespace fs = std::filesystem;

namespace {

bool starts_with(std::string_view s, std::string_view prefix) { return s.substr(0, prefix.size()) == prefix; }
bool ends_with(std::string_view s, std::string_view suffix) {
  return s.size() >= suffix.size() && s.substr(s.size() - suffix.size()) == suffix;
}
bool all_digits(std::string_view s) {
  return !s.empty() && std::all_of(s.begin(), s.end(), [](char c) { return c >= '0' && c <= '9'; });
}

/// A file name particula writes at the top of every run directory (or of its .resume scratch).
bool fixed_top_file(std::string_view name) {
  for (const char* known : {kRunMarker, kRunLock, "case.toml", "summary.json", "log.txt", "bodies.csv", "walls.csv",
                            "coefficients.csv", "open_boundaries.csv", "particles.pvd"})
    if (name == known) return true;
  return false;
}

/// A file name particula writes at the top of a run directory: with `probes`, only those of
/// the case's probes; without, any probe's.
bool top_file(const std::string& name, const std::vector<std::string>* probes) {
  if (fixed_top_file(name)) return true;
  if (!probes)
    return (starts_with(name, "probe_") && ends_with(name, ".csv") && name.size() > 10) ||
           (starts_with(name, "flow_") && ends_with(name, ".csv") && name.size() > 9);
  return std::any_of(probes->begin(), probes->end(),
                     [&](const std::string& p) { return name == probe_csv_name(p) || name == flow_csv_name(p); });
}

/// An image particula draws into plots/: with `probes`, only those of the case; without, any.
bool plot_file(const std::string& name, const std::vector<std::string>* probes) {
  if (!probes)
    return std::any_of(plot_formats().begin(), plot_formats().end(), [&](const std::string& format) {
      return ends_with(name, "." + format) && name.size() > format.size() + 1;
    });
  const std::vector<std::string> names = plot_file_names(*probes);
  return std::find(names.begin(), names.end(), name) != names.end();
}

/// particula_run_entry (probes == nullptr) and case_run_entry.
bool run_entry(const fs::path& rel, bool directory, const std::vector<std::string>* probes) {
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
    return top_file(name, probes);
  }
  if (parts.size() != 2 || directory) return false;
  const std::string_view n = name;
  if (parts[0] == "particles")
    return starts_with(n, "step_") && ends_with(n, ".vtp") && all_digits(n.substr(5, n.size() - 9));
  if (parts[0] == "checkpoint") return n == "state.bin" || n == "failure.bin";
  if (parts[0] == "plots") return plot_file(name, probes);
  return false;
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

std::string probe_csv_name(const std::string& probe) { return "probe_" + probe + ".csv"; }
std::string flow_csv_name(const std::string& probe) { return "flow_" + probe + ".csv"; }

bool particula_run_entry(const fs::path& rel, bool directory) { return run_entry(rel, directory, nullptr); }

bool case_run_entry(const fs::path& rel, bool directory, const std::vector<std::string>& probes) {
  return run_entry(rel, directory, &probes);
}

std::optional<std::vector<std::string>> run_probe_names(const fs::path& dir) {
  std::error_code ec;
  const fs::path file = dir / "case.toml";
  if (!fs::is_regular_file(fs::symlink_status(file, ec))) return std::nullopt;
  try {
    const toml::table doc = toml::parse(io::read_file(file), file.string());
    std::vector<std::string> names;
    if (const toml::array* probes = doc["probe"].as_array())
      for (const toml::node& p : *probes) {
        const auto name = p.as_table() ? (*p.as_table())["name"].value<std::string>() : std::nullopt;
        if (!name) return std::nullopt;
        names.push_back(*name);
      }
    return names;
  } catch (const std::exception&) {  // toml::parse_error, io::IoError
    return std::nullopt;
  }
}

namespace {

/// The entries of run directory `dir` that its run did not write (case_run_entry with `probes`),
/// the first five named ("notes.txt", "analysis/", "x (a link)"), or why it cannot be listed.
std::optional<std::string> foreign_entries(const fs::path& dir, const std::vector<std::string>& probes) {
  std::vector<std::string> foreign;
  std::size_t n_foreign = 0;
  std::error_code ec;
  fs::recursive_directory_iterator it(dir, fs::directory_options::none, ec), end;
  if (ec) return fmt::format("it cannot be listed ({})", ec.message());
  for (; it != end; it.increment(ec)) {
    if (ec) return fmt::format("it cannot be listed ({})", ec.message());
    const fs::path rel = it->path().lexically_relative(dir);
    const auto est = it->symlink_status(ec);
    const bool is_dir = fs::is_directory(est);
    const bool ours = !fs::is_symlink(est) && (is_dir || fs::is_regular_file(est)) &&
                      case_run_entry(rel, is_dir, probes);
    if (!ours) {
      if (is_dir) it.disable_recursion_pending();
      if (++n_foreign <= 5) foreign.push_back(rel.string() + (is_dir ? "/" : fs::is_symlink(est) ? " (a link)" : ""));
    }
  }
  if (n_foreign == 0) return std::nullopt;
  std::string list;
  for (const auto& f : foreign) list += (list.empty() ? "" : ", ") + f;
  if (n_foreign > foreign.size()) list += fmt::format(" and {} more", n_foreign - foreign.size());
  return list;
}

}  // namespace

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
  // Everything in it must be a file its run writes: the names of its case, not every name that
  // looks like particula's.
  const std::optional<std::vector<std::string>> probes = run_probe_names(dir);
  if (const auto foreign = foreign_entries(dir, probes ? *probes : std::vector<std::string>{}))
    return fmt::format("it holds files its run did not write ({}){}: move them out first", *foreign,
                       probes ? "" : "; its case.toml is missing or unreadable, so only particula's fixed file "
                                     "names count as the run's");
  return std::nullopt;
}

// ---- RunDirectory ------------------------------------------------------------------------------

namespace {

/// Renames `from` to `to` unless `to` exists (renameat2 RENAME_NOREPLACE; where the file system
/// lacks it, checked first). Returns 0 or an errno (EEXIST: `to` exists).
int rename_noreplace(const fs::path& from, const fs::path& to) {
  if (::renameat2(AT_FDCWD, from.c_str(), AT_FDCWD, to.c_str(), RENAME_NOREPLACE) == 0) return 0;
  if (errno != EINVAL && errno != ENOSYS && errno != ENOTSUP) return errno;
  std::error_code ec;
  if (fs::exists(fs::symlink_status(to, ec))) return EEXIST;
  return std::rename(from.c_str(), to.c_str()) == 0 ? 0 : errno;
}

/// Swaps `a` and `b` atomically (renameat2 RENAME_EXCHANGE). Returns 0 or an errno (EINVAL:
/// the file system cannot).
int swap_entries(const fs::path& a, const fs::path& b) {
  return ::renameat2(AT_FDCWD, a.c_str(), AT_FDCWD, b.c_str(), RENAME_EXCHANGE) == 0 ? 0 : errno;
}

bool cannot_exchange(int err) { return err == EINVAL || err == ENOSYS || err == ENOTSUP; }

/// A hidden sibling `.NAME.<what>.<pid>[.k]` of `dir` in `parent` that does not exist yet.
fs::path free_sibling(const fs::path& parent, const fs::path& dir, const char* what) {
  std::error_code ec;
  const std::string base = fmt::format(".{}.{}.{}", dir.filename().string(), what, static_cast<long>(::getpid()));
  fs::path p = parent / base;
  for (int k = 1; fs::exists(fs::symlink_status(p, ec)); ++k) p = parent / fmt::format("{}.{}", base, k);
  return p;
}

/// The process that uses run directory `dir` (run_dir_user), when `dir` is a directory itself
/// (not a link to one: that is refused as a link).
std::optional<long> user_of(const fs::path& dir) {
  std::error_code ec;
  return fs::is_directory(fs::symlink_status(dir, ec)) ? run_dir_user(dir) : std::nullopt;
}

[[noreturn]] void cannot_create(const fs::path& dir, int err) {
  throw io::WriteError(fmt::format("cannot create run directory '{}': {}", shown(dir), std::strerror(err)));
}

}  // namespace

void RunDirectory::note_left_behind(const fs::path& parent) {
  // Run directories left by a particula killed while creating (.NAME.new.<pid>) or replacing
  // (.NAME.old.<pid>) NAME.
  std::error_code ec;
  const fs::path listed = parent.empty() ? fs::path(".") : parent;
  if (!fs::is_directory(listed, ec)) return;
  for (const auto& e : fs::directory_iterator(listed, ec))
    for (const char* what : {"old", "new"}) {
      const std::string prefix = fmt::format(".{}.{}.", dir_.filename().string(), what);
      const std::string name = e.path().filename().string();
      if (!starts_with(name, prefix)) continue;
      std::string_view rest = std::string_view(name).substr(prefix.size());
      rest = rest.substr(0, rest.find('.'));
      long pid = 0;
      std::from_chars(rest.data(), rest.data() + rest.size(), pid);
      if (all_digits(rest) && !process_running(pid))
        notes_.push_back(fmt::format("note: '{}' holds a run directory that an earlier 'particula run' was "
                                     "{} when it was killed; it is left as it is (move it back or delete it)",
                                     shown(parent / e.path().filename()),
                                     what == std::string("old") ? "replacing" : "creating or replacing"));
    }
}

fs::path RunDirectory::stage(const fs::path& parent, const RunMarker& marker) {
  fs::path staged;
  for (;;) {
    staged = free_sibling(parent, dir_, "new");
    std::error_code ec;
    if (fs::create_directory(staged, ec)) break;  // false without an error: another process made it first
    if (ec) cannot_create(dir_, ec.value());
  }
  staging_ = staged;
  lock_ = RunDirLock(staged);
  write_marker(staged, marker);
  return staged;
}

bool RunDirectory::create(const fs::path& parent, const RunMarker& marker) {
  std::error_code ec;
  created_ = missing_directories(dir_);
  if (!created_.empty() && created_.front() == dir_) created_.erase(created_.begin());  // the parents only
  if (!parent.empty()) {
    fs::create_directories(parent, ec);
    if (ec) cannot_create(dir_, ec.value());
  }
  const fs::path staged = stage(parent, marker);
  const int err = rename_noreplace(staged, dir_);
  if (err == EEXIST || err == ENOTEMPTY) {  // another process made it meanwhile: it is not this run's
    fs::remove_all(staged, ec);
    staging_.clear();
    lock_.release();
    return false;
  }
  if (err != 0) cannot_create(dir_, err);
  staging_.clear();
  own_dir_ = true;
  return true;
}

void RunDirectory::replace(const fs::path& parent, const RunMarker& marker) {
  auto refuse = [&](const std::string& why) {
    throw RunDirRefused(fmt::format("--overwrite: not replacing '{}': {}", shown(dir_), why));
  };
  if (const auto why = why_not_replaceable(dir_)) {
    if (const auto user = user_of(dir_)) throw RunDirBusy(dir_, user);
    refuse(*why);
  }
  old_lock_ = RunDirLock(dir_);  // before anything is moved; RunDirBusy when another particula has it
  if (const auto why = why_not_replaceable(dir_)) refuse(*why);  // looked at again under the lock
  const fs::path staged = stage(parent, marker);
  const fs::path aside = free_sibling(parent, dir_, "old");
  std::error_code ec;
  if (const int err = swap_entries(staged, dir_); err == 0) {  // `staged` holds the old run now
    staging_.clear();
    own_dir_ = true;
    fs::rename(staged, aside, ec);
    aside_ = ec ? staged : aside;
    return;
  } else if (!cannot_exchange(err)) {
    throw io::WriteError(fmt::format("cannot replace the run directory '{}': {}", shown(dir_), std::strerror(err)));
  }
  // Without RENAME_EXCHANGE: the old run is moved aside, then the new one moved in.
  fs::rename(dir_, aside, ec);
  if (ec)
    throw io::WriteError(fmt::format("cannot move the old run directory '{}' aside to '{}': {}", shown(dir_),
                                     shown(aside), ec.message()));
  if (const int err = rename_noreplace(staged, dir_); err != 0) {
    const bool back = rename_noreplace(aside, dir_) == 0;
    if (back) cannot_create(dir_, err);
    throw RunDirRefused(fmt::format("another process created '{}' while this run was replacing it; the previous "
                                    "run is kept in '{}'",
                                    shown(dir_), shown(aside)));
  }
  staging_.clear();
  own_dir_ = true;
  aside_ = aside;
}

RunDirectory::RunDirectory(fs::path dir_in, bool overwrite, const RunMarker& marker) : dir_(normalized(dir_in)) {
  const fs::path parent = dir_.has_parent_path() ? dir_.parent_path() : fs::path();  // empty: the working directory
  note_left_behind(parent);
  try {
    for (int attempt = 0;; ++attempt) {
      std::error_code ec;
      if (!fs::exists(fs::symlink_status(dir_, ec))) {
        if (create(parent, marker)) return;
        if (attempt < 2) continue;  // made by another process meanwhile: look at it again
      }
      if (overwrite) {
        replace(parent, marker);
        return;
      }
      if (const auto user = user_of(dir_)) throw RunDirBusy(dir_, user);
      if (const auto why = why_not_replaceable(dir_))
        throw RunDirRefused(fmt::format("'{}' already exists, and --overwrite would not replace it either: {}",
                                        shown(dir_), *why));
      throw RunDirRefused(
          fmt::format("run directory '{}' already exists (use --overwrite to replace it)", shown(dir_)));
    }
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
  old_lock_.release();
  if (ec)
    return fmt::format("could not delete the old run directory moved aside to '{}': {}; delete it yourself",
                       shown(aside_), ec.message());
  return std::nullopt;
}

std::optional<std::string> RunDirectory::put_back() {
  std::error_code ec;
  if (swap_entries(aside_, dir_) == 0) {  // `aside_` holds the new run now
    fs::remove_all(aside_, ec);
    return std::nullopt;
  }
  fs::remove_all(dir_, ec);  // the new run (this process holds its lock)
  if (const int err = rename_noreplace(aside_, dir_); err != 0)
    return fmt::format("could not put the old run directory back from '{}' to '{}': {}", shown(aside_), shown(dir_),
                       std::strerror(err));
  return std::nullopt;
}

std::optional<std::string> RunDirectory::rollback() {
  if (committed_ || rolled_back_) return std::nullopt;
  rolled_back_ = true;
  std::error_code ec;
  if (!staging_.empty()) fs::remove_all(staging_, ec);  // never became the run directory
  std::optional<std::string> warning;
  if (!aside_.empty()) {
    warning = put_back();
  } else if (own_dir_) {
    fs::remove_all(dir_, ec);  // it holds only what this run wrote
  }
  for (const fs::path& p : created_) fs::remove(p, ec);  // the parents this created, only if empty
  lock_.release();
  old_lock_.release();
  return warning;
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
