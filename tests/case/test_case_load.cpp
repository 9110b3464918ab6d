// Case files: valid cases load with their defaults; every kind of user error gives a CaseError
// naming the file, line and key.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "particula/case/load.hpp"

using namespace particula;

namespace {

const std::string kFile = "cases/test.toml";

/// The smallest valid case: only the required keys (integers where reals are expected).
const std::string kMinimal = R"(name = "mini"

[domain]
min = [0, 0]
max = [1e-3, 1e-3]

[resolution]
d0 = 2.5e-5

[fluid]
nu = 1e-6
c = 0.1

[time]
end = 1

[output]
interval = 0.01
)";

/// `text` with the first occurrence of `from` replaced by `to` (which must exist).
std::string with(std::string text, const std::string& from, const std::string& to) {
  const auto p = text.find(from);
  EXPECT_NE(p, std::string::npos) << "fixture lacks: " << from;
  if (p != std::string::npos) text.replace(p, from.size(), to);
  return text;
}

/// 1-based line of the first occurrence of `needle` in `text`.
int line_of(const std::string& text, const std::string& needle) {
  const auto p = text.find(needle);
  EXPECT_NE(p, std::string::npos) << needle;
  return 1 + static_cast<int>(std::count(text.begin(), text.begin() + static_cast<long>(p), '\n'));
}

/// The CaseError thrown by loading `text` (a test failure if it loads or throws anything else).
CaseError error_of(const std::string& text, const std::vector<std::string>& overrides = {}) {
  try {
    load_case_text(text, kFile, overrides);
  } catch (const CaseError& e) {
    return e;
  }
  ADD_FAILURE() << "expected a CaseError for:\n" << text;
  return CaseError("", 0, "", "");
}

/// Asserts an error at `key`, on the line of `needle` in `text`, whose message contains `part`.
void expect_error(const std::string& text, const std::string& key, const std::string& needle,
                  const std::string& part) {
  const CaseError e = error_of(text);
  EXPECT_EQ(e.file(), kFile) << e.what();
  EXPECT_EQ(e.key(), key) << e.what();
  EXPECT_EQ(e.line(), line_of(text, needle)) << e.what();
  EXPECT_NE(e.message().find(part), std::string::npos) << e.what();
}

/// A temporary file holding `text`, removed at scope exit.
struct TempFile {
  std::filesystem::path path;
  explicit TempFile(const std::string& text, const std::string& name = "case.toml") {
    const auto dir =
        std::filesystem::temp_directory_path() / ("particula_test_case_load_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    path = dir / name;
    std::ofstream(path, std::ios::binary) << text;
  }
  ~TempFile() { std::filesystem::remove_all(path.parent_path()); }
};

}  // namespace

// ---------------------------------------------------------------------------------------------
// Valid cases.

