// Checkpoint tampering for the tests of checkpoint checks: a small case with walls, a free and a
// fixed body, and a list of edits of a checkpoint's fields (indices, counts, kinds, ids, sizes,
// values, identity). Each edited checkpoint is written with encode_checkpoint, i.e. with a valid
// checksum, so only the consistency checks stand between it and the solver.
#pragma once

#include <cmath>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "particula/run/checkpoint.hpp"

namespace tamper {

/// A closed box with a free disc and a fixed post: 4 wall groups, then 2 body groups.
inline const char* const kCase = R"(name = "tamper"
[domain]
min = [0.0, 0.0]
max = [0.006, 0.006]
[resolution]
d0 = 2.0e-4
[fluid]
rho0 = 1000.0
mu = 0.01
c = 1.0
gravity = [0.0, -9.81]
[time]
end = 0.001
[output]
interval = 0.0005
[[wall]]
name = "bottom"
from = [0.0, 0.0]
to = [0.006, 0.0]
[[wall]]
name = "right"
from = [0.006, 0.0]
to = [0.006, 0.006]
[[wall]]
name = "top"
from = [0.006, 0.006]
to = [0.0, 0.006]
[[wall]]
name = "left"
from = [0.0, 0.006]
to = [0.0, 0.0]
[[body]]
name = "disc"
shape = "circle"
center = [0.002, 0.004]
radius = 1.0e-3
density = 1250.0
[[body]]
name = "post"
shape = "circle"
center = [0.0042, 0.0018]
radius = 1.0e-3
motion = "fixed"
)";

struct Tamper {
  std::string name;
  std::function<void(particula::Checkpoint&)> apply;
  /// Only `particula resume` can refuse it (it compares with the run directory's marker).
  bool needs_run_directory = false;
};

