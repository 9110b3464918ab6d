// The sections of the case file, in documentation and output order: its tables ([fluid]) and
// arrays of tables ([[wall]]), each with its meaning (see include/particula/case/schema.hpp). The
// keys of each section are rows of the schema's table (schema.cpp).
#include <string>
#include <utility>
#include <vector>

#include "particula/case/schema.hpp"

namespace particula {
namespace {

/// An array of tables stored as std::vector<E> in Case.
template <class E>
SectionSpec array_section(std::string name, std::vector<E> Case::*m, std::string meaning) {
  return {std::move(name), true, std::move(meaning), [m](const Case& c) { return (c.*m).size(); },
          [m](Case& c, std::size_t n) { (c.*m).resize(n); }};
}

/// [[inlet]] or [[outlet]]: an array of OpenSpec whose elements all get `kind` when it is sized
/// (the kind is the section, not a key).
SectionSpec open_section(std::string name, std::vector<OpenSpec> Case::*m, OpenKind kind,
                         std::string meaning) {
  return {std::move(name), true, std::move(meaning), [m](const Case& c) { return (c.*m).size(); },
          [m, kind](Case& c, std::size_t n) {
            (c.*m).resize(n);
            for (OpenSpec& o : c.*m) o.kind = kind;
          }};
}

SectionSpec table_section(std::string name, std::string meaning) {
  return {std::move(name), false, std::move(meaning), {}, {}};
}

std::vector<SectionSpec> make_sections() {
  return {
      table_section("", "Top-level keys."),
      table_section("domain", "The rectangular computational domain and its periodicity."),
      table_section("resolution", "Particle spacing and kernel size."),
      table_section("fluid", "Fluid properties and forces on the fluid."),
      table_section("time", "Simulated time span and time-step control."),
      table_section(
          "numerics",
          "Discretisation schemes and their coefficients. The defaults are meant to work unchanged: "
          "they run the shipped cases and the robustness suite of `particula validate --group "
          "robustness` (untuned cases: piles of bodies, flows past bodies at Re 0.1 to 100, closing "
          "gaps; docs/validation.md). Change one only for a reason: `shifting_beta` (0.05, the top of the "
          "paper's range: "
          "lower values let particles pile into chains at the stagnation point between approaching "
          "bodies) down to the paper's 0.01-0.02 to reproduce its cases, or when shifting's "
          "smoothing of a sharp velocity gradient matters; `odd_even_damping` up (to 0.01) "
          "if column-wise alternating velocities appear at a high cell Reynolds number c d0 / nu, 0 "
          "to reproduce the paper's scheme; `surface_guard` and `film_gap` 0 only to study the scheme "
          "without them "
          "(guard_events in summary.json count its interventions: many events mean the flow is "
          "under-resolved next to a surface); `rhie_chow_factor` above 1 only to reproduce older "
          "runs; `normals = \"kernel\"` and `laplacian = \"morris\"` and `boundary = \"dummy\"` are "
          "the paper's baselines for comparison; `load_band_motion` 0 builds the loads' band every "
          "step (the kept band's reference: docs/validation.md, \"The kept band\"). A run that stops "
          "with exit 3 names the likely cause and the keys to look at."),
      table_section("initial", "Initial particle arrangement and velocity field."),
      table_section("output", "What is written to the run directory, and how often."),
      table_section("guard", "Bounds that stop a run that is blowing up."),
      table_section("validation", "Comparison with an exact solution."),
      table_section(
          "analysis",
          "References of the dimensionless coefficients: a body whose reference velocity and length "
          "are both known (from this table or its own [[body]] keys) gets rows in coefficients.csv "
          "(Re, C_D, C_L, C_M at every output.interval; README, \"What the output files hold\")."),
      table_section(
          "collision",
          "Contacts between bodies and between bodies and walls: a spring-dashpot law that needs no "
          "tuning (default), or the paper's repulsion P.38 generalised to the closest-surface "
          "distance."),
      array_section(
          "wall", &Case::walls,
          "Walls, one [[wall]] table each: straight segments and circular arcs, joined head to tail into "
          "chains; list a closed container counter-clockwise. The fluid fills the region on the left of "
          "the walls (and up to the domain's edges). Checked at load: a wall's chain ends only on the "
          "domain's edge or where it closes; a wall on an edge of the domain has the fluid (its left side) "
          "inside; walls that meet "
          "share an end point, one's `to` being the next one's `from`, at most two per point (ends "
          "closer than d0/2 must be equal); a wall is at least d0/2 long; no wall lies on a periodic "
          "edge, overlaps another on the same line, or comes within d0/2 of a body (a fixed body may "
          "stand on a wall with a flat side); a wall with a velocity slides along itself, so it must run "
          "along a periodic axis and share no end point with another wall; a turning wall stays in the "
          "domain and shares end points only with walls turning with it. The fluid sides of closed "
          "chains (loops joined head to tail, not through a periodic side) must agree: every region "
          "between walls is fluid or solid by all the walls round it. So a loop directly inside another "
          "turns the other way: in a container (counter-clockwise, fluid inside) obstacles are "
          "clockwise (fluid outside), and inside an obstacle only a pocket of fluid, counter-clockwise "
          "(a thick ring: a clockwise circle round a counter-clockwise one); a loop inside no other "
          "has outside it the kind of region the other walls (chains ending on the domain's edge or "
          "closing through a periodic side) give it there, an obstacle in a channel's fluid, and "
          "without such walls the outermost loops are all containers or all obstacles. A box of walls "
          "round a counter-clockwise circle is refused, naming both chains."),
      array_section(
          "probe", &Case::probes,
          "Probes, one [[probe]] table each: velocity and pressure interpolated at a line of points or "
          "at a list of points, by moving least squares over the fluid and surface particles (exact for "
          "quadratic fields: a point on a wall reads the wall's velocity). A line probe also writes its "
          "flow rate. Checked at load: every point inside the domain, the points of a line at least "
          "d0/100 apart (only a probe of length 0 may have 2 points at one place), at most 1e6 points "
          "over all probes (`info` counts their memory)."),
      array_section("body", &Case::bodies,
                    "Rigid bodies, one [[body]] table each: free, fixed or with prescribed motion. The keys "
                    "marked \"for shape\" or \"for motion\" are used by those shapes or motions only, and "
                    "giving them for another is an error."),
      open_section(
          "inlet", &Case::inlets, OpenKind::Inlet,
          "Inlets, one [[inlet]] table each: a straight segment on an edge of the domain where fluid "
          "enters with a prescribed speed along the inward normal (uniform, parabolic or from a table, "
          "optionally ramped up), fed by `layers` rows of buffer particles outside the domain behind it. "
          "Checked at load: the segment lies on an edge of the domain that is not periodic, with the "
          "fluid (its left side) inside; it is at least 4 d0 long; each end is a corner of the domain or "
          "the end of a wall; no wall runs along it and no wall that slides or turns ends on it; it "
          "overlaps no other inlet or outlet; the case has an outlet at least L_b + 2 h away (L_b = "
          "layers d0, the larger of the two); numerics.boundary is \"single_layer\"; every body starts on "
          "the fluid side of the boundary's screen, at least the contact distance from it. The screen "
          "is a line parallel to the segment, max(L_b + h, 5 h with numerics.force = \"momentum\") "
          "inside the fluid, that free bodies meet like a fixed wall and the fluid passes (a "
          "distributor plate, a sieve): it keeps bodies clear of the fluid that sets the buffer. With "
          "--backend cuda the open-boundary passes run on the host, the rest on the GPU."),
      open_section(
          "outlet", &Case::outlets, OpenKind::Outlet,
          "Outlets, one [[outlet]] table each: a straight segment on an edge of the domain where fluid "
          "leaves at a prescribed pressure, with `layers` rows of buffer particles outside the domain "
          "behind it. Checked at load as inlets (an outlet needs no inlet)."),
  };
}

}  // namespace

const std::vector<SectionSpec>& case_sections() {
  static const std::vector<SectionSpec> sections = make_sections();
  return sections;
}

const SectionSpec* find_section(std::string_view name) {
  for (const SectionSpec& s : case_sections())
    if (s.name == name) return &s;
  return nullptr;
}

}  // namespace particula