TEST(CaseLoad, MinimalCaseGetsDefaults) {
  const Case c = load_case_text(kMinimal, kFile);
  const Case d = default_case();  // the schema's defaults
  EXPECT_EQ(c.name, "mini");
  EXPECT_EQ(c.description, "");
  EXPECT_EQ(c.source, kFile);
  EXPECT_EQ(c.domain_min.x, 0.0);
  EXPECT_EQ(c.domain_max.y, 1e-3);
  EXPECT_FALSE(c.periodic_x);
  EXPECT_FALSE(c.periodic_y);
  EXPECT_EQ(c.d0, 2.5e-5);
  EXPECT_EQ(c.h_over_d0, 2.6);
  EXPECT_EQ(c.rho0, 1000.0);
  EXPECT_EQ(c.nu, 1e-6);
  EXPECT_EQ(c.c, 0.1);
  EXPECT_EQ(c.p0, d.p0);
  EXPECT_EQ(c.gravity.y, 0.0);
  EXPECT_EQ(c.gravity_in_fluid, d.gravity_in_fluid);
  EXPECT_EQ(c.t_end, 1.0);  // TOML integer accepted as a real
  EXPECT_EQ(c.cfl, 0.5);
  EXPECT_EQ(c.dt_max, 0.0);
  EXPECT_EQ(c.max_steps, 0);
  EXPECT_EQ(c.laplacian, LaplacianScheme::FatehiManzari);
  EXPECT_EQ(c.boundary, BoundaryModel::SingleLayer);
  EXPECT_EQ(c.normals, NormalModel::Analytic);
  EXPECT_EQ(c.rhie_chow_factor, 1.0);
  EXPECT_EQ(c.shifting_beta, 0.05);
  EXPECT_EQ(c.film_gap, 2.0);
  EXPECT_EQ(c.wall_pressure_sweeps, 1);
  EXPECT_EQ(c.perturbation, 0.05);
  EXPECT_EQ(c.seed, 1u);
  EXPECT_EQ(c.initial_flow, InitialFlow::Rest);
  EXPECT_EQ(c.initial_amplitude, 1.0);
  EXPECT_FALSE(c.hydrostatic);
  EXPECT_EQ(c.output_interval, 0.01);
  EXPECT_TRUE(c.snapshots);
  EXPECT_EQ(c.snapshot_interval, 0.0);
  EXPECT_EQ(c.checkpoint_interval, 0.0);
  EXPECT_EQ(c.rho_min_ratio, 0.5);
  EXPECT_EQ(c.rho_max_ratio, 2.0);
  EXPECT_TRUE(c.walls.empty());
  EXPECT_TRUE(c.probes.empty());
}

TEST(CaseLoad, ChoicesWallsAndProbes) {
  // Periodic along x: the lid slides along x.
  const std::string text = with(kMinimal, "max = [1e-3, 1e-3]", "max = [1e-3, 1e-3]\nperiodic = [true, false]") + R"(
[numerics]
laplacian = "morris"
boundary = "dummy"
normals = "analytic"

[initial]
flow = "taylor_green"
amplitude = 1e-3

[[wall]]
from = [0, 0]
to = [1e-3, 0]

[[wall]]
name = "lid"
from = [1e-3, 1e-3]
to = [0, 1e-3]
velocity = [1e-3, 0]

[[probe]]
name = "mid"
from = [5e-4, 0]
to = [5e-4, 1e-3]
points = 11
interval = 0.1
)";
  const Case c = load_case_text(text, kFile);
  EXPECT_EQ(c.laplacian, LaplacianScheme::Morris);
  EXPECT_EQ(c.boundary, BoundaryModel::Dummy);
  EXPECT_EQ(c.normals, NormalModel::Analytic);
  EXPECT_EQ(c.initial_flow, InitialFlow::TaylorGreen);
  ASSERT_EQ(c.walls.size(), 2u);
  EXPECT_EQ(c.walls[0].name, "wall0");
  EXPECT_EQ(c.walls[1].name, "lid");
  EXPECT_EQ(c.walls[1].velocity.x, 1e-3);
  EXPECT_EQ(c.walls[0].velocity.x, 0.0);
  ASSERT_EQ(c.probes.size(), 1u);
  EXPECT_EQ(c.probes[0].name, "mid");
  EXPECT_EQ(c.probes[0].points, 11);
  EXPECT_EQ(c.probes[0].interval, 0.1);
}

TEST(CaseLoad, DynamicViscosityBecomesKinematic) {
  const Case c = load_case_text(
      with(with(kMinimal, "nu = 1e-6", "mu = 2e-3"), "[fluid]", "[fluid]\nrho0 = 2000"), kFile);
  EXPECT_DOUBLE_EQ(c.nu, 1e-6);
  EXPECT_DOUBLE_EQ(c.mu(), 2e-3);
}

TEST(CaseLoad, WallEndpointsWithinToleranceOfTheDomain) {
  // 1e-7 * d0 outside the box is inside the tolerance d0 * 1e-6.
  const std::string text = kMinimal + "[[wall]]\nfrom = [0, 0]\nto = [1.0000000000025e-3, 0]\n";
  EXPECT_NO_THROW(load_case_text(text, kFile));
}

