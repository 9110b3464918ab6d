// The case-file schema is self-consistent and docs/case-files.md is exactly the reference
// generated from it (its defaults against Case and PhysicsParams: test_defaults.cpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <set>
#include <sstream>
#include <string>

#include "particula/case/load.hpp"
#include "particula/case/schema.hpp"

using namespace particula;

namespace {

const std::filesystem::path kDocs = std::filesystem::path(PARTICULA_SOURCE_DIR) / "docs" / "case-files.md";
const std::filesystem::path kJsonSchema = std::filesystem::path(PARTICULA_SOURCE_DIR) / "docs" / "case.schema.json";

bool numeric(ValueType t) {
  return t == ValueType::Real || t == ValueType::Int || t == ValueType::Vec2 || t == ValueType::Vec2List ||
         t == ValueType::Real4Table;
}

/// The alternative of Value that a key of type `t` holds.
std::size_t value_index(ValueType t) {
  switch (t) {
    case ValueType::Real:
      return 0;
    case ValueType::Int:
      return 1;
    case ValueType::Bool:
      return 2;
    case ValueType::String:
    case ValueType::Choice:
      return 3;
    case ValueType::Vec2:
      return 4;
    case ValueType::Bool2:
      return 5;
    case ValueType::Vec2Loops:
      return 8;
    case ValueType::Vec2List:
      return 6;
    case ValueType::Real4Table:
      return 7;
  }
  return 99;
}

std::string read_file(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace

TEST(CaseSchema, RowsAreWellFormed) {
  std::set<std::string> keys;
  for (const KeySpec& s : case_schema()) {
    SCOPED_TRACE(s.key);
    EXPECT_TRUE(keys.insert(s.key).second) << "duplicate key";
    EXPECT_NE(find_section(s.section()), nullptr) << "section not listed in case_sections()";
    EXPECT_EQ(find_section(s.section())->array, s.in_array());
    EXPECT_TRUE(s.bind.set && s.bind.get);
    EXPECT_FALSE(s.meaning.empty());
    EXPECT_EQ(s.meaning.back(), '.') << "meaning should be one sentence";
    if (numeric(s.type)) {
      EXPECT_FALSE(s.unit.empty()) << "numeric keys need a unit";
    }
    if (s.type == ValueType::Choice) {
      EXPECT_GE(s.choices.size(), 2u);
    }
    if (s.need == Need::OneOf) {
      EXPECT_FALSE(s.group.empty());
    }
    if (s.type == ValueType::Vec2List || s.type == ValueType::Real4Table) {
      EXPECT_GE(s.min_items, 1u);
    }
    if (s.type == ValueType::Real4Table) {
      EXPECT_EQ(s.columns.size(), 4u);
    }
    if (s.used_when) {  // decided by an earlier choice member of the same element
      const KeySpec* decider = find_key(s.used_when->key);
      ASSERT_NE(decider, nullptr);
      EXPECT_EQ(decider->type, ValueType::Choice);
      EXPECT_EQ(decider->section(), s.section());
      EXPECT_LT(decider, &s);
      for (const std::string& v : s.used_when->values)
        EXPECT_NE(std::find(decider->choices.begin(), decider->choices.end(), v), decider->choices.end())
            << v;
    }
  }
}

TEST(CaseSchema, DefaultsHaveTheirTypeAndLieInTheirRange) {
  for (const KeySpec& s : case_schema()) {
    if (s.need != Need::Default) continue;
    SCOPED_TRACE(s.key);
    const Value v = s.default_at(3);
    ASSERT_EQ(v.index(), value_index(s.type));
    if (s.type == ValueType::Real) {
      EXPECT_TRUE(s.range.contains(std::get<real>(v)));
    }
    if (s.type == ValueType::Int) {
      EXPECT_TRUE(s.range.contains(static_cast<real>(std::get<std::int64_t>(v))));
    }
    if (s.type == ValueType::Choice) {
      EXPECT_NE(std::find(s.choices.begin(), s.choices.end(), std::get<std::string>(v)), s.choices.end());
    }
  }
}

TEST(CaseSchema, ViscosityIsOneOfNuOrMu) {
  EXPECT_EQ(default_text(*find_key("fluid.nu")), "one of fluid.nu / fluid.mu");
  EXPECT_EQ(find_key("fluid.mu")->group, find_key("fluid.nu")->group);
}

TEST(CaseSchema, RangeText) {
  EXPECT_EQ(find_key("resolution.d0")->range.text(), "> 0");
  EXPECT_EQ(find_key("resolution.h_over_d0")->range.text(), "[1.5, 4]");
  EXPECT_EQ(find_key("time.cfl")->range.text(), "(0, 1]");
  EXPECT_EQ(find_key("guard.rho_min_ratio")->range.text(), "(0, 1)");
  EXPECT_EQ(find_key("fluid.p0")->range.text(), ">= 0");
  EXPECT_FALSE(find_key("time.cfl")->range.contains(0));
  EXPECT_TRUE(find_key("time.cfl")->range.contains(1));
}

TEST(CaseDocs, ReferenceIsUpToDate) {
  const std::string generated = case_reference_markdown();
  if (std::getenv("PARTICULA_UPDATE_DOCS")) {
    std::ofstream(kDocs, std::ios::binary) << generated;
    GTEST_SKIP() << "rewrote " << kDocs;
  }
  EXPECT_EQ(read_file(kDocs), generated)
      << kDocs
      << " differs from case_reference_markdown(); run test_case_schema with PARTICULA_UPDATE_DOCS=1";
}

// docs/case.schema.json (the file .taplo.toml points editors to) is `particula schema --json`;
// tests/python/test_schema.py checks it as JSON Schema against every shipped case file.
TEST(CaseDocs, JsonSchemaIsUpToDate) {
  const std::string generated = case_json_schema();
  if (std::getenv("PARTICULA_UPDATE_DOCS")) {
    std::ofstream(kJsonSchema, std::ios::binary) << generated;
    GTEST_SKIP() << "rewrote " << kJsonSchema;
  }
  EXPECT_EQ(read_file(kJsonSchema), generated)
      << kJsonSchema << " differs from case_json_schema(); run test_case_schema with PARTICULA_UPDATE_DOCS=1";
}

TEST(CaseDocs, JsonSchemaNamesEveryKeyWithItsUnit) {
  const std::string json = case_json_schema();
  for (const KeySpec& s : case_schema()) {
    EXPECT_NE(json.find("\"" + s.leaf() + "\": {"), std::string::npos) << s.key;
    if (!s.unit.empty() && s.unit != "-") {
      EXPECT_NE(json.find("\"x-unit\": \"" + s.unit + "\""), std::string::npos) << s.key;
    }
  }
  for (const SectionSpec& sec : case_sections()) {
    if (!sec.name.empty()) {
      EXPECT_NE(json.find("\"" + sec.name + "\": {"), std::string::npos) << sec.name;
    }
  }
}

TEST(CaseDocs, EveryKeyIsDocumented) {
  const std::string doc = case_reference_markdown();
  for (const KeySpec& s : case_schema())
    EXPECT_NE(doc.find("| `" + s.key + "` |"), std::string::npos) << s.key;
}

TEST(CaseDocs, EveryExampleLoads) {
  const std::string doc = case_reference_markdown();
  int examples = 0;
  for (auto b = doc.find("```toml\n"); b != std::string::npos; b = doc.find("```toml\n", b + 1)) {
    const auto e = doc.find("```", b + 8);
    ASSERT_NE(e, std::string::npos);
    SCOPED_TRACE(examples);
    EXPECT_NO_THROW(load_case_text(doc.substr(b + 8, e - b - 8), "docs/case-files.md"));
    ++examples;
  }
  EXPECT_GE(examples, 2);
}

TEST(CaseDocs, MinimalExampleLoads) {
  const std::string doc = case_reference_markdown();
  const auto b = doc.find("```toml\n");
  ASSERT_NE(b, std::string::npos);
  const auto e = doc.find("```", b + 8);
  const Case c = load_case_text(doc.substr(b + 8, e - b - 8), "docs/case-files.md");
  EXPECT_EQ(c.name, "channel");
  EXPECT_EQ(c.walls.size(), 2u);
}
