// The case-file reference (docs/case-files.md), generated from the schema.
#include <fmt/format.h>

#include "internal.hpp"

namespace particula {
namespace {

constexpr const char* kHeader = R"(# Case-file reference

This page is generated from the case-file schema (`src/case/schema.cpp`) by
`particula::case_reference_markdown()`; do not edit it by hand. The test `test_case_schema`
(CaseDocs.ReferenceIsUpToDate) fails when this file differs from the generated text; run that
test with `PARTICULA_UPDATE_DOCS=1` in the environment to rewrite it.

A case file is TOML. Rules that hold for every key:

- All quantities are in SI units (column "Unit"; `-` means dimensionless).
- Unknown keys are errors; the message suggests the nearest known key.
- A `real` also accepts a TOML integer (`1` reads as `1.0`); an `integer` key rejects a float.
  `nan` and `inf` are rejected. `vec2` is `[x, y]` of reals, `bool2` is `[x, y]` of booleans.
- `vec2 list` is an array of points `[[x0, y0], [x1, y1], ...]`; `real4 table` is an array of
  rows of four reals `[[a, b, c, d], ...]` whose columns are named in the Type column. Both may
  span several lines (one point or row per line).
- Ranges: `[a, b]` includes its ends, `(a, b)` excludes them; the range of a `vec2` applies to
  each component.
- Some members of `[[body]]` are used only by some shapes or motions (Default column: "required
  for shape circle, half_disc", "only for motion prescribed"), and some of `[[inlet]]` only by
  some profiles; giving one for another shape, motion or profile is an error.
- On the command line, `--set key=value` overrides any key before the checks; the value is
  TOML (`--set fluid.gravity=[0,-9.81]`), and strings and choices also take a bare word
  (`--set numerics.laplacian=morris`). Members of arrays of tables are addressed by index from
  0: `--set probe.0.points=81`, `--set wall.1.velocity=[1e-5,0]`,
  `--set 'body.0.vertices=[[0,0],[1e-3,0],[0,1e-3]]'`.
- The run directory gets `case.toml`, the fully resolved case (every key, defaults filled in;
  viscosity written as `fluid.nu`).
- Beyond each key's range, the whole case is checked before anything is written (exit code 2,
  with the file, line and key): names (case, walls, probes, bodies, inlets, outlets) have at
  most 64 characters; every derived scale (d0, the domain, c, rho0 c^2, the particle mass rho0
  d0^2, 1/h^3, the time step, wall forces, accelerations, body masses and speeds) lies within
  [1e-150, 1e150], so that squares and products stay finite non-zero doubles (a case with
  every number times 1e150 is refused); the time step, estimated from d0, `fluid.c`,
  `fluid.nu` and the initial speeds, gives at most 1e9 steps to `time.end`; `time.dt_max`
  (when set) and every output interval (`output.*`, `probe[].interval`) are at least 1e-3 of
  that step, and each output stream makes at most 1e6 outputs; no speed the case sets at t = 0
  (a sliding or turning wall, a body's velocity, rotation or schedule, `initial.amplitude`, an
  inlet's full speed) reaches `fluid.c` (the weakly compressible fluid needs c at least 10 times
  the fastest speed of the flow). The sections below list the checks of walls, probes, bodies,
  inlets and outlets.

A minimal case:

```toml
name = "channel"

[domain]
min = [0.0, 0.0]
max = [1e-3, 1e-3]
periodic = [true, false]

[resolution]
d0 = 2.5e-5

[fluid]
nu = 1e-6
c = 0.1

[time]
end = 1.0

[output]
interval = 0.01

[[wall]]
from = [0.0, 0.0]
to = [1e-3, 0.0]

[[wall]]
from = [1e-3, 1e-3]
to = [0.0, 1e-3]
velocity = [-1e-3, 0.0]
```

A case with bodies: an ellipse falling onto a half-disc obstacle that sits on the left wall, and a
square paddle turned by a prescribed schedule. The keys of each body depend on its shape:
`center` and `radius` (circle, half_disc), `center` and `semi_axes` (ellipse), `vertices`
(polygon).

```toml
name = "obstacle"

[domain]
min = [0.0, 0.0]
max = [0.02, 0.06]

[resolution]
d0 = 1e-4

[fluid]
mu = 0.01
c = 0.5
gravity = [0.0, -9.81]

[time]
end = 2.0

[output]
interval = 0.01

[collision]
model = "spring_dashpot"  # the default: the stiffness is derived, nothing to tune
friction = 0.3

[[wall]]
from = [0.0, 0.0]
to = [0.02, 0.0]

[[wall]]
from = [0.02, 0.0]
to = [0.02, 0.06]

[[wall]]
from = [0.02, 0.06]
to = [0.0, 0.06]

[[wall]]
from = [0.0, 0.06]
to = [0.0, 0.0]

[[body]]
name = "ellipse"
shape = "ellipse"
center = [0.01, 0.054]
semi_axes = [0.002, 0.001]
density = 1100

[[body]]
name = "obstacle"
shape = "half_disc"
center = [0.0, 0.04]
radius = 0.01
motion = "fixed"

[[body]]
name = "paddle"
shape = "polygon"
vertices = [[0.014, 0.01], [0.018, 0.01], [0.018, 0.014], [0.014, 0.014]]
motion = "prescribed"
schedule = [
  [0.0, 0.0, 0.0, 0.0],
  [0.5, 0.0, 0.0, 2.0],
]
```

A fixed cylinder in a channel driven by a body force, with the drag and lift coefficients and the
Reynolds number of the cylinder (`[analysis]`: coefficients.csv), the flow rate through a line
probe across the channel (flow_inlet.csv) and a probe at two points (the second on the lower
wall, where it reads the wall's velocity):

```toml
name = "cylinder_in_channel"

[domain]
min = [0.0, 0.0]
max = [0.02, 0.01]
periodic = [true, false]

[resolution]
d0 = 1e-4

[fluid]
nu = 1e-4
c = 0.2
body_force = [0.05, 0.0]

[time]
end = 1.0

[output]
interval = 0.01

[analysis]
reference_velocity = [0.01, 0.0]  # the free stream: drag along +x
reference_length = 0.002          # the cylinder's diameter

[[wall]]
from = [0.0, 0.0]
to = [0.02, 0.0]

[[wall]]
from = [0.02, 0.01]
to = [0.0, 0.01]

[[body]]
name = "cylinder"
shape = "circle"
center = [0.01, 0.005]
radius = 0.001
motion = "fixed"

[[probe]]
name = "inlet"
from = [0.002, 0.0]
to = [0.002, 0.01]
points = 41
interval = 0.05

[[probe]]
name = "wake"
kind = "points"
at = [[0.014, 0.005], [0.014, 0.0]]
interval = 0.05
```
)";

/// Escapes what breaks a markdown table cell ('|') or reads as HTML ('<' outside code spans).
std::string cell(const std::string& s) {
  std::string out;
  bool in_code = false;
  for (const char ch : s) {
    if (ch == '`') in_code = !in_code;
    if (ch == '|' || (ch == '<' && !in_code)) out += '\\';
    out += ch;
  }
  return out;
}

std::string code(const std::string& s) { return s.empty() ? "" : "`" + s + "`"; }

std::string type_cell(const KeySpec& s) {
  if (s.type == ValueType::Real4Table)
    return fmt::format("{}: rows {}", type_name(s.type),
                       code(fmt::format("[{}]", fmt::join(s.columns, ", "))));
  if (s.type == ValueType::Choice) {
    std::string list;
    for (const std::string& c : s.choices) list += (list.empty() ? "" : " \\| ") + code(c);
    return "choice: " + list;
  }
  return type_name(s.type) + (s.identifier ? " (name)" : "");
}

std::string range_cell(const KeySpec& s) {
  if (s.identifier)
    return code("[A-Za-z0-9_-]+") + fmt::format(", at most {} characters", kMaxNameLength) +
           (s.unique ? ", unique" : "");
  if (s.type == ValueType::Vec2List) return fmt::format("at least {} points", s.min_items);
  if (s.type == ValueType::Real4Table) return fmt::format("at least {} rows", s.min_items);
  if (s.type == ValueType::Vec2Loops) return "at least 3 points each";
  if (s.type == ValueType::Vec2 && !s.range.text().empty()) return code(s.range.text()) + " each";
  return code(s.range.text());
}

std::string default_cell(const KeySpec& s) {
  if (s.need != Need::Default || !s.default_doc.empty()) return cell(default_text(s));
  return code(cell(default_text(s)));
}

std::string section_heading(const SectionSpec& s) {
  if (s.name.empty()) return "## Top level";
  return s.array ? fmt::format("## [[{}]] (array of tables)", s.name) : fmt::format("## [{}]", s.name);
}

/// One markdown table with the rows of a section.
std::string section_table(const SectionSpec& sec) {
  std::string out = fmt::format("\n{}\n\n{}\n\n", section_heading(sec), sec.meaning);
  out += "| Key | Type | Unit | Default | Range | Meaning |\n|---|---|---|---|---|---|\n";
  for (const KeySpec& s : case_schema()) {
    if (s.section() != sec.name) continue;
    out += fmt::format("| {} | {} | {} | {} | {} | {} |\n", code(s.key), type_cell(s), code(s.unit),
                       default_cell(s), range_cell(s), cell(s.meaning));
  }
  return out;
}

}  // namespace

std::string case_reference_markdown() {
  std::string out = kHeader;
  for (const SectionSpec& s : case_sections()) out += section_table(s);
  return out;
}

}  // namespace particula