TEST(CaseLoad, FromFile) {
  const TempFile f(kMinimal);
  const Case c = load_case(f.path);
  EXPECT_EQ(c.name, "mini");
  EXPECT_EQ(c.source, f.path);
}

// ---------------------------------------------------------------------------------------------
// The file itself.

TEST(CaseLoadErrors, MissingFile) {
  try {
    load_case("no/such/case.toml");
    FAIL() << "no error";
  } catch (const CaseError& e) {
    EXPECT_EQ(e.file(), "no/such/case.toml");
    EXPECT_EQ(e.line(), 0);
    EXPECT_STREQ(e.what(), "no/such/case.toml: case file not found");
  }
}

TEST(CaseLoadErrors, DirectoryIsNotACaseFile) {
  const TempFile f(kMinimal);
  try {
    load_case(f.path.parent_path());
    FAIL() << "no error";
  } catch (const CaseError& e) {
    EXPECT_NE(e.message().find("directory"), std::string::npos) << e.what();
  }
}

TEST(CaseLoadErrors, UnreadableFile) {
  const TempFile f(kMinimal);
  std::filesystem::permissions(f.path, std::filesystem::perms::none);
  if (std::ifstream(f.path).good()) GTEST_SKIP() << "running with permissions that read anything";
  EXPECT_THROW(load_case(f.path), CaseError);
}

TEST(CaseLoadErrors, TomlSyntaxErrorHasTheLine) {
  const std::string text = with(kMinimal, "c = 0.1", "c = = 0.1");
  const CaseError e = error_of(text);
  EXPECT_EQ(e.line(), line_of(text, "c = = 0.1")) << e.what();
  EXPECT_EQ(e.key(), "");
  EXPECT_NE(e.message().find("TOML syntax error"), std::string::npos) << e.what();
}

TEST(CaseLoadErrors, DuplicateKeyIsASyntaxError) {
  const std::string text = with(kMinimal, "c = 0.1", "c = 0.1\nc = 0.2");
  EXPECT_EQ(error_of(text).line(), line_of(text, "c = 0.2"));
}

TEST(CaseLoadErrors, BinaryGarbage) {
  const std::string text = kMinimal + std::string("\x00\xff\xfe\x01 = \x80", 8);
  EXPECT_GT(error_of(text).line(), 0);
}

// ---------------------------------------------------------------------------------------------
// Keys.

TEST(CaseLoadErrors, UnknownKeySuggestsTheNearest) {
  const std::string text = with(kMinimal, "nu = 1e-6", "nu = 1e-6\nnuu = 1e-6");
  const CaseError e = error_of(text);
  EXPECT_EQ(e.key(), "fluid.nuu");
  EXPECT_EQ(e.line(), 12);
  EXPECT_STREQ(e.what(), "cases/test.toml:12: key 'fluid.nuu': unknown key (did you mean 'fluid.nu'?)");
}

TEST(CaseLoadErrors, UnknownSectionAndArrayMemberSuggestions) {
  expect_error(with(kMinimal, "[time]", "[tme]"), "tme", "[tme]", "did you mean 'time'?");
  const std::string probe = kMinimal +
                            "[[probe]]\nname = \"p\"\nfrom = [0, 0]\nto = [0, 1e-3]\npoints = 3\n"
                            "intervall = 0.1\n";
  expect_error(probe, "probe[0].intervall", "intervall", "did you mean 'probe[0].interval'?");
}

TEST(CaseLoadErrors, UnknownKeyFarFromAllGetsNoSuggestion) {
  const std::string text = with(kMinimal, "name = \"mini\"", "name = \"mini\"\nbanana_split = 3");
  const CaseError e = error_of(text);
  EXPECT_EQ(e.key(), "banana_split");
  EXPECT_EQ(e.message(), "unknown key");
}

