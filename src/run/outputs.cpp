#include "outputs.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <optional>

#include "particula/io/atomic_file.hpp"
#include "particula/io/csv.hpp"
#include "particula/io/number.hpp"
#include "particula/io/vtk.hpp"
#include "particula/run/run_dir.hpp"

namespace particula::run_detail {

namespace fs = std::filesystem;

real next_multiple(real t, real interval) {
  const real k = std::floor(t / interval + 1e-9) + 1;
  // k * interval to 15 digits: 7 * 0.05 is 0.35, not 0.35000000000000003, so the times written
  // are the decimal values they stand for (the loop lands on them exactly: Solver::step_to).
  return io::round_significant(k * interval, 15);
}

// ---- relays for resumed runs ------------------------------------------------------------------
//
// The observers (observers.hpp) create their files afresh. A resumed run lets them write into a
// scratch directory and relays what they write to the run directory's existing files: CSV rows
// are appended to the file reopened with CsvWriter::append (rows after the checkpoint dropped),
// snapshots are moved into particles/ and added to the existing .pvd index. Numbers go through
// the CSV text unchanged (shortest round-trip form), so the rows are bitwise those of the
// observer.

/// Appends the rows an observer writes to `scratch` to the run directory's file `target`.
class CsvRelay {
 public:
  CsvRelay(fs::path scratch, const fs::path& target, real drop_after) : scratch_(std::move(scratch)) {
    // The observer has written its header (and units line) so far: the target gets the same.
    const io::CsvTable head = io::read_csv(scratch_);
    offset_ = io::read_file(scratch_).size();
    target_.emplace(io::CsvWriter::append(target, head.header, drop_after, head.units));
  }

  /// Relays the complete rows written since the last call.
  void pump() {
    std::FILE* f = std::fopen(scratch_.c_str(), "rb");
    if (!f) throw io::IoError(fmt::format("cannot read '{}'", scratch_.string()));
    std::string text;
    if (std::fseek(f, static_cast<long>(offset_), SEEK_SET) == 0) {
      char buf[1 << 16];
      for (std::size_t n; (n = std::fread(buf, 1, sizeof buf, f)) > 0;) text.append(buf, n);
    }
    std::fclose(f);
    std::vector<double> row;
    std::size_t start = 0;
    for (std::size_t nl; (nl = text.find('\n', start)) != std::string::npos; start = nl + 1) {
      if (text[start] == '#') continue;  // a comment line
      row.clear();
      for (std::size_t pos = start; pos <= nl;) {
        std::size_t end = text.find(',', pos);
        if (end == std::string::npos || end > nl) end = nl;
        double v = 0;
        const auto [ptr, ec] = std::from_chars(text.data() + pos, text.data() + end, v);
        if (ec != std::errc() || ptr != text.data() + end)
          throw io::IoError(fmt::format("'{}': unreadable number in '{}'", scratch_.string(),
                                        text.substr(start, nl - start)));
        row.push_back(v);
        pos = end + 1;
      }
      target_->row(row);
    }
    offset_ += start;
  }

 private:
  fs::path scratch_;
  std::size_t offset_ = 0;
  std::optional<io::CsvWriter> target_;
};

/// Moves the snapshots an observer writes to `scratch`/particles into the run directory and
/// adds them to its particles.pvd (entries and files after `drop_after` removed first).
class SnapshotRelay {
 public:
  SnapshotRelay(fs::path scratch, fs::path dir, real drop_after) : scratch_(std::move(scratch)), dir_(std::move(dir)) {
    std::error_code ec;
    if (fs::exists(dir_ / "particles.pvd", ec)) index_ = io::PvdIndex::read(dir_ / "particles.pvd");
    // Only snapshots particula writes (particles/step_<n>.vtp) are removed, whatever the index names.
    for (const auto& e : index_.entries())
      if (e.time > drop_after && particula_run_entry(fs::path(e.file).lexically_normal(), false) &&
          fs::path(e.file).lexically_normal().begin()->string() == "particles")
        fs::remove(dir_ / e.file, ec);
    index_.drop_after(drop_after);
    fs::create_directories(dir_ / "particles", ec);
    if (ec) throw io::WriteError(fmt::format("cannot create '{}': {}", (dir_ / "particles").string(), ec.message()));
    index_.write(dir_ / "particles.pvd");
  }