/// Edits of a checkpoint of kCase that must each be refused.
inline std::vector<Tamper> structured() {
  using particula::Checkpoint;
  using particula::Kind;
  using particula::Motion;
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  // Groups 0-3 are the walls, 4 the disc (free), 5 the post (fixed).
  auto fluid = [](const Checkpoint& k) { return k.particles.n_boundary; };
  auto surface = [](const Checkpoint& k) { return k.groups[4].first; };
  return {
      {"body index beyond the bodies", [](Checkpoint& k) { k.groups[4].body = 7; }},
      {"negative body index", [](Checkpoint& k) { k.groups[4].body = -3; }},
      {"body indices swapped", [](Checkpoint& k) { std::swap(k.groups[4].body, k.groups[5].body); }},
      {"wall with a body index", [](Checkpoint& k) { k.groups[0].body = 0; }},
      {"group range past the boundary block", [](Checkpoint& k) { k.groups[5].count += 10; }},
      {"overlapping group ranges", [](Checkpoint& k) { k.groups[1].first -= 1; }},
      {"huge group range", [](Checkpoint& k) { k.groups[5].first = std::numeric_limits<std::size_t>::max() - 2; }},
      {"boundary count above the particle count", [](Checkpoint& k) { k.particles.n_boundary = k.particles.size() + 5; }},
      {"boundary count below its arrays", [](Checkpoint& k) { k.particles.n_boundary -= 1; }},
      {"boundary block shortened",
       [](Checkpoint& k) {
         auto& P = k.particles;
         P.n_boundary -= 1;
         P.local.pop_back();
         P.normal_local.pop_back();
         P.ds.pop_back();
         P.acc.pop_back();
         P.normal.pop_back();
         P.source.pop_back();
       }},
      {"particle group out of range", [](Checkpoint& k) { k.particles.group[0] = 99; }},
      {"boundary particle without a group", [](Checkpoint& k) { k.particles.group[0] = -1; }},
      {"particle outside its group's range", [](Checkpoint& k) { k.particles.group[0] = 1; }},
      {"fluid particle with a group", [=](Checkpoint& k) { k.particles.group[fluid(k)] = 0; }},
      {"kind out of range", [=](Checkpoint& k) { k.particles.kind[fluid(k)] = static_cast<Kind>(7); }},
      {"fluid kind in the boundary block", [](Checkpoint& k) { k.particles.kind[0] = Kind::Fluid; }},
      {"boundary kind in the fluid block", [=](Checkpoint& k) { k.particles.kind[fluid(k)] = Kind::Boundary; }},
      {"dummy particle with the single-layer boundary",
       [=](Checkpoint& k) {
         k.particles.kind[surface(k)] = Kind::Dummy;
         k.particles.source[surface(k)] = static_cast<std::int32_t>(surface(k) + 1);
       }},
      {"dummy source out of range",
       [=](Checkpoint& k) {
         k.particles.kind[surface(k)] = Kind::Dummy;
         k.particles.source[surface(k)] = static_cast<std::int32_t>(k.particles.n_boundary + 100);
       }},
      {"dummy without a source",
       [=](Checkpoint& k) {
         k.particles.kind[surface(k)] = Kind::Dummy;
         k.particles.source[surface(k)] = -1;
       }},
      {"dummy source in another group",
       [=](Checkpoint& k) {
         k.particles.kind[surface(k)] = Kind::Dummy;
         k.particles.source[surface(k)] = 0;
       }},
      {"surface particle with a source", [](Checkpoint& k) { k.particles.source[0] = 1; }},
      {"duplicate particle id", [](Checkpoint& k) { k.particles.id[1] = k.particles.id[0]; }},
      {"particle id out of range",
       [](Checkpoint& k) { k.particles.id[0] = static_cast<std::int64_t>(k.particles.size()); }},
      {"negative particle id", [](Checkpoint& k) { k.particles.id[0] = -1; }},
      {"per-particle array shortened", [](Checkpoint& k) { k.particles.rho.pop_back(); }},
      {"boundary array shortened", [](Checkpoint& k) { k.particles.normal.pop_back(); }},
      {"rigid group missing", [](Checkpoint& k) { k.groups.pop_back(); }},
      {"rigid group added",
       [](Checkpoint& k) {
         auto g = k.groups.back();
         g.first = k.particles.n_boundary;
         g.count = 0;
         k.groups.push_back(g);
       }},
      {"rigid group renamed", [](Checkpoint& k) { k.groups[4].name = "another"; }},
      {"free body made fixed", [](Checkpoint& k) { k.groups[4].motion = Motion::Fixed; }},
      {"motion out of range", [](Checkpoint& k) { k.groups[4].motion = static_cast<Motion>(9); }},
      {"body made a wall", [](Checkpoint& k) { k.groups[5].is_wall = true; }},
      {"body with particles marked removed", [](Checkpoint& k) {
         k.groups[4].removed = true;
         k.groups[4].removed_at = 0;
       }},
      {"removal at an open boundary of a closed box", [](Checkpoint& k) { k.groups[4].removed_at = 0; }},
      {"NaN removal time", [=](Checkpoint& k) { k.groups[4].removed_time = nan; }},
      {"NaN position", [=](Checkpoint& k) { k.particles.x[fluid(k)].x = nan; }},
      {"infinite velocity", [=](Checkpoint& k) { k.particles.v[fluid(k)].y = inf; }},
      {"zero density", [=](Checkpoint& k) { k.particles.rho[fluid(k)] = 0; }},
      {"negative mass", [=](Checkpoint& k) { k.particles.m[fluid(k)] = -1; }},
      {"particle far outside the domain", [=](Checkpoint& k) { k.particles.x[fluid(k)] = {1e300, 0.003}; }},
      {"body far outside the domain", [](Checkpoint& k) { k.groups[4].pos = {1e200, 0.003}; }},
      {"free body without mass", [](Checkpoint& k) { k.groups[4].mass = 0; }},
      {"NaN body angle", [=](Checkpoint& k) { k.groups[4].angle = nan; }},
      {"NaN surface normal", [=](Checkpoint& k) { k.particles.normal[0].x = nan; }},
      {"negative surface length", [](Checkpoint& k) { k.particles.ds[0] = -1; }},
      {"kept load band of the wrong size",
       [](Checkpoint& k) {
         k.load_band.x = k.particles.x;
         k.load_band.pos.assign(k.groups.size() - 1, {0.003, 0.003});
         k.load_band.angle.assign(k.groups.size(), 0.0);
       }},
      {"kept load band without its particles",
       [](Checkpoint& k) {
         k.load_band.x.clear();
         k.load_band.pos.assign(k.groups.size(), {0.003, 0.003});
         k.load_band.angle.assign(k.groups.size(), 0.0);
       }},
      {"NaN in the kept load band",
       [=](Checkpoint& k) {
         k.load_band.x = k.particles.x;
         k.load_band.pos.assign(k.groups.size(), {0.003, 0.003});
         k.load_band.angle.assign(k.groups.size(), 0.0);
         k.load_band.x[fluid(k)].y = nan;
       }},
      {"NaN time", [=](Checkpoint& k) { k.time = nan; }},
      {"negative time", [](Checkpoint& k) { k.time = -1; }},
      {"negative step", [](Checkpoint& k) { k.step = -5; }},
      {"negative guard counter", [](Checkpoint& k) { k.counters.singular_B = -1; }},
      {"NaN output mark", [=](Checkpoint& k) { k.marks[0].last_scheduled = nan; }},
      {"output mark after the checkpoint", [](Checkpoint& k) { k.marks[0].last_scheduled = k.time + 1; }},
      {"case text of another case",
       [](Checkpoint& k) {
         k.case_toml = "name = \"other\"\n[domain]\nmin = [0.0, 0.0]\nmax = [0.006, 0.006]\n[resolution]\nd0 = "
                       "2.0e-4\n[fluid]\nnu = 1e-6\nc = 1.0\n[time]\nend = 1.0\n[output]\ninterval = 0.1\n";
       }},
      {"case text that is not TOML", [](Checkpoint& k) { k.case_toml = "name = [unterminated"; }},
      {"case identity of another case", [](Checkpoint& k) { k.case_hash ^= 1; }, true},
  };
}

}  // namespace tamper