TEST(CaseLoadErrors, QuotedDottedKeyIsNotAKey) {
  const std::string text = with(kMinimal, "name = \"mini\"", "name = \"mini\"\n\"fluid.c\" = 1");
  EXPECT_EQ(error_of(text).key(), "fluid.c");
  EXPECT_EQ(error_of(text).line(), 2);
}

TEST(CaseLoadErrors, MissingRequiredKey) {
  expect_error(with(kMinimal, "c = 0.1\n", ""), "fluid.c", "[fluid]", "missing required key");
  const CaseError e = error_of(with(kMinimal, "name = \"mini\"", ""));
  EXPECT_EQ(e.key(), "name");
  EXPECT_EQ(e.line(), 0);  // no table to point at
  const std::string probe = kMinimal + "[[probe]]\nname = \"p\"\nfrom = [0, 0]\nto = [0, 1e-3]\npoints = 3\n";
  expect_error(probe, "probe[0].interval", "[[probe]]", "missing required key (real, s)");
}

TEST(CaseLoadErrors, WrongType) {
  expect_error(with(kMinimal, "c = 0.1", "c = \"fast\""), "fluid.c",
               "c = ", "expected a real number, got a string");
}

TEST(CaseLoadErrors, WrongTypeDetails) {
  const auto msg = [](const std::string& text) { return error_of(text).message(); };
  EXPECT_EQ(msg(kMinimal + "[numerics]\nwall_pressure_sweeps = 2.0\n"),
            "wrong type: expected an integer, got a float");
  EXPECT_EQ(msg(with(kMinimal, "max = [1e-3, 1e-3]", "max = [1e-3, 1e-3, 0]")),
            "wrong type: expected an array of two real numbers [x, y], got an array of 3 elements");
  EXPECT_EQ(msg(with(kMinimal, "max = [1e-3, 1e-3]", "max = [1e-3, \"y\"]")),
            "wrong type: expected an array of two real numbers [x, y], got an array of 2 elements");
  EXPECT_EQ(msg(with(kMinimal, "max = [1e-3, 1e-3]", "max = [1e-3, 1e-3]\nperiodic = [true, 1]")),
            "wrong type: expected an array of two booleans [x, y], got an array of 2 elements");
  EXPECT_EQ(msg(with(kMinimal, "name = \"mini\"", "name = 3")),
            "wrong type: expected a string, got an integer");
  EXPECT_EQ(msg(kMinimal + "[initial]\nhydrostatic = \"yes\"\n"),
            "wrong type: expected true or false, got a string");
  EXPECT_EQ(msg(with(kMinimal, "d0 = 2.5e-5", "d0 = 1979-05-27")),
            "wrong type: expected a real number, got a date");
}

TEST(CaseLoadErrors, SectionGivenAsValueOrArray) {
  expect_error("time = 1\n" + with(kMinimal, "[time]\nend = 1\n", ""), "time", "time = 1",
               "expected a table [time]");
  expect_error(with(kMinimal, "[time]", "[[time]]"), "time", "[[time]]", "expected a table [time]");
  expect_error(kMinimal + "[wall]\nfrom = [0, 0]\n", "wall", "[wall]",
               "expected an array of tables [[wall]]");
  expect_error(with(kMinimal, "c = 0.1\n", "") + "[fluid.c]\nx = 1\n", "fluid.c", "[fluid.c]",
               "expected a real number, got a table");
}

TEST(CaseLoadErrors, OutOfRangeSaysRangeAndUnit) {
  expect_error(with(kMinimal, "d0 = 2.5e-5", "d0 = 0"), "resolution.d0", "d0 = 0",
               "value 0 is out of range: must be > 0 m");
  expect_error(with(kMinimal, "d0 = 2.5e-5", "d0 = 2.5e-5\nh_over_d0 = 4.5"), "resolution.h_over_d0",
               "h_over_d0", "value 4.5 is out of range: must be in [1.5, 4]");
  expect_error(kMinimal + "[guard]\nrho_min_ratio = 1\n", "guard.rho_min_ratio", "rho_min_ratio",
               "must be in (0, 1)");
  expect_error(with(kMinimal, "end = 1", "end = 1\ncfl = 0"), "time.cfl", "cfl", "must be in (0, 1]");
  expect_error(with(kMinimal, "end = 1", "end = 1\nmax_steps = -1"), "time.max_steps", "max_steps",
               "value -1 is out of range: must be >= 0");
  expect_error(with(kMinimal, "interval = 0.01", "interval = -0.01"), "output.interval", "interval",
               "must be > 0 s");
}

