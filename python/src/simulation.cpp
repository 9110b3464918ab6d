// particula._core.Simulation: a case loaded (load_case, with the --set overrides) and built
// (build_scene) into a Solver, or a Solver restarted from a checkpoint as `particula resume` does;
// stepped from Python by one thread at a time; its particle fields exposed as NumPy views of the
// solver's arrays.
#include <fmt/format.h>
#include <omp.h>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <mutex>
#include <optional>
#include <type_traits>
#include <utility>

#include "bindings.hpp"
#include "particula/case/load.hpp"
#include "particula/io/error.hpp"
#include "particula/run/checkpoint.hpp"
#include "particula/run/limits.hpp"
#include "particula/run/observers.hpp"
#include "particula/run/runner.hpp"
#include "particula/scene/scene.hpp"

namespace py = pybind11;
namespace fs = std::filesystem;

namespace particula::python {

namespace {

// The views below read Vec2 arrays as (n, 2) arrays of doubles.
static_assert(std::is_standard_layout_v<Vec2> && sizeof(Vec2) == 2 * sizeof(real));
static_assert(sizeof(Kind) == sizeof(std::uint8_t));

/// A case and its solver, stepped by one thread at a time.
struct Simulation {
  Case c;
  std::uint64_t case_hash = 0;  // the case identity every checkpoint of it carries
  std::unique_ptr<Solver> solver;
  /// Held while a thread steps the solver (without the GIL) or writes its checkpoint.
  mutable std::mutex busy;
  /// The numerical failure that ended the last step; the state after it is not stepped further.
  std::optional<StepFailure> failed;

  /// The solver, for reading, when no other thread is stepping it (the GIL is held here, and a
  /// step takes `busy` with the GIL held, so no step starts before the reading ends).
  const Solver& idle() const {
    if (!busy.try_lock()) throw std::runtime_error(busy_message());
    busy.unlock();
    return *solver;
  }
  /// The particle state on the host (with the GPU backend, copied from the device when stale).
  const Particles& particles() const { return idle().particles(); }

  static std::string busy_message() {
    return "this Simulation is being stepped by another thread: step it from one thread at a time "
           "(a Simulation per thread, or a lock around its use)";
  }
};

/// `busy` held for one call (step, run_to, write_checkpoint); RuntimeError when another thread
/// holds it.
class Exclusive {
 public:
  explicit Exclusive(Simulation& sim) : lock_(sim.busy, std::try_to_lock) {
    if (!lock_.owns_lock()) throw std::runtime_error(Simulation::busy_message());
  }

