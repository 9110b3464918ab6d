// summary.json of a run (docs: README, "Outputs"): see session.hpp.
#include <omp.h>

#include "particula/case/schema.hpp"
#include "particula/run/observers.hpp"
#include "particula/run/version.hpp"
#include "session.hpp"

namespace particula::run_detail {

namespace {

/// The failure of a run as structured fields: reason, time, step, particle (null when the
/// failure is not a particle's) and position.
io::JsonObject failure_json(const Failure& f, real t, std::int64_t step) {
  io::JsonObject j;
  j.set("reason", f.what);
  j.set("time", t);
  j.set("step", step);
  if (f.particle_id >= 0)
    j.set("particle", f.particle_id);
  else
    j.set("particle", io::JsonRaw{"null"});
  j.set("position", std::vector<double>{f.position.x, f.position.y});
  return j;
}

/// The text of choice key `key` ("body[].shape") of element `index` of the case.
std::string choice_text(const Case& c, const char* key, std::size_t index) {
  const KeySpec* spec = find_key(key);
  const std::optional<Value> v = spec ? spec->bind.get(c, index) : std::nullopt;
  const auto* text = v ? std::get_if<std::string>(&*v) : nullptr;
  return text ? *text : "";
}

/// The legend of the body and wall numbers of bodies.csv, walls.csv and the snapshots' `body`
/// and `wall` arrays: index (case order), name, and for bodies shape and motion.
void add_legend(io::JsonObject& summary, const Case& c) {
  std::vector<io::JsonObject> bodies, walls;
  for (std::size_t k = 0; k < c.bodies.size(); ++k) {
    io::JsonObject b;
    b.set("index", k).set("name", c.bodies[k].name);
    b.set("shape", choice_text(c, "body[].shape", k)).set("motion", choice_text(c, "body[].motion", k));
    bodies.push_back(std::move(b));
  }
  for (std::size_t k = 0; k < c.walls.size(); ++k)
    walls.push_back(io::JsonObject().set("index", k).set("name", c.walls[k].name));
  summary.set("bodies", bodies);
  summary.set("walls", walls);
}

}  // namespace

io::JsonObject run_summary(const Session& s, const RunEnd& end, std::optional<double> profile_error) {
  const Solver& solver = *s.solver;
  const RunStats& st = s.stats;
  const double wall = st.wall_seconds();
  io::JsonObject summary;
  summary.set("case", s.c.name);
  summary.set("status", end.status);
  summary.set("exit_code", end.exit_code);
  if (end.failure) summary.set("failure", failure_json(*end.failure, solver.time(), solver.step_count()));
  if (!end.error.empty()) summary.set("error", end.error);
  summary.set("version", version());
  summary.set("commit", git_commit());
  summary.set("particles", static_cast<std::int64_t>(solver.particle_count()));
  summary.set("backend", std::string(solver.backend_name()));
  summary.set("fluid_particles", static_cast<std::int64_t>(s.n_fluid));
  summary.set("d0", s.c.d0);
  summary.set("h", solver.params().h);
  summary.set("steps", solver.step_count());
  summary.set("end_time", solver.time());
  if (s.resumed) summary.set("resumed_from", s.t_start);
  summary.set("dt_min", st.dt_min);
  summary.set("dt_max", st.dt_max);
  // The steps against the case's own (Solver::case_dt): how far the step fell, and how often it
  // stayed below kTimeStepDrop of it.
  io::JsonObject drops;
  drops.set("case_dt", solver.case_dt());
  drops.set("dt_min_ratio", st.dt_min / solver.case_dt());
  drops.set("threshold", kTimeStepDrop);
  drops.set("steps_below", st.dt_drop_steps);
  drops.set("reported_runs", st.dt_drop_reports);
  if (!std::isnan(st.dt_drop_first_time)) drops.set("first_reported_at", st.dt_drop_first_time);
  io::JsonObject limits;  // what set each step's length
  for (int k = 0; k < kStepLimits; ++k)
    limits.set(step_limit_name(static_cast<StepLimit>(k)), st.limited_by[static_cast<std::size_t>(k)]);
  drops.set("limited_by", limits);
  summary.set("time_step", drops);
  summary.set("overrides", s.overrides);
  add_legend(summary, s.c);
  summary.set("wall_seconds", wall);
  summary.set("threads", static_cast<std::int64_t>(omp_get_max_threads()));
  summary.set("particle_steps_per_second", wall > 0 ? st.particle_steps / wall : 0.0);
  summary.set("interactions_per_second", wall > 0 ? st.interactions / wall : 0.0);
  io::JsonObject guards;
  for (const auto& [name, count] : guard_events(solver.counters())) guards.set(name, count);
  summary.set("guard_events", guards);
  if (solver.params().load_band_motion > 0) summary.set("load_band_builds", solver.load_band_builds());
  if (!solver.open_flux().empty()) {
    summary.set("open_boundaries", open_boundary_summary(solver));
    std::vector<io::JsonObject> removed;
    for (const RigidGroup& g : solver.groups())
      if (g.removed)
        removed.push_back(
            io::JsonObject()
                .set("index", static_cast<std::int64_t>(g.body))
                .set("name", g.name)
                .set("time", g.removed_time)
                .set("outlet", solver.params().open_specs[static_cast<std::size_t>(g.removed_at)].name));
    summary.set("bodies_removed", removed);
    summary.set("fluid_mass", fluid_mass(solver.particles()));
  }
  for (const auto& p : s.outputs->probes())
    if (auto e = p->last_error()) summary.set("probe_error_" + p->spec().name, *e);
  if (profile_error) summary.set("profile_error", *profile_error);
  return summary;
}

}  // namespace particula::run_detail