TEST(CaseLoadErrors, NonFiniteNumbersAreOutOfRange) {
  expect_error(with(kMinimal, "c = 0.1", "c = nan"), "fluid.c", "c = nan", "must be a finite number > 0 m/s");
  expect_error(with(kMinimal, "c = 0.1", "c = inf"), "fluid.c", "c = inf", "finite");
  expect_error(with(kMinimal, "c = 0.1", "c = 0.1\ngravity = [0, -inf]"), "fluid.gravity", "gravity",
               "must be a finite number");
  // Huge but finite numbers pass the key's range, and then the check of the case's scales.
  expect_error(with(kMinimal, "c = 0.1", "c = 1e308"), "fluid.c", "c = 1e308", "outside [1e-150, 1e+150]");
  EXPECT_NO_THROW(load_case_text(with(kMinimal, "c = 0.1", "c = 1e3"), kFile));
  // Integers too large for TOML are syntax errors.
  EXPECT_GT(error_of(with(kMinimal, "end = 1", "end = 1\nmax_steps = 99999999999999999999")).line(), 0);
}

TEST(CaseLoadErrors, ChoiceNotInListListsTheChoices) {
  expect_error(kMinimal + "[numerics]\nlaplacian = \"brookshaw\"\n", "numerics.laplacian", "laplacian",
               "'brookshaw' is not a valid choice: expected one of fatehi_manzari, morris");
}

TEST(CaseLoadErrors, InvalidName) {
  expect_error(with(kMinimal, "name = \"mini\"", "name = \"my case\""), "name", "name =", "not a valid name");
  expect_error(with(kMinimal, "name = \"mini\"", "name = \"\""), "name", "name =", "not a valid name");
}

TEST(CaseLoadErrors, NamesAtMost64Characters) {
  // Names become file names (runs/<name>, probe_<name>.csv) and columns: a 300-character probe name
  // would fail with "File name too long" after the run directory was made.
  const std::string ok(64, 'n'), long_name(65, 'n');
  const std::string walls_probes = kMinimal +
                                   "\n[[wall]]\nname = \"w\"\nfrom = [0, 0]\nto = [1e-3, 0]\n"
                                   "\n[[probe]]\nname = \"p\"\nfrom = [5e-4, 0]\nto = [5e-4, 1e-3]\npoints = 11\n"
                                   "interval = 0.1\n";
  for (const auto& [key, needle] : {std::pair{"name", "name = \"mini\""}, std::pair{"wall[0].name", "name = \"w\""},
                                    std::pair{"probe[0].name", "name = \"p\""}}) {
    const std::string from = needle;
    EXPECT_NO_THROW(load_case_text(with(walls_probes, from, "name = \"" + ok + "\""), kFile)) << key;
    expect_error(with(walls_probes, from, "name = \"" + long_name + "\""), key, "name = \"" + long_name,
                 "'nnnnnnnnnnnnnnnn...' (65 characters) is too long: a name becomes part of file names and "
                 "columns, at most 64 characters");
  }
  // Through --set as well (file "--set", no line).
  const CaseError e = error_of(walls_probes, {"probe.0.name=" + std::string(300, 'a')});
  EXPECT_EQ(e.file(), "--set");
  EXPECT_EQ(e.key(), "probe[0].name");
  EXPECT_NE(e.message().find("(300 characters) is too long"), std::string::npos) << e.what();
}