 private:
  std::unique_lock<std::mutex> lock_;
};

/// Checks the backend before anything is built, as the CLI does; sets the OpenMP threads.
void prepare(const std::string& backend, int threads) {
  std::string why;
  if (backend != "cpu" && backend != "cuda")
    throw UsageError("backend '" + backend + "': unknown (cpu or cuda)");
  if (backend == "cuda" && !cuda_backend_available(&why)) throw UsageError("backend cuda: " + why);
  check_threads(threads);
  if (threads > 0) omp_set_num_threads(threads);
}

/// `particula run`'s set-up without the run directory: the case with its overrides, the size
/// guard, the scene and a fresh solver.
std::unique_ptr<Simulation> from_case(const fs::path& file, const std::vector<std::string>& overrides,
                                      const std::string& backend, int threads,
                                      const std::optional<std::string>& text = std::nullopt) {
  prepare(backend, threads);
  auto sim = std::make_unique<Simulation>();
  sim->c = text ? load_case_text(*text, file, overrides) : load_case(file, overrides);
  check_case_size(sim->c);  // before anything is allocated
  sim->case_hash = case_identity_hash(resolved_case_toml(sim->c));
  Scene scene = build_scene(sim->c);
  scene.params.cuda = backend == "cuda";
  sim->solver = std::make_unique<Solver>(scene.params, scene.domain, std::move(scene.particles),
                                         std::move(scene.groups));
  return sim;
}

/// `particula resume`'s set-up: the checkpoint read and checked against its case (with the
/// overrides `resume` allows), the solver restarted from it exactly as it was.
std::unique_ptr<Simulation> from_checkpoint(const fs::path& file, const std::vector<std::string>& overrides,
                                            const std::string& backend, int threads) {
  for (const auto& o : overrides)
    if (!resume_override_allowed(o))
      throw UsageError(
          "--set " + o +
          ": only time.end and output.* keys can be changed when resuming (the checkpoint fixes the rest "
          "of the case)");
  prepare(backend, threads);
  auto sim = std::make_unique<Simulation>();
  Checkpoint k = read_checkpoint(file);
  sim->c = load_case_text(k.case_toml, file, overrides);
  check_checkpoint_fits_case(k, sim->c, file);
  sim->case_hash = k.case_hash;
  const Domain domain{sim->c.domain_min, sim->c.domain_max, sim->c.periodic_x, sim->c.periodic_y};
  PhysicsParams prm = physics_params(sim->c);
  prm.cuda = backend == "cuda";
  sim->solver = std::make_unique<Solver>(prm, domain, std::move(k.particles), std::move(k.groups),
                                         SolverStart::Restart, k.time, k.step);
  sim->solver->set_counters(k.counters);
  sim->solver->set_open_flux(k.open_flux);
  sim->solver->set_load_band_state(k.load_band);
  return sim;
}

/// The checkpoint `particula run` writes, without output marks (a Simulation writes no outputs),
/// to a new file or over a particula checkpoint, never over anything else (why_not_checkpoint_target).
void write_simulation_checkpoint(Simulation& sim, const fs::path& file) {
  if (const auto why = why_not_checkpoint_target(file))
    throw io::WriteError(fmt::format("not writing a checkpoint to '{}': {}", file.string(), *why));
  const Exclusive only(sim);
  const Solver& s = *sim.solver;
  const std::string toml = resolved_case_toml(sim.c);
  const real t = s.time();
  const std::int64_t step = s.step_count();
  const std::vector<OutputMark> no_marks;
  write_checkpoint(file, CheckpointView{toml, sim.case_hash, t, step, s.counters(), no_marks, s.particles(),
                                        s.groups(), s.open_flux(), s.load_band_state()});
}

/// Raises the failure that ended an earlier step again: the state after it is not sound.
void refuse_after_failure(const Simulation& sim) {
  if (!sim.failed) return;
  const StepFailure& f = *sim.failed;
  throw StepFailure(fmt::format("this Simulation failed at t = {:.9g} s, step {} and steps no further (start "
                                "again from a checkpoint: Simulation.from_checkpoint); the failure: {}",
                                f.time, f.step, f.failure.what),
                    f);
}

/// One step of at most max_dt (0: the stable step), or with `land_at` one that ends exactly at that
/// time when it is limited by it; without the GIL (the caller holds `busy`); a failure is raised,
/// and refused from then on.
real step_held(Simulation& sim, real max_dt, std::optional<real> land_at = std::nullopt) {
  refuse_after_failure(sim);
  std::optional<Failure> failure;
  {
    py::gil_scoped_release nogil;
    failure = land_at ? sim.solver->step_to(*land_at) : sim.solver->step(max_dt);
  }
  if (failure) {
    sim.failed.emplace(*failure, sim.solver->time(), sim.solver->step_count());
    throw *sim.failed;
  }
  return sim.solver->last_dt();
}

/// Simulation.step(max_dt): max_dt is 0 (the stable step) or a positive, finite cap that
/// advances the time.
real step(Simulation& sim, real max_dt) {
  const Exclusive only(sim);
  const real t = sim.solver->time();
  if (!std::isfinite(max_dt) || max_dt < 0)
    throw py::value_error(fmt::format("step: max_dt = {} s: must be 0 (the stable step) or positive and finite",
                                      max_dt));
  if (max_dt > 0 && t + max_dt == t)
    throw py::value_error(fmt::format("step: max_dt = {} s is too small to advance t = {} s", max_dt, t));
  return step_held(sim, max_dt);
}

/// Steps until time t, the last step shortened to land on it (as the run loop lands on time.end);
/// Ctrl-C is honoured between steps. Returns the number of steps taken. t is finite and not before
/// the current time.
std::int64_t run_to(Simulation& sim, real t, const py::object& progress) {
  const Exclusive only(sim);
  const real now = sim.solver->time();
  if (!std::isfinite(t) || t < now)
    throw py::value_error(
        fmt::format("run_to: t = {} s: must be a finite time not before the current t = {} s", t, now));
  const std::int64_t first = sim.solver->step_count();
  const real eps = 1e-9 * std::abs(t);
  auto due = std::chrono::steady_clock::now();
  while (sim.solver->time() < t - eps) {
    step_held(sim, 0, t);
    if (PyErr_CheckSignals() != 0) throw py::error_already_set();
    // progress(time, t, step) every kProgressInterval s of wall time and after the last step
    const auto now = std::chrono::steady_clock::now();
    if (!progress.is_none() && (now >= due || sim.solver->time() >= t - eps)) {
      progress(sim.solver->time(), t, sim.solver->step_count());
      due = now + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                      std::chrono::duration<double>(kProgressInterval));
    }
  }
  return sim.solver->step_count() - first;
}

/// Makes a view read-only: the solver owns the state, and writing into it would bypass the
/// GPU upload and the rigid placement of boundary particles.
py::array read_only(py::array a) {
  a.attr("setflags")(py::arg("write") = false);
  return a;
}

/// A read-only view of `v` whose base is `owner` (the Python Simulation), so the memory lives
/// as long as the view.
template <class T>
py::array view(const std::vector<T>& v, py::handle owner) {
  return read_only(py::array_t<T>({v.size()}, {sizeof(T)}, v.data(), owner));
}

/// A Vec2 array as a read-only (n, 2) view.
py::array view(const std::vector<Vec2>& v, py::handle owner) {
  return read_only(py::array_t<real>({v.size(), std::size_t{2}}, {sizeof(Vec2), sizeof(real)},
                                     reinterpret_cast<const real*>(v.data()), owner));
}

py::array kind_view(const std::vector<Kind>& v, py::handle owner) {
  return read_only(py::array_t<std::uint8_t>({v.size()}, {sizeof(Kind)},
                                             reinterpret_cast<const std::uint8_t*>(v.data()), owner));
}

/// Per particle: the case index of the body (or wall, with `walls`) its boundary particle
/// belongs to, -1 for fluid particles and for the other kind of group (a copy).
py::array_t<std::int32_t> group_index(const Simulation& sim, bool walls) {
  const std::vector<std::int32_t> index = particle_case_index(sim.particles(), sim.idle().groups(), walls);
  py::array_t<std::int32_t> out(static_cast<py::ssize_t>(index.size()));
  std::copy(index.begin(), index.end(), out.mutable_data());
  return out;
}

/// Columns of per-group values (copies), one row per group selected.
class GroupTable {
 public:
  explicit GroupTable(std::size_t rows) : rows_(rows) {}
  void scalar(const char* name, const std::vector<real>& v) {
    table_[name] = py::array_t<real>(v.size(), v.data());
  }
  void vector(const char* name, const std::vector<Vec2>& v) {
    py::array_t<real> a({rows_, std::size_t{2}});
    auto o = a.mutable_unchecked<2>();
    for (std::size_t i = 0; i < rows_; ++i) {
      o(static_cast<py::ssize_t>(i), 0) = v[i].x;
      o(static_cast<py::ssize_t>(i), 1) = v[i].y;
    }
    table_[name] = a;
  }
  py::dict& dict() { return table_; }

