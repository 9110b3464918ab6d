// Where two resolved cases differ (load.hpp): a stored validation result against today's case,
// an edited case.toml against the checkpoint's.
#include <map>
#include <set>
#include <sstream>

#include "particula/case/load.hpp"

namespace particula {

namespace {

/// The key lines of a resolved case, each prefixed with its table; comments and blank lines dropped.
std::vector<std::string> qualified_lines(const std::string& text) {
  std::vector<std::string> out;
  std::string table;
  std::map<std::string, int> seen;  // arrays of tables: their n-th element
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) {
    if (line.empty() || line[0] == '#') continue;
    if (line.rfind("[[", 0) == 0) table = line + "#" + std::to_string(seen[line]++);
    else if (line[0] == '[') table = line;
    out.push_back(line[0] == '[' || table.empty() ? line : table + " " + line);
  }
  return out;
}

}  // namespace

std::vector<std::string> resolved_case_differences(const std::string& before, const std::string& after,
                                                   std::size_t max_lines) {
  const std::vector<std::string> b = qualified_lines(before), a = qualified_lines(after);
  const std::set<std::string> bs(b.begin(), b.end()), as(a.begin(), a.end());
  std::vector<std::string> out;
  for (const auto& l : b)
    if (!as.count(l) && out.size() < max_lines) out.push_back("- " + l);
  for (const auto& l : a)
    if (!bs.count(l) && out.size() < max_lines) out.push_back("+ " + l);
  return out;
}

}  // namespace particula