  void pump() {
    const io::PvdIndex written = io::PvdIndex::read(scratch_ / "particles.pvd");
    const auto& entries = written.entries();
    for (; consumed_ < entries.size(); ++consumed_) {
      const auto& e = entries[consumed_];
      std::error_code ec;
      fs::rename(scratch_ / e.file, dir_ / e.file, ec);
      if (ec) throw io::WriteError(fmt::format("cannot move '{}' to '{}': {}", (scratch_ / e.file).string(),
                                            (dir_ / e.file).string(), ec.message()));
      index_.add(e.time, e.file);
    }
    index_.write(dir_ / "particles.pvd");
  }

 private:
  fs::path scratch_, dir_;
  io::PvdIndex index_;
  std::size_t consumed_ = 0;
};

// ---- the streams --------------------------------------------------------------------------------

void RunOutputs::add(std::string key, real interval, std::function<std::optional<Failure>(const Solver&)> write) {
  Stream s;
  s.key = std::move(key);
  s.interval = interval;
  s.write = std::move(write);
  streams_.push_back(std::move(s));
}

RunOutputs::RunOutputs(const fs::path& dir, const Case& c, io::StopCheck stop) {
  bodies_ = std::make_unique<BodyHistoryWriter>(dir, c);
  add("bodies", c.output_interval, [this](const Solver& s) { return bodies_->write(s); });
  if (!c.inlets.empty() || !c.outlets.empty()) {
    open_ = std::make_unique<OpenBoundaryWriter>(dir);
    add("open_boundaries", c.output_interval, [this](const Solver& s) { return open_->write(s); });
  }
  for (const auto& p : c.probes) {
    probes_.push_back(std::make_unique<ProbeWriter>(dir, p, c, stop));
    ProbeWriter* w = probes_.back().get();
    add("probe:" + p.name, p.interval, [w](const Solver& s) { return w->write(s); });
  }
  if (c.snapshots) {
    snapshots_ = std::make_unique<SnapshotWriter>(dir, stop);
    add("snapshots", c.snapshot_interval > 0 ? c.snapshot_interval : c.output_interval, [this](const Solver& s) {
      snapshots_->write(s);  // the particle fields: checked by the solver's health check every step
      return std::optional<Failure>();
    });
  }
}

RunOutputs::RunOutputs(const fs::path& dir, const Case& c, const std::vector<OutputMark>& marks, real t0,
                       io::StopCheck stop)
    : scratch_(dir / ".resume") {
  std::error_code ec;
  fs::remove_all(scratch_, ec);  // left over by a resumed run that was killed
  fs::create_directories(scratch_, ec);
  if (ec) throw io::WriteError(fmt::format("cannot create '{}': {}", scratch_.string(), ec.message()));
  auto mark = [&](const std::string& key) {
    for (const auto& m : marks)
      if (m.stream == key) return m.last_scheduled;
    return -std::numeric_limits<real>::infinity();
  };

  bodies_ = std::make_unique<BodyHistoryWriter>(scratch_, c);
  std::vector<CsvRelay*> body_relays;  // bodies.csv, walls.csv and coefficients.csv: one stream
  for (const char* file : {"bodies.csv", "walls.csv", "coefficients.csv"}) {
    if (file == std::string("coefficients.csv") && !BodyHistoryWriter::writes_coefficients(c)) continue;
    csv_relays_.push_back(std::make_unique<CsvRelay>(scratch_ / file, dir / file, mark("bodies")));
    body_relays.push_back(csv_relays_.back().get());
  }
  add("bodies", c.output_interval, [this, body_relays](const Solver& s) {
    if (auto f = bodies_->write(s)) return f;
    for (CsvRelay* r : body_relays) r->pump();
    return std::optional<Failure>();
  });
  if (!c.inlets.empty() || !c.outlets.empty()) {
    open_ = std::make_unique<OpenBoundaryWriter>(scratch_);
    csv_relays_.push_back(std::make_unique<CsvRelay>(scratch_ / "open_boundaries.csv", dir / "open_boundaries.csv",
                                                     mark("open_boundaries")));
    CsvRelay* relay = csv_relays_.back().get();
    add("open_boundaries", c.output_interval, [this, relay](const Solver& s) {
      if (auto f = open_->write(s)) return f;
      relay->pump();
      return std::optional<Failure>();
    });
  }
  for (const auto& p : c.probes) {
    probes_.push_back(std::make_unique<ProbeWriter>(scratch_, p, c, stop));
    std::vector<CsvRelay*> relays;  // probe_<name>.csv and, for a line, flow_<name>.csv
    std::vector<std::string> files{probe_csv_name(p.name)};
    if (p.kind == ProbeKind::Line) files.push_back(flow_csv_name(p.name));
    for (const std::string& file : files) {
      csv_relays_.push_back(std::make_unique<CsvRelay>(scratch_ / file, dir / file, mark("probe:" + p.name)));
      relays.push_back(csv_relays_.back().get());
    }
    ProbeWriter* w = probes_.back().get();
    add("probe:" + p.name, p.interval, [w, relays](const Solver& s) {
      if (auto f = w->write(s)) return f;
      for (CsvRelay* r : relays) r->pump();
      return std::optional<Failure>();
    });
  }
  if (c.snapshots) {
    snapshots_ = std::make_unique<SnapshotWriter>(scratch_, stop);
    snapshot_relay_ = std::make_unique<SnapshotRelay>(scratch_, dir, mark("snapshots"));
    add("snapshots", c.snapshot_interval > 0 ? c.snapshot_interval : c.output_interval, [this](const Solver& s) {
      snapshots_->write(s);
      snapshot_relay_->pump();
      return std::optional<Failure>();
    });
  }
  resume_schedule(marks, t0);
}

void RunOutputs::resume_schedule(const std::vector<OutputMark>& marks, real t0) {
  for (Stream& s : streams_) {
    for (const auto& m : marks)
      if (m.stream == s.key) s.last_scheduled = m.last_scheduled;
    s.last_written = s.last_scheduled;
    // Exactly the next time an uninterrupted run had computed after its last scheduled write;
    // after the checkpoint when the interval was changed on resuming. A write due at the
    // checkpoint's time itself was given up (a stop request during a long output): it is due
    // at once.
    s.next = std::isfinite(s.last_scheduled) ? next_multiple(s.last_scheduled, s.interval) : 0;
    const real tol = 1e-9 * s.interval;
    if (s.next < t0 - tol) s.next = next_multiple(t0, s.interval);
  }
}

RunOutputs::~RunOutputs() {
  if (scratch_.empty()) return;
  std::error_code ec;
  fs::remove_all(scratch_, ec);
}

std::optional<Failure> RunOutputs::write(const Solver& solver, bool force) {
  const real t = solver.time();
  bool cancelled = false;
  std::optional<Failure> failure;
  for (Stream& s : streams_) {
    const bool due = t >= s.next - 1e-9 * s.interval;
    if (!due && !(force && s.last_written < t)) continue;
    try {
      if (auto f = s.write(solver)) {  // nothing written: the run ends with exit 3
        if (!failure) failure = std::move(f);
        continue;
      }
    } catch (const io::Cancelled&) {
      cancelled = true;
      continue;
    }
    s.last_written = t;
    if (due) {
      s.last_scheduled = t;
      s.next = next_multiple(t, s.interval);
    }
  }
  if (cancelled && !failure) throw io::Cancelled();
  return failure;
}

real RunOutputs::next_event(real t_end) const {
  real t = t_end;
  for (const Stream& s : streams_) t = std::min(t, s.next);
  return t;
}

std::vector<OutputMark> RunOutputs::marks() const {
  std::vector<OutputMark> m;
  for (const Stream& s : streams_) m.push_back({s.key, s.last_scheduled});
  return m;
}

}  // namespace particula::run_detail