 private:
  std::size_t rows_;
  py::dict table_;
};

const char* motion_name(Motion m) {
  switch (m) {
    case Motion::Fixed:
      return "fixed";
    case Motion::Prescribed:
      return "prescribed";
    case Motion::Free:
      return "free";
  }
  return "?";
}

/// The state of the bodies (or walls) in case order, as a dict of NumPy arrays (copies):
/// the columns of bodies.csv (walls.csv) and the mass properties.
py::dict group_states(const Simulation& sim, bool walls) {
  std::vector<const RigidGroup*> sel;
  for (const auto& g : sim.idle().groups())
    if (g.is_wall == walls) sel.push_back(&g);
  auto column = [&](auto get) {
    std::vector<std::decay_t<decltype(get(*sel[0]))>> v;
    for (const RigidGroup* g : sel) v.push_back(get(*g));
    return v;
  };
  GroupTable t(sel.size());
  py::list names, motions, removed;
  for (const RigidGroup* g : sel) {
    names.append(g->name);
    motions.append(motion_name(g->motion));
    removed.append(g->removed);  // taken out at an outlet (outlet[].bodies = "removed")
  }
  t.dict()["name"] = names;
  t.dict()["motion"] = motions;
  if (!walls) t.dict()["removed"] = removed;
  t.vector("position", column([](const RigidGroup& g) { return g.pos; }));
  t.vector("velocity", column([](const RigidGroup& g) { return g.vel; }));
  t.scalar("angle", column([](const RigidGroup& g) { return g.angle; }));
  t.scalar("omega", column([](const RigidGroup& g) { return g.omega; }));
  t.vector("force", column([](const RigidGroup& g) { return g.force_pressure + g.force_viscous; }));
  t.vector("force_pressure", column([](const RigidGroup& g) { return g.force_pressure; }));
  t.vector("force_viscous", column([](const RigidGroup& g) { return g.force_viscous; }));
  t.vector("force_damping", column([](const RigidGroup& g) { return g.force_damping; }));  // fdx, fdy
  t.scalar("torque", column([](const RigidGroup& g) { return g.torque; }));
  if (!walls) {
    t.vector("force_collision", column([](const RigidGroup& g) { return g.force_collision; }));
    t.scalar("torque_collision", column([](const RigidGroup& g) { return g.torque_collision; }));
    t.scalar("mass", column([](const RigidGroup& g) { return g.mass; }));
    t.scalar("inertia", column([](const RigidGroup& g) { return g.inertia; }));
    t.scalar("area", column([](const RigidGroup& g) { return g.area; }));
  }
  return t.dict();
}

/// Registers a read-only property returning a view of one particle array.
template <class Get>
void field(py::class_<Simulation>& cls, const char* name, Get get, const char* doc) {
  cls.def_property_readonly(
      name, [get](py::object self) { return view(get(self.cast<const Simulation&>().particles()), self); },
      doc);
}

}  // namespace

