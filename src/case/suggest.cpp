// Suggestions for unknown keys: the nearest schema key by edit distance, when it is close.
#include <algorithm>
#include <cctype>
#include <vector>

#include "internal.hpp"

namespace particula::case_detail {
namespace {

/// Keys longer than this are garbage; they get no suggestion (bounds the quadratic cost).
constexpr std::size_t kMaxSuggestLength = 128;

std::string lower(std::string s) {
  for (char& ch : s) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
  return s;
}

/// Levenshtein distance (insertions, deletions, substitutions), two-row dynamic programming.
std::size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> prev(b.size() + 1), cur(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) prev[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    cur[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t subst = prev[j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1);
      cur[j] = std::min({prev[j] + 1, cur[j - 1] + 1, subst});
    }
    std::swap(prev, cur);
  }
  return prev[b.size()];
}

/// Every name a user may write, in schema form: all keys and all section names.
std::vector<std::string> candidates() {
  std::vector<std::string> out;
  for (const KeySpec& s : case_schema()) out.push_back(s.key);
  for (const SectionSpec& s : case_sections())
    if (!s.name.empty()) out.push_back(s.name);
  return out;
}

/// Puts the index of `concrete` back into a candidate of the same array ("wall[]." -> "wall[2].").
std::string with_index(const std::string& candidate, const std::string& concrete) {
  const auto open = concrete.find('[');
  const auto close = concrete.find(']');
  if (open == std::string::npos || close == std::string::npos || close < open) return candidate;
  if (candidate.compare(0, open + 2, concrete.substr(0, open) + "[]") != 0) return candidate;
  return concrete.substr(0, close + 1) + candidate.substr(open + 2);
}

}  // namespace

std::string unknown_key_message(const std::string& concrete) {
  const std::string wanted = lower(schema_form(concrete));
  if (wanted.size() > kMaxSuggestLength) return "unknown key";
  // Close means at most a quarter of the key's letters differ (at least 1, at most 3).
  const std::size_t limit = std::clamp<std::size_t>(wanted.size() / 4, 1, 3);
  std::string best;
  std::size_t best_distance = limit + 1;
  for (const std::string& c : candidates()) {
    const std::size_t d = edit_distance(wanted, c);
    if (d < best_distance) best_distance = d, best = c;
  }
  if (best.empty()) return "unknown key";
  return "unknown key (did you mean '" + with_index(best, concrete) + "'?)";
}

}  // namespace particula::case_detail
