// Internals of the case module shared between its source files (not a public header).
#pragma once

#include <toml++/toml.h>

#include <cstddef>
#include <map>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include "particula/case/case.hpp"
#include "particula/case/error.hpp"
#include "particula/case/schema.hpp"

namespace particula::case_detail {

/// Name of the pseudo-file that override errors are reported in.
inline constexpr std::string_view kOverrideSource = "--set";

/// Where the keys of one load came from, so that any error can name a file and line.
/// Keys are concrete: "fluid.nu", "probe[1].points".
struct LoadContext {
  std::string file;                  // the case file as given
  std::map<std::string, int> lines;  // line of every key and table found in the document
  std::set<std::string> overridden;  // keys (and their parents) set by --set
  std::set<std::string> given;       // keys whose value came from the document (not defaults)

  /// A CaseError located at `key`: "--set" for overridden keys, else the key's line, else the
  /// line of its nearest enclosing table, else 0.
  CaseError error(const std::string& key, const std::string& message) const;
  /// As error(), but located at `line` (of one item of a list value) when it is known (> 0) and
  /// the key was not overridden.
  CaseError error_at(const std::string& key, int line, const std::string& message) const;
  /// Line of item `i` of the list value of `key` ("body[0].vertices"), 0 if unknown. The walk
  /// over the document records them as "body[0].vertices[2]".
  int item_line(const std::string& key, std::size_t i) const;
};

/// The concrete key of a schema key for element `index` ("wall[].from", 2 -> "wall[2].from").
std::string concrete_key(const std::string& schema_key, std::size_t index);
/// The schema form of a concrete key ("wall[2].from" -> "wall[].from").
std::string schema_form(const std::string& concrete);
/// Splits "a.b.c" at dots (empty parts kept).
std::vector<std::string> split_dots(std::string_view s);

/// True if `name` can be a plain (unquoted, dot-free) key component.
bool plain_component(std::string_view name);
/// True if some schema key lies below `prefix` + "." (a table section, e.g. "fluid").
bool is_table_section(std::string_view prefix);
/// True if some schema key lies below `prefix` + "[]." (an array of tables, e.g. "wall").
bool is_array_section(std::string_view prefix);
/// Message for an unknown concrete key, with a suggestion when a schema key is close.
std::string unknown_key_message(const std::string& concrete);

/// Converts and checks one TOML node against a row. Returns "" and sets `out` on success, or
/// an error message (wrong type, out of range, not a choice, bad name). For a problem with one
/// item of a list value, `element_line` (if given) receives the item's line.
std::string convert_node(const toml::node& node, const KeySpec& spec, Value& out,
                         int* element_line = nullptr);
/// True for value types that are lists of items (Vec2List, Real4Table, Vec2Loops).
inline bool is_list_type(ValueType t) {
  return t == ValueType::Vec2List || t == ValueType::Real4Table || t == ValueType::Vec2Loops;
}

/// Applies --set overrides to the parsed document (see load_case).
void apply_overrides(toml::table& root, const std::vector<std::string>& overrides, LoadContext& ctx);

/// Cost checks (cost_checks.cpp), run by run_cross_checks: derived scales within double range,
/// probes inside the domain and of a sensible size, time steps and output counts bounded, no
/// speed the case sets at or above the speed of sound.
void check_magnitudes(const Case& c, const LoadContext& ctx);
void check_probes(const Case& c, const LoadContext& ctx);
void check_references(const Case& c, const LoadContext& ctx);
void check_time_steps(const Case& c, const LoadContext& ctx);
void check_mach(const Case& c, const LoadContext& ctx);

/// "wall[2].from".
std::string wall_key(std::size_t k, std::string_view leaf);
/// "wall 'bottom' (wall[0])".
std::string wall_text(const Case& c, std::size_t k);

/// Checks of curved and turning walls and of the fluid region (wall_checks.cpp), run by
/// run_cross_checks: an arc's sweep, size and place (check_arc_wall, from check_walls), arcs on
/// other walls, turning walls inside the domain and joined only to walls turning with them, and
/// every chain closed or ending on the domain's edge.
void check_arc_wall(const Case& c, const LoadContext& ctx, std::size_t k);
void check_arc_overlap(const Case& c, const LoadContext& ctx);
void check_turning_walls(const Case& c, const LoadContext& ctx);
void check_region_closed(const Case& c, const LoadContext& ctx);
void check_spin_up(const Case& c, const LoadContext& ctx);
/// The fluid sides of closed chains of walls agree (wall_regions.cpp): nested loops turn opposite
/// ways, and a loop inside no other has the kind of the region it stands in on its outside.
void check_wall_regions(const Case& c, const LoadContext& ctx);

/// Checks of bodies (body_checks.cpp), run by run_cross_checks in this order: valid polygons
/// and holes, density of free bodies, schedules, fixed bodies without velocity, size against d0,
/// inside the domain, no overlap at t = 0.
void check_polygons(const Case& c, const LoadContext& ctx);
void check_density(const Case& c, const LoadContext& ctx);
void check_schedules(const Case& c, const LoadContext& ctx);
void check_fixed_bodies(const Case& c, const LoadContext& ctx);
void check_body_sizes(const Case& c, const LoadContext& ctx);
void check_bodies_in_domain(const Case& c, const LoadContext& ctx);
void check_body_overlap(const Case& c, const LoadContext& ctx);
/// A prescribed body's path up to time.end stays d0/2 clear of the walls, inside the domain's
/// closed edges and clear of fixed and prescribed bodies (path_checks.cpp).
void check_prescribed_paths(const Case& c, const LoadContext& ctx);

/// Checks of open boundaries (open_checks.cpp), run by run_cross_checks: check_open_boundaries
/// after the walls (names unique among inlets and outlets, layers, each segment on a bounded
/// domain edge with the fluid inside, at least 4 d0 wide, ending at corners or wall ends, no wall
/// along it, no overlap, no moving wall ending on it, inlet tables, an outlet for every inlet
/// and far enough from it, numerics.boundary single_layer); check_open_bodies after the bodies
/// (no body within reach of an open segment at t = 0).
void check_open_boundaries(const Case& c, const LoadContext& ctx);
void check_open_bodies(const Case& c, const LoadContext& ctx);

/// Consistency checks between keys (domain, walls, periodic width, bodies, ...); throw CaseError.
void run_cross_checks(const Case& c, const LoadContext& ctx);

/// A point or vector as the case file writes it, e.g. [0.1, 0.2] (for the checks' messages).
inline std::string vec(Vec2 v) { return format_toml_value(Value{v}); }

/// Component `axis` (0: x, 1: y) of v.
inline real component(Vec2 v, int axis) { return axis == 0 ? v.x : v.y; }

}  // namespace particula::case_detail