void check_threads(int threads) {
  if (threads < 0 || threads > kMaxThreads)
    throw UsageError(fmt::format("threads = {}: must be 1 .. {} (or 0: OpenMP's default)", threads, kMaxThreads));
  if (threads == 0)
    if (const std::string why = default_threads_problem(); !why.empty()) throw UsageError(why);
}

void register_simulation(py::module_& m) {
  m.attr("MAX_THREADS") = kMaxThreads;
  py::class_<Simulation> cls(m, "Simulation", "A case built into a solver (use particula.Simulation)");
  cls.def_static("from_case", &from_case, py::arg("case_file"), py::arg("overrides"), py::arg("backend"),
                 py::arg("threads"), py::arg("case_text") = std::nullopt)
      .def_static("from_checkpoint", &from_checkpoint, py::arg("file"), py::arg("overrides"),
                  py::arg("backend"), py::arg("threads"))
      .def("write_checkpoint", &write_simulation_checkpoint, py::arg("file"))
      .def(
          "step", [](Simulation& sim, real max_dt) { return step(sim, max_dt); }, py::arg("max_dt") = 0.0)
      .def("run_to", &run_to, py::arg("t"), py::arg("progress") = py::none())
      .def_property_readonly("time", [](const Simulation& s) { return s.idle().time(); })
      .def_property_readonly("step_count", [](const Simulation& s) { return s.idle().step_count(); })
      .def_property_readonly("dt", [](const Simulation& s) { return s.idle().last_dt(); })
      .def_property_readonly("n_particles", [](const Simulation& s) { return s.idle().particle_count(); })
      .def_property_readonly("n_boundary", [](const Simulation& s) { return s.particles().n_boundary; })
      .def_property_readonly("d0", [](const Simulation& s) { return s.idle().params().d0; })
      .def_property_readonly("h", [](const Simulation& s) { return s.idle().params().h; })
      .def_property_readonly("backend",
                             [](const Simulation& s) { return std::string(s.idle().backend_name()); })
      .def_property_readonly("case_toml", [](const Simulation& s) { return resolved_case_toml(s.c); })
      .def_property_readonly("guard_events",
                             [](const Simulation& s) {
                               const SolverCounters& c = s.idle().counters();
                               py::dict d;
                               for (const auto& [name, count] : guard_events(c)) d[name] = count;
                               return d;
                             })
      .def("body_states", [](const Simulation& s) { return group_states(s, false); })
      .def("wall_states", [](const Simulation& s) { return group_states(s, true); })
      .def_property_readonly("body_index", [](const Simulation& s) { return group_index(s, false); })
      .def_property_readonly("wall_index", [](const Simulation& s) { return group_index(s, true); });
  field(
      cls, "positions", [](const Particles& P) -> const auto& { return P.x; }, "(n, 2) positions (m), view");
  field(
      cls, "velocity", [](const Particles& P) -> const auto& { return P.v; }, "(n, 2) velocity (m/s), view");
  field(
      cls, "density", [](const Particles& P) -> const auto& { return P.rho; }, "(n,) density (kg/m^3), view");
  field(
      cls, "pressure", [](const Particles& P) -> const auto& { return P.p; }, "(n,) pressure (Pa), view");
  field(
      cls, "mass", [](const Particles& P) -> const auto& { return P.m; },
      "(n,) mass per unit depth (kg/m), view");
  field(
      cls, "group", [](const Particles& P) -> const auto& { return P.group; },
      "(n,) rigid group, -1 fluid, view");
  field(
      cls, "id", [](const Particles& P) -> const auto& { return P.id; }, "(n,) stable particle id, view");
  field(
      cls, "normals", [](const Particles& P) -> const auto& { return P.normal; },
      "(n_boundary, 2) surface normals of the boundary particles, view");
  cls.def_property_readonly(
      "kind",
      [](py::object self) { return kind_view(self.cast<const Simulation&>().particles().kind, self); },
      "(n,) uint8 kind: 0 fluid, 1 boundary (wall or body surface), 2 dummy, view");
}

}  // namespace particula::python
