// load_case: TOML text -> overrides -> unknown-key walk -> schema rows -> cross checks -> Case.
#include "particula/case/load.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <map>
#include <sstream>
#include <system_error>

#include "internal.hpp"

namespace particula {

using case_detail::LoadContext;

namespace {

/// Case files larger than this are not case files.
constexpr std::uintmax_t kMaxCaseFileBytes = 16u << 20;

// ---------------------------------------------------------------------------------------------
// Reading and parsing.

/// The bytes of the case file; CaseError (line 0) if it is missing, unreadable or huge.
std::string read_case_file(const std::filesystem::path& file) {
  const std::string name = file.string();
  std::error_code ec;
  const auto status = std::filesystem::status(file, ec);
  if (ec || !std::filesystem::exists(status)) throw CaseError(name, 0, "", "case file not found");
  if (std::filesystem::is_directory(status)) throw CaseError(name, 0, "", "is a directory, not a case file");
  const auto size = std::filesystem::file_size(file, ec);
  if (!ec && size > kMaxCaseFileBytes) throw CaseError(name, 0, "", "case file is too large (over 16 MiB)");
  std::ifstream in(file, std::ios::binary);
  if (!in) throw CaseError(name, 0, "", fmt::format("cannot open case file: {}", std::strerror(errno)));
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw CaseError(name, 0, "", "error while reading the case file");
  return std::move(text).str();
}

/// Parses TOML; syntax errors become CaseError at toml++'s line, with the column in the message.
toml::table parse_document(std::string_view text, const std::string& file) {
  try {
    return toml::parse(text, file);
  } catch (const toml::parse_error& e) {
    const auto& at = e.source().begin;
    throw CaseError(file, static_cast<int>(at.line), "",
                    fmt::format("TOML syntax error (column {}): {}", at.column, e.description()));
  }
}

// ---------------------------------------------------------------------------------------------
// Unknown keys: every key in the document must be a schema key or lead to one.

void walk_table(const toml::table& t, const std::string& schema_prefix, const std::string& concrete_prefix,
                LoadContext& ctx);

/// A key that names an array of tables ([[wall]]): each element is walked as a table.
void walk_array(const toml::node& node, const std::string& schema, const std::string& concrete,
                LoadContext& ctx) {
  const auto* a = node.as_array();
  if (!a) throw ctx.error(concrete, fmt::format("expected an array of tables [[{}]]", concrete));
  for (std::size_t i = 0; i < a->size(); ++i) {
    const std::string element = fmt::format("{}[{}]", concrete, i);
    const toml::node& e = *a->get(i);
    ctx.lines.emplace(element, static_cast<int>(e.source().begin.line));
    if (!e.is_table()) throw ctx.error(element, fmt::format("expected a table [[{}]]", concrete));
    walk_table(*e.as_table(), schema + "[].", element + ".", ctx);
  }
}

/// The entries of a table in the order they appear in the file (toml++ sorts them by name), so
/// that the first problem reported is the first one in the file.
std::vector<std::pair<std::string, const toml::node*>> in_file_order(const toml::table& t) {
  std::vector<std::pair<std::string, const toml::node*>> entries;
  for (auto&& [k, node] : t) entries.emplace_back(std::string(k.str()), &node);
  std::stable_sort(entries.begin(), entries.end(), [](const auto& a, const auto& b) {
    return a.second->source().begin.line < b.second->source().begin.line;
  });
  return entries;
}

/// Records the line of every key and throws for the first one the schema does not know.
void walk_table(const toml::table& t, const std::string& schema_prefix, const std::string& concrete_prefix,
                LoadContext& ctx) {
  for (const auto& [name, node] : in_file_order(t)) {
    const std::string schema = schema_prefix + name, concrete = concrete_prefix + name;
    const int line = static_cast<int>(node->source().begin.line);
    if (!case_detail::plain_component(name))  // a quoted key such as "fluid.c": located by its own line
      throw CaseError(ctx.file, line, concrete, "not a valid key name (letters, digits, '_' and '-' only)");
    ctx.lines.emplace(concrete, line);
    if (const KeySpec* spec = find_key(schema)) {  // a value: checked when its row is read
      const auto* items = case_detail::is_list_type(spec->type) ? node->as_array() : nullptr;
      for (std::size_t i = 0; items && i < items->size(); ++i)  // lines of list items, for messages
        ctx.lines.emplace(fmt::format("{}[{}]", concrete, i),
                          static_cast<int>(items->get(i)->source().begin.line));
      continue;
    }
    if (case_detail::is_array_section(schema)) {
      walk_array(*node, schema, concrete, ctx);
    } else if (case_detail::is_table_section(schema)) {
      if (!node->is_table()) throw ctx.error(concrete, fmt::format("expected a table [{}]", concrete));
      walk_table(*node->as_table(), schema + ".", concrete + ".", ctx);
    } else {
      throw ctx.error(concrete, case_detail::unknown_key_message(concrete));
    }
  }
}

// ---------------------------------------------------------------------------------------------
// Reading the schema rows into a Case.

/// The node of `spec` for element `index` in the document, or nullptr if absent.
const toml::node* find_node(const toml::table& root, const KeySpec& spec, std::size_t index) {
  const toml::node* node = &root;
  for (std::string part : case_detail::split_dots(spec.key)) {
    const bool array = part.ends_with("[]");
    if (array) part.resize(part.size() - 2);
    const auto* table = node->as_table();
    node = table ? table->get(part) : nullptr;
    if (node && array) node = node->is_array() ? node->as_array()->get(index) : nullptr;
    if (!node) return nullptr;
  }
  return node;
}

/// Sizes every array of tables in the Case to its number of elements in the document.
void size_arrays(const toml::table& root, Case& c) {
  for (const SectionSpec& s : case_sections()) {
    if (!s.array) continue;
    const auto* a = root.get_as<toml::array>(s.name);
    s.resize(c, a ? a->size() : 0);
  }
}

/// Reads one key of element `index`: the document's value (checked) or the row's default.
void read_key(const toml::table& root, const KeySpec& spec, std::size_t index, Case& c, LoadContext& ctx) {
  const std::string key = case_detail::concrete_key(spec.key, index);
  if (const toml::node* node = find_node(root, spec, index)) {
    Value v;
    int item_line = 0;
    if (const std::string problem = case_detail::convert_node(*node, spec, v, &item_line); !problem.empty())
      throw ctx.error_at(key, item_line, problem);
    ctx.given.insert(key);  // a key given where it is not used is reported by the cross checks
    spec.bind.set(c, index, v);
  } else if (!spec.used_for(c, index)) {
    return;  // e.g. body[].radius of an ellipse: left value-initialised
  } else if (spec.need == Need::Required) {
    const std::string unit = spec.unit.empty() || spec.unit == "-" ? "" : ", " + spec.unit;
    std::string why;
    if (spec.used_when) {
      const KeySpec* decider = find_key(spec.used_when->key);
      why = fmt::format(" for {} '{}'", decider->leaf(), std::get<std::string>(*decider->bind.get(c, index)));
    }
    throw ctx.error(
        key, fmt::format("missing required key{} ({}{}): {}", why, type_name(spec.type), unit, spec.meaning));
  } else if (spec.need == Need::Default) {
    spec.bind.set(c, index, spec.default_at(index));
  }
}

/// Number of elements a row applies to: 1 for plain keys, the array's size for members.
std::size_t element_count(const KeySpec& spec, const Case& c) {
  if (!spec.in_array()) return 1;
  return find_section(spec.section())->size(c);
}

/// Exactly one key of each OneOf group (e.g. fluid.nu / fluid.mu) must be given.
void check_groups(const Case& c, const LoadContext& ctx) {
  std::map<std::string, std::vector<const KeySpec*>> groups;
  for (const KeySpec& s : case_schema())
    if (s.need == Need::OneOf) groups[s.group].push_back(&s);
  for (const auto& [label, rows] : groups) {
    for (std::size_t i = 0; i < element_count(*rows.front(), c); ++i) {
      std::vector<std::string> keys, given;
      for (const KeySpec* s : rows) {
        keys.push_back(case_detail::concrete_key(s->key, i));
        if (ctx.given.contains(keys.back())) given.push_back(keys.back());
      }
      const std::string list = fmt::format("'{}'", fmt::join(keys, "' or '"));
      if (given.empty())
        throw ctx.error(keys.front(), fmt::format("missing required key: give one of {} ({})", list, label));
      if (given.size() > 1)
        throw ctx.error(given.back(), fmt::format("give only one of {} ({}), not both", list, label));
    }
  }
}

/// Members marked unique (probe names) must differ across the elements of their array.
void check_unique(const Case& c, const LoadContext& ctx) {
  for (const KeySpec& s : case_schema()) {
    if (!s.unique) continue;
    std::map<std::string, std::size_t> seen;
    for (std::size_t i = 0; i < element_count(s, c); ++i) {
      const std::string text = format_toml_value(*s.bind.get(c, i));
      const auto [it, fresh] = seen.emplace(text, i);
      if (!fresh)
        throw ctx.error(case_detail::concrete_key(s.key, i),
                        fmt::format("duplicate {} {} (already used by {})", s.section(),
                                    s.leaf() + " " + text, case_detail::concrete_key(s.key, it->second)));
    }
  }
}

}  // namespace

Case load_case_text(std::string_view text, const std::filesystem::path& source,
                    const std::vector<std::string>& overrides) {
  LoadContext ctx;
  ctx.file = source.string();
  toml::table root = parse_document(text, ctx.file);
  case_detail::apply_overrides(root, overrides, ctx);
  walk_table(root, "", "", ctx);

  Case c;
  c.source = source;
  size_arrays(root, c);
  for (const KeySpec& spec : case_schema())
    for (std::size_t i = 0; i < element_count(spec, c); ++i) read_key(root, spec, i, c, ctx);
  // An arc's end points, so that the checks of joints and chains read every wall's ends alike.
  for (WallSpec& w : c.walls)
    if (w.shape == WallShape::Arc) {
      w.from = w.piece().start();
      w.to = w.piece().end();
    }
  check_groups(c, ctx);
  check_unique(c, ctx);
  case_detail::run_cross_checks(c, ctx);
  return c;
}

Case load_case(const std::filesystem::path& file, const std::vector<std::string>& overrides) {
  return load_case_text(read_case_file(file), file, overrides);
}

}  // namespace particula
