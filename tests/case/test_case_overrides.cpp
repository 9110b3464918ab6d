// --set key=value overrides: every kind of key, arrays of tables by index, and their errors.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "particula/case/load.hpp"

using namespace particula;

namespace {

const std::string kFile = "cases/test.toml";

const std::string kCase = R"(name = "ovr"

[domain]
min = [0.0, 0.0]
max = [1e-3, 1e-3]

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

[[probe]]
name = "mid"
from = [5e-4, 0.0]
to = [5e-4, 1e-3]
points = 11
interval = 0.1
)";

Case load(const std::vector<std::string>& overrides) { return load_case_text(kCase, kFile, overrides); }

/// The CaseError thrown by loading kCase with `overrides`.
CaseError error_of(const std::vector<std::string>& overrides) {
  try {
    load(overrides);
  } catch (const CaseError& e) {
    return e;
  }
  ADD_FAILURE() << "expected a CaseError";
  return CaseError("", 0, "", "");
}

/// Asserts an override error at `key` whose message contains `part`.
void expect_error(const std::vector<std::string>& overrides, const std::string& key,
                  const std::string& part) {
  const CaseError e = error_of(overrides);
  EXPECT_EQ(e.file(), "--set") << e.what();
  EXPECT_EQ(e.line(), 0) << e.what();
  EXPECT_EQ(e.key(), key) << e.what();
  EXPECT_NE(e.message().find(part), std::string::npos) << e.what();
}

}  // namespace

TEST(CaseOverrides, Real) {
  EXPECT_EQ(load({"resolution.d0=5e-5"}).d0, 5e-5);
  EXPECT_EQ(load({"time.end=2"}).t_end, 2.0);        // integer for a real
  EXPECT_EQ(load({" time.end = 3.5 "}).t_end, 3.5);  // spaces around key and value
}

TEST(CaseOverrides, LaterOverridesWin) { EXPECT_EQ(load({"time.end=2", "time.end=4"}).t_end, 4.0); }

TEST(CaseOverrides, ChoiceAndStringBareOrQuoted) {
  EXPECT_EQ(load({"numerics.laplacian=morris"}).laplacian, LaplacianScheme::Morris);  // new [numerics] table
  EXPECT_EQ(load({"numerics.boundary=\"dummy\""}).boundary, BoundaryModel::Dummy);
  EXPECT_EQ(load({"name=other-name"}).name, "other-name");
  EXPECT_EQ(load({"description=a long text, with = signs"}).description, "a long text, with = signs");
  EXPECT_EQ(load({"name=123"}).name, "123");  // a bare word is a string for string keys
}

TEST(CaseOverrides, IntBoolVec2Bool2) {
  const Case c = load({"time.max_steps=100", "output.snapshots=false", "fluid.gravity=[0,-9.81]",
                       "domain.periodic=[true, false]", "initial.seed=42"});
  EXPECT_EQ(c.max_steps, 100);
  EXPECT_FALSE(c.snapshots);
  EXPECT_EQ(c.gravity.x, 0.0);
  EXPECT_EQ(c.gravity.y, -9.81);
  EXPECT_TRUE(c.periodic_x);
  EXPECT_FALSE(c.periodic_y);
  EXPECT_EQ(c.seed, 42u);
}

TEST(CaseOverrides, ArrayOfTablesMembersByIndex) {
  const Case c = load({"probe.0.points=81", "domain.periodic=[true,false]", "wall.1.velocity=[1e-5,0]",
                       "wall.0.name=bottom"});
  EXPECT_EQ(c.probes[0].points, 81);
  EXPECT_EQ(c.walls[1].velocity.x, 1e-5);
  EXPECT_EQ(c.walls[0].name, "bottom");
  EXPECT_EQ(c.walls[1].name, "wall1");
}

TEST(CaseOverrides, ViscosityFromMuReplacesNothingSilently) {
  // The file gives nu; also giving mu is "both".
  expect_error({"fluid.mu=1e-3"}, "fluid.mu", "give only one of");
}

TEST(CaseOverrides, MalformedOverrides) {
  const CaseError e = error_of({"resolution.d0"});
  EXPECT_EQ(e.file(), "--set");
  EXPECT_STREQ(e.what(), "--set: malformed override 'resolution.d0': expected key=value");
  expect_error({"=3"}, "", "the key is empty");
  expect_error({"resolution..d0=3"}, "resolution..d0", "malformed key");
  expect_error({"resolution.d0=[1,"}, "resolution.d0", "cannot read value '[1,' as TOML");
  expect_error({"resolution.d0=1\nx = 2"}, "resolution.d0", "malformed value");
  expect_error({"resolution.d0="}, "resolution.d0", "cannot read value");
}

TEST(CaseOverrides, UnknownKeyWithSuggestion) {
  const CaseError e = error_of({"fluid.nuu=1e-6"});
  EXPECT_STREQ(e.what(), "--set: key 'fluid.nuu': unknown key (did you mean 'fluid.nu'?)");
  expect_error({"fluid=3"}, "fluid", "unknown key");
  expect_error({"probe.0.pints=3"}, "probe[0].pints", "did you mean 'probe[0].points'?");
}

TEST(CaseOverrides, ArrayIndexErrors) {
  expect_error({"probe.points=3"}, "probe.points",
               "[[probe]] is an array of tables: write probe.<index>.<key>");
  expect_error({"probe.1.points=3"}, "probe[1].points", "no element 1 in [[probe]]: the case has 1 of them");
  expect_error({"probe.99999999999.points=3"}, "probe.99999999999.points", "array of tables");
}

TEST(CaseOverrides, TypeAndRangeErrorsPointAtTheOverride) {
  expect_error({"resolution.d0=fine"}, "resolution.d0", "cannot read value 'fine'");
  expect_error({"resolution.d0=\"fine\""}, "resolution.d0", "expected a real number, got a string");
  expect_error({"resolution.d0=-1"}, "resolution.d0", "must be > 0 m");
  expect_error({"probe.0.points=2.5"}, "probe[0].points", "expected an integer, got a float");
  expect_error({"probe.0.points=1"}, "probe[0].points", "must be in [2, 1000000]");
  expect_error({"numerics.laplacian=sph"}, "numerics.laplacian", "expected one of fatehi_manzari, morris");
  expect_error({"fluid.gravity=[0]"}, "fluid.gravity", "expected an array of two real numbers");
  expect_error({"wall.1.velocity=[0, 1]"}, "wall[1].velocity", "must be tangential");
  expect_error({"time.end=nan"}, "time.end", "finite");
}

TEST(CaseOverrides, ErrorsInTheFileStillPointAtTheFile) {
  // An override elsewhere does not move the location of an error in the file.
  try {
    load_case_text(kCase + "bogus = 1\n", kFile, {"time.end=2"});
    FAIL();
  } catch (const CaseError& e) {
    EXPECT_EQ(e.file(), kFile);
    EXPECT_GT(e.line(), 0);
  }
}

TEST(CaseOverrides, SectionThatIsNotATableInTheFile) {
  std::string text = "time = 3\n" + kCase;
  text.erase(text.find("[time]"), std::string("[time]\nend = 1.0\n").size());
  try {
    load_case_text(text, kFile, {"time.end=2"});
    FAIL();
  } catch (const CaseError& e) {
    EXPECT_NE(std::string(e.what()).find("is not a table"), std::string::npos) << e.what();
  }
}
