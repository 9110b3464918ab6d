// Run directories and what particula may do to them.
//
// `run` writes a marker file (kRunMarker) into every run directory it creates, naming particula,
// the marker's format, the kind of directory and the run's case identity (case_identity_hash).
// `run --overwrite` replaces only a directory that holds such a marker and nothing particula
// does not write; never `.`, the working directory or one of its parents, a plain file or a
// symbolic link. The old run is renamed aside (a hidden sibling `.NAME.old.<pid>`) while the new
// one starts, and deleted only once the new run has written its initial state and a checkpoint;
// if the new run fails before that, the old one is put back (RunDirectory::rollback).
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

/// Writes DIR/.particula-run. Throws io::WriteError.
void write_marker(const std::filesystem::path& dir, const RunMarker& marker);
/// The marker of `dir`: nullopt when it has none (or `dir` is not a directory); throws
/// io::IoError naming the file when the marker is unreadable or of another format.
std::optional<RunMarker> read_marker(const std::filesystem::path& dir);

/// Whether `rel`, a path relative to a run directory, names a file or directory particula
/// writes there (case.toml, log.txt, particles/step_00000010.vtp, checkpoint/state.bin, plots/
/// images, the marker, their temporary files `<name>.tmp.<pid>`, ...). `directory`: whether it
/// is a directory.
bool particula_run_entry(const std::filesystem::path& rel, bool directory);

/// Why --overwrite must not remove `dir` (not a directory, a symbolic link, the working
/// directory or one of its parents, no marker, files particula did not write); nullopt when it
/// may. `dir` must exist.
std::optional<std::string> why_not_replaceable(const std::filesystem::path& dir);

/// The run directory of a `run`: created (or, with overwrite, replacing an old run directory)
/// with its marker. Until commit(), the destructor undoes everything (rollback()).
class RunDirectory {
 public:
  /// Creates `dir` with `marker`. When `dir` exists: without `overwrite`, or when
  /// why_not_replaceable() gives a reason, throws RunDirRefused (nothing changed); otherwise the
  /// old directory is renamed aside and a new one is created. Throws io::WriteError when the
  /// file system fails.
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
  std::filesystem::path dir_, aside_;
  std::vector<std::filesystem::path> created_;  // directories created, innermost first
  std::vector<std::string> notes_;
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