// ---------------------------------------------------------------------------------------------
// Consistency between keys.

TEST(CaseLoadErrors, ViscosityBothOrNeither) {
  expect_error(with(kMinimal, "nu = 1e-6", "nu = 1e-6\nmu = 1e-3"), "fluid.mu", "mu = 1e-3",
               "give only one of 'fluid.nu' or 'fluid.mu'");
  expect_error(with(kMinimal, "nu = 1e-6\n", ""), "fluid.nu", "[fluid]",
               "missing required key: give one of 'fluid.nu' or 'fluid.mu'");
}

TEST(CaseLoadErrors, DomainMaxNotAboveMin) {
  expect_error(with(kMinimal, "max = [1e-3, 1e-3]", "max = [1e-3, 0]"), "domain.max",
               "max =", "must be greater than domain.min");
  expect_error(with(kMinimal, "max = [1e-3, 1e-3]", "max = [-1e-3, 1e-3]"), "domain.max", "max =", "");
}

TEST(CaseLoadErrors, PeriodicDomainNarrowerThanThreeH) {
  // 3 h = 3 * 2.6 * 2.5e-5 = 1.95e-4 m.
  const std::string text =
      with(kMinimal, "max = [1e-3, 1e-3]", "max = [1.9e-4, 1e-3]\nperiodic = [true, false]");
  expect_error(text, "domain.periodic", "periodic", "periodic along x needs the domain to be at least 3 h");
  EXPECT_NO_THROW(load_case_text(with(text, "[true, false]", "[false, true]"), kFile));
}

TEST(CaseLoadErrors, WallVelocityMustBeTangential) {
  const std::string text = kMinimal + "\n[[wall]]\nfrom = [0, 0]\nto = [1e-3, 1e-3]\nvelocity = [1, 0.999]\n";
  expect_error(text, "wall[0].velocity", "velocity", "wall velocity must be tangential");
  // Tangential, so the next check speaks: a sliding wall must run along a periodic axis.
  expect_error(with(text, "[1, 0.999]", "[-2, -2]"), "wall[0].velocity", "velocity",
               "does not run along a periodic axis");
}

TEST(CaseLoadErrors, WallOutsideTheDomainOrOfZeroLength) {
  expect_error(kMinimal + "[[wall]]\nfrom = [0, 0]\nto = [1.1e-3, 0]\n", "wall[0].to", "to = [1.1e-3",
               "lies outside the domain");
  expect_error(kMinimal + "[[wall]]\nfrom = [0, 0]\nto = [0, 0]\n", "wall[0].to", "to = [0, 0]",
               "zero length");
}

TEST(CaseLoadErrors, DuplicateProbeName) {
  const std::string probe =
      "[[probe]]\nname = \"p\"\nfrom = [0, 0]\nto = [0, 1e-3]\npoints = 3\ninterval = 1\n";
  const std::string text = kMinimal + probe + "\n" + probe;
  const CaseError e = error_of(text);
  EXPECT_EQ(e.key(), "probe[1].name");
  EXPECT_EQ(e.line(), 27) << e.what();
  EXPECT_NE(e.message().find("duplicate probe name \"p\" (already used by probe[0].name)"), std::string::npos)
      << e.what();
}

TEST(CaseLoadErrors, ProbePointsRequiredAndAtLeastTwo) {
  const std::string probe = kMinimal +
                            "[[probe]]\nname = \"p\"\nfrom = [0, 0]\nto = [0, 1e-3]\npoints = 1\n"
                            "interval = 1\n";
  expect_error(probe, "probe[0].points", "points", "must be in [2, 1000000]");
  expect_error(with(probe, "points = 1\n", ""), "probe[0].points", "[[probe]]", "missing required key");
}

// ---------------------------------------------------------------------------------------------
// Probes at points and coefficient references.

namespace {
const std::string kPointProbe = kMinimal + R"(
[[probe]]
name = "spots"
kind = "points"
at = [[5e-4, 5e-4], [5e-4, 0.0]]
interval = 0.1
)";

