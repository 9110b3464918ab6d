// The output streams of a run (bodies.csv, probe CSVs, snapshots) and their schedule, for a
// fresh run and for a resumed one. Private to src/run.
#pragma once

#include <filesystem>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "particula/case/case.hpp"
#include "particula/run/checkpoint.hpp"
#include "particula/run/observers.hpp"
#include "particula/solver/solver.hpp"

namespace particula::run_detail {

/// The first multiple of `interval` after t (the next output time after a write at t), rounded
/// to 15 significant digits (the decimal time it stands for).
real next_multiple(real t, real interval);

class CsvRelay;
class SnapshotRelay;

/// Every output stream of a run. A stream writes when its next time is reached (the loop lands
/// steps on these times) and, with `force`, whenever it has not yet written the current time
/// (initial, final and failure states). Writes on the schedule are remembered per stream
/// (marks()) so that a resumed run can drop the forced extra rows of an interrupted one.
/// Long writes poll `stop` (observers.hpp); a stream whose write is given up keeps its mark, so
/// a run resumed from a checkpoint taken then writes that stream's due output first.
class RunOutputs {
 public:
  /// A fresh run: creates bodies.csv, walls.csv, coefficients.csv (when bodies have references),
  /// probe_<name>.csv, flow_<name>.csv (line probes) and particles.pvd in `dir`.
  RunOutputs(const std::filesystem::path& dir, const Case& c, io::StopCheck stop = {});
  /// A resumed run at `t0`: keeps each existing stream up to its mark (rows after it are
  /// dropped: CsvWriter::append, PvdIndex::drop_after) and appends to it. Throws io::IoError
  /// when an existing file does not fit (e.g. another header).
  RunOutputs(const std::filesystem::path& dir, const Case& c, const std::vector<OutputMark>& marks, real t0,
             io::StopCheck stop = {});
  ~RunOutputs();
  RunOutputs(const RunOutputs&) = delete;
  RunOutputs& operator=(const RunOutputs&) = delete;

  /// Writes every stream that is due at the solver's time (or, with `force`, every stream that
  /// has not written this time yet). A stream whose write is given up on the stop check is
  /// skipped (nothing of it written, its schedule unchanged) and the others are written; then
  /// io::Cancelled is thrown. A stream whose values are not all finite writes nothing; the first
  /// such failure is returned (the run ends with exit 3).
  std::optional<Failure> write(const Solver& s, bool force);
  /// The earliest next output time, capped at t_end.
  real next_event(real t_end) const;
  /// The last scheduled write of each stream, for checkpoints.
  std::vector<OutputMark> marks() const;
  const std::vector<std::unique_ptr<ProbeWriter>>& probes() const { return probes_; }

 private:
  struct Stream {
    std::string key;
    real interval = 0;
    real next = 0;
    real last_written = -std::numeric_limits<real>::infinity();
    real last_scheduled = -std::numeric_limits<real>::infinity();
    std::function<std::optional<Failure>(const Solver&)> write;
  };
  void add(std::string key, real interval, std::function<std::optional<Failure>(const Solver&)> write);
  void resume_schedule(const std::vector<OutputMark>& marks, real t0);

  std::filesystem::path scratch_;  // resumed runs: where the observers write before relaying
  std::unique_ptr<SnapshotWriter> snapshots_;
  std::unique_ptr<BodyHistoryWriter> bodies_;
  std::unique_ptr<OpenBoundaryWriter> open_;  // cases with inlets or outlets
  std::vector<std::unique_ptr<ProbeWriter>> probes_;
  std::vector<std::unique_ptr<CsvRelay>> csv_relays_;
  std::unique_ptr<SnapshotRelay> snapshot_relay_;
  std::vector<Stream> streams_;
};

}  // namespace particula::run_detail
