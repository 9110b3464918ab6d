// Run directories and what particula may do to them.
//
// `run` writes a marker file (kRunMarker) into every run directory it creates, naming particula,
// the marker's format, the kind of directory and the run's case identity (case_identity_hash).
// `run`, `resume` and `run --overwrite` hold an advisory lock (flock on kRunLock, RunDirLock) on
// the run directory for as long as they use it; a second particula that wants the same directory
// is refused (RunDirBusy, exit code 2) with the pid of the one that holds it. A new run directory
// is made under a hidden sibling `.NAME.new.<pid>` (marker written, lock held) and renamed to NAME
// only when NAME does not exist, so it never appears without its marker and lock.
// `run --overwrite` replaces only a directory that holds a run marker and nothing but the files
// its case writes (the fixed names, its probes' files and plots: case_run_entry); never `.`, the
// working directory or one of its parents, a plain file or a symbolic link. It takes the old
// directory's lock first, checks it again under the lock, and swaps the new directory in
// (renameat2 RENAME_EXCHANGE); the old run is kept aside (a hidden sibling `.NAME.old.<pid>`) and
// deleted only once the new run has written its initial state and a checkpoint; if the new run
// fails before that, the old one is put back (RunDirectory::rollback).
// `resume` compares the marker's case identity with the checkpoint's, and removes temporary
// files that a killed particula left (remove_stale_temp_files).
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace particula {

/// The marker file of a directory particula created (a run directory or a validation directory).
inline constexpr const char* kRunMarker = ".particula-run";
/// Format of the marker file; a marker of another format is not recognised.
inline constexpr int kRunMarkerFormat = 1;
/// The lock file of a run directory: locked (flock) by the particula that uses the directory,
/// holding that process's pid while it is locked (emptied when released). It stays in the
/// directory: removing it would let two processes lock two different files.
inline constexpr const char* kRunLock = ".particula-lock";

enum class MarkedKind { Run, Validation };

struct RunMarker {
  MarkedKind kind = MarkedKind::Run;
  std::uint64_t case_hash = 0;  // runs: case_identity_hash of the case the run was created with
};

/// What --out or --overwrite refuses to touch: bad input (exit code 2), nothing was changed.
class RunDirRefused : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Another particula process uses the run directory (holds its lock): exit code 2, nothing was
/// changed. The message names the directory and, when known, the other process's pid.
class RunDirBusy : public RunDirRefused {
 public:
  RunDirBusy(const std::filesystem::path& dir, std::optional<long> pid);
};

/// Whether process `pid` may still be running.
bool process_running(long pid);

/// The exclusive advisory lock (flock) of a run directory, DIR/.particula-lock, held until
/// release() or destruction. The lock file is opened close-on-exec, so that no child process
/// (the plotting script) keeps it.
class RunDirLock {
 public:
  RunDirLock() = default;
  /// Locks DIR/.particula-lock, creating it when missing, and writes this process's pid into it.
  /// Throws RunDirBusy when another process (or another lock in this one) holds it,
  /// RunDirRefused when the lock file is a symbolic link or not a regular file, io::WriteError
  /// when it cannot be created or locked.
  explicit RunDirLock(const std::filesystem::path& dir);
  ~RunDirLock() { release(); }
  RunDirLock(RunDirLock&& other) noexcept : fd_(other.fd_) { other.fd_ = -1; }
  RunDirLock& operator=(RunDirLock&& other) noexcept;
  RunDirLock(const RunDirLock&) = delete;
  RunDirLock& operator=(const RunDirLock&) = delete;

  bool held() const { return fd_ >= 0; }
  /// Empties the lock file and unlocks it.
  void release();

 private:
  int fd_ = -1;
};

/// The pid in DIR's lock file when that process is running, else nullopt. Takes no lock (it
/// names the user of a directory that is refused for another reason, e.g. without --overwrite).
std::optional<long> run_dir_user(const std::filesystem::path& dir);

/// Writes DIR/.particula-run. Throws io::WriteError.
void write_marker(const std::filesystem::path& dir, const RunMarker& marker);
/// The marker of `dir`: nullopt when it has none (or `dir` is not a directory); throws
/// io::IoError naming the file when the marker is unreadable or of another format.
std::optional<RunMarker> read_marker(const std::filesystem::path& dir);

/// The files a probe named `probe` writes at the top of its run directory: probe_<probe>.csv and,
/// for a line probe, flow_<probe>.csv.
std::string probe_csv_name(const std::string& probe);
std::string flow_csv_name(const std::string& probe);

/// Whether `rel`, a path relative to a run directory, has the name of a file or directory
/// particula writes there (case.toml, log.txt, probe_*.csv, particles/step_00000010.vtp,
/// checkpoint/state.bin, plots/ images, the marker and lock, their temporary files
/// `<name>.tmp.<pid>`, ...), whatever the case. `directory`: whether it is a directory.
bool particula_run_entry(const std::filesystem::path& rel, bool directory);

/// As particula_run_entry, for the run of a case with the probes `probes`: only the files that
/// case writes (the fixed names, probe_<name>.csv and flow_<name>.csv of its probes, their plots
/// and the fixed plots), not everything that matches a pattern (a user's probe_mine.csv or
/// plots/figure.png is not the run's).
bool case_run_entry(const std::filesystem::path& rel, bool directory, const std::vector<std::string>& probes);

/// The probe names of the case in run directory `dir` (its case.toml); nullopt when case.toml is
/// missing or unreadable.
std::optional<std::vector<std::string>> run_probe_names(const std::filesystem::path& dir);

/// Why --overwrite must not remove `dir` (not a directory, a symbolic link, the working
/// directory or one of its parents, no marker, files its run did not write: case_run_entry with
/// run_probe_names); nullopt when it may. `dir` must exist.
std::optional<std::string> why_not_replaceable(const std::filesystem::path& dir);

/// The run directory of a `run`: created (or, with overwrite, replacing an old run directory)
/// with its marker, and locked (RunDirLock) for the object's lifetime. Until commit(), the
/// destructor undoes everything (rollback()).
class RunDirectory {
 public:
  /// Creates `dir` with `marker`. When `dir` exists: without `overwrite`, or when
  /// why_not_replaceable() gives a reason, throws RunDirRefused (nothing changed); when another
  /// particula uses it, RunDirBusy; otherwise, holding the old directory's lock, the new one
  /// takes its place and the old one is kept aside. Throws io::WriteError when the file system
  /// fails.
  RunDirectory(std::filesystem::path dir, bool overwrite, const RunMarker& marker);
  ~RunDirectory();
  RunDirectory(const RunDirectory&) = delete;
  RunDirectory& operator=(const RunDirectory&) = delete;

  const std::filesystem::path& path() const { return dir_; }
  /// Whether an old run directory is being replaced (then aside() holds it until commit()).
  bool replacing() const { return !aside_.empty(); }
  const std::filesystem::path& aside() const { return aside_; }
  bool committed() const { return committed_; }
  /// Notes for the log (e.g. an old run directory left aside by a particula that was killed).
  const std::vector<std::string>& notes() const { return notes_; }

  /// The new run has started (its initial state and a checkpoint are written): deletes the old
  /// run directory. Returns a warning when it could not be deleted (the run goes on).
  std::optional<std::string> commit();
  /// Removes the new directory (and the parents this created) and puts the old run back.
  /// Returns a warning when the old run could not be put back (then it names where it is).
  std::optional<std::string> rollback();

 private:
  void note_left_behind(const std::filesystem::path& parent);
  /// Makes `.NAME.new.<pid>` with the marker and the held lock; returns it.
  std::filesystem::path stage(const std::filesystem::path& parent, const RunMarker& marker);
  /// A new `dir_` (parents created as needed); false when another process made `dir_` meanwhile.
  bool create(const std::filesystem::path& parent, const RunMarker& marker);
  /// Puts the new run in place of the old one, kept aside, under the old one's lock.
  void replace(const std::filesystem::path& parent, const RunMarker& marker);
  std::optional<std::string> put_back();

  std::filesystem::path dir_, aside_, staging_;
  std::vector<std::filesystem::path> created_;  // parent directories created, innermost first
  std::vector<std::string> notes_;
  RunDirLock lock_, old_lock_;  // the new run directory's lock; the old one's while replacing
  bool own_dir_ = false;        // dir_ is this run's new directory
  bool committed_ = false, rolled_back_ = false;
};

/// Removes the temporary files `<name>.tmp.<pid>` left in run directory `dir` (and its
/// checkpoint/, particles/ and plots/) by a particula that was killed while writing: only names
/// particula writes, only regular files, only when process <pid> is not running. Returns the
/// removed files.
std::vector<std::filesystem::path> remove_stale_temp_files(const std::filesystem::path& dir);

/// The output directory of `validate`: created with a validation marker, or an existing one
/// that has that marker (or is empty) is used. Anything else throws RunDirRefused (exit code 2;
/// `validate` replaces run directories and report.md in it); io::WriteError when it cannot be
/// created.
void prepare_validation_dir(const std::filesystem::path& dir);

}  // namespace particula