/// kMinimal with a fixed circle of radius 2e-4 m (16 particles across) and `extra` appended.
std::string with_body(const std::string& analysis, const std::string& body_extra) {
  return kMinimal + analysis + R"(
[[body]]
name = "disc"
shape = "circle"
center = [5e-4, 5e-4]
radius = 2e-4
motion = "fixed"
)" + body_extra;
}
}  // namespace

TEST(CaseLoad, PointProbeLoadsItsPoints) {
  const Case c = load_case_text(kPointProbe, kFile);
  ASSERT_EQ(c.probes.size(), 1u);
  EXPECT_EQ(c.probes[0].kind, ProbeKind::Points);
  const auto pts = probe_points(c.probes[0]);
  ASSERT_EQ(pts.size(), 2u);
  EXPECT_EQ(pts[1].x, 5e-4);
  EXPECT_EQ(pts[1].y, 0.0);
  // a single point
  const Case one = load_case_text(with(kPointProbe, "at = [[5e-4, 5e-4], [5e-4, 0.0]]", "at = [[1e-4, 2e-4]]"), kFile);
  EXPECT_EQ(probe_point_count(one.probes[0]), 1u);
}

TEST(CaseLoad, PointProbeErrors) {
  expect_error(with(kPointProbe, "at = [[5e-4, 5e-4], [5e-4, 0.0]]", "at = [[5e-4, 5e-4], [5e-4, -1e-4]]"),
               "probe[0].at[1]", "at = ", "outside the domain");
  expect_error(with(kPointProbe, "interval = 0.1", "interval = 0.1\nfrom = [0.0, 0.0]"), "probe[0].from",
               "from = [0.0, 0.0]", "not used by kind 'points'");
  expect_error(with(kPointProbe, "at = [[5e-4, 5e-4], [5e-4, 0.0]]\n", ""), "probe[0].at", "[[probe]]",
               "missing required key");
  // a line probe still needs its line
  expect_error(with(kPointProbe, "kind = \"points\"", "kind = \"line\""), "probe[0].from", "[[probe]]",
               "missing required key");
}

TEST(CaseLoad, CoefficientReferencesFromAnalysisOrTheBody) {
  const Case a = load_case_text(with_body("\n[analysis]\nreference_velocity = [0.0, 0.01]\nreference_length = 4e-4\n", ""),
                                kFile);
  EXPECT_TRUE(body_reference(a, 0).complete());
  EXPECT_EQ(body_reference(a, 0).velocity.y, 0.01);
  // the body's own velocity with [analysis]'s length
  const Case b = load_case_text(
      with_body("\n[analysis]\nreference_length = 4e-4\n", "reference_velocity = [0.02, 0.0]\n"), kFile);
  EXPECT_EQ(body_reference(b, 0).velocity.x, 0.02);
  EXPECT_EQ(body_reference(b, 0).length, 4e-4);
  // none at all: no coefficients, no error
  EXPECT_FALSE(body_reference(load_case_text(with_body("", ""), kFile), 0).complete());
}

TEST(CaseLoad, HalfAReferenceIsAnError) {
  const std::string length_only = with_body("\n[analysis]\nreference_length = 4e-4\n", "");
  expect_error(length_only, "analysis.reference_length", "reference_length = 4e-4", "no reference_velocity");
  const std::string body_velocity_only = with_body("", "reference_velocity = [0.02, 0.0]\n");
  expect_error(body_velocity_only, "body[0].reference_velocity", "reference_velocity = [0.02",
               "no reference_length");
  expect_error(kMinimal + "\n[analysis]\nreference_velocity = [1.0, 0.0]\n", "analysis.reference_velocity",
               "reference_velocity = [1.0", "give both or neither");
  expect_error(with_body("\n[analysis]\nreference_length = -1.0\n", ""), "analysis.reference_length",
               "reference_length = -1.0", ">= 0");
}
