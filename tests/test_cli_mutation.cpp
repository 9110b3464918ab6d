// Mutation test of the command line: malformed case files derived from the shipped cases
// (deleted and duplicated lines, numbers replaced by strings, negative numbers, 0, 1e308, nan,
// random bytes, truncation) each make `particula info` end with exit code 2 (bad input) or 0
// (the mutant is still a valid case) - never another code, a signal or a hang.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <map>
#include <random>
#include <regex>
#include <string>
#include <vector>

#include "cli_process.hpp"

namespace fs = std::filesystem;

namespace {

constexpr int kMutantsTotal = 520;  // spread over the shipped cases
constexpr const char* kTimeoutSeconds = "20";

std::vector<std::string> split_lines(const std::string& text) {
  std::vector<std::string> lines;
  std::size_t start = 0;
  while (start < text.size()) {
    const std::size_t nl = text.find('\n', start);
    const std::size_t end = nl == std::string::npos ? text.size() : nl;
    lines.push_back(text.substr(start, end - start));
    start = end + 1;
  }
  return lines;
}

std::string join_lines(const std::vector<std::string>& lines) {
  std::string s;
  for (const auto& l : lines) s += l + "\n";
  return s;
}

/// Derives malformed case files from a valid one with a seeded generator (portable: only the
/// raw mt19937_64 output is used, never a std distribution).
class Mutator {
 public:
  Mutator(std::string text, std::uint64_t seed) : text_(std::move(text)), rng_(seed) {
    static const std::regex number(R"([-+]?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?)");
    for (auto it = std::sregex_iterator(text_.begin(), text_.end(), number); it != std::sregex_iterator(); ++it)
      numbers_.emplace_back(static_cast<std::size_t>(it->position()), static_cast<std::size_t>(it->length()));
  }

  /// One mutant and a short description of the mutation.
  std::pair<std::string, std::string> next() {
    switch (pick(7)) {
      case 0: {
        auto lines = split_lines(text_);
        const std::size_t k = pick(lines.size());
        const std::string what = "deleted line " + std::to_string(k + 1);
        lines.erase(lines.begin() + static_cast<std::ptrdiff_t>(k));
        return {join_lines(lines), what};
      }
      case 1: {
        auto lines = split_lines(text_);
        const std::size_t k = pick(lines.size());
        lines.insert(lines.begin() + static_cast<std::ptrdiff_t>(k), lines[k]);
        return {join_lines(lines), "duplicated line " + std::to_string(k + 1)};
      }
      case 2:
      case 3:
      case 4: {
        static const std::vector<std::string> replacements{
            "\"text\"", "0", "-0", "1e308", "-1e308", "nan", "inf", "-inf", "1e-308", "-1", "1", "true",
            "[]", "[1, 2, 3]", "99999999999999999999", "0.5", "2", "1e6", "-1e-6", "{}", "\"\""};
        const auto [pos, len] = numbers_[pick(numbers_.size())];
        std::string original = text_.substr(pos, len), r = replacements[pick(replacements.size())];
        if (pick(4) == 0) r = original[0] == '-' ? original.substr(1) : "-" + original;  // flip the sign
        std::string m = text_;
        m.replace(pos, len, r);
        return {m, "replaced " + original + " at byte " + std::to_string(pos) + " by " + r};
      }
      case 5: {
        std::string m = text_, bytes;
        const std::size_t n = 1 + pick(8);
        for (std::size_t k = 0; k < n; ++k) bytes.push_back(static_cast<char>(pick(256)));
        const std::size_t pos = pick(m.size() + 1);
        m.insert(pos, bytes);
        return {m, "inserted " + std::to_string(n) + " random bytes at byte " + std::to_string(pos)};
      }
      default: {
        const std::size_t pos = pick(text_.size());
        return {text_.substr(0, pos), "truncated at byte " + std::to_string(pos)};
      }
    }
  }

 private:
  std::size_t pick(std::size_t n) { return n == 0 ? 0 : static_cast<std::size_t>(rng_() % n); }

  std::string text_;
  std::mt19937_64 rng_;
  std::vector<std::pair<std::size_t, std::size_t>> numbers_;
};

}  // namespace

TEST(CliMutation, InfoOnMalformedCasesEndsWithExitZeroOrTwo) {
  const fs::path dir = cli_test::fresh_dir("cli_mutation");
  std::vector<fs::path> cases;
  for (const auto& e : fs::directory_iterator(fs::path(PARTICULA_SOURCE_DIR) / "cases"))
    if (e.path().extension() == ".toml") cases.push_back(e.path());
  std::sort(cases.begin(), cases.end());
  ASSERT_GE(cases.size(), 4u);

  std::map<int, int> codes;
  int total = 0;
  for (std::size_t ci = 0; ci < cases.size(); ++ci) {
    Mutator mutator(cli_test::read_text(cases[ci]), 0x5eed0000 + ci);
    const int per_case = static_cast<int>((kMutantsTotal + cases.size() - 1) / cases.size());
    for (int k = 0; k < per_case; ++k) {
      const auto [text, what] = mutator.next();
      const fs::path file = dir / (cases[ci].stem().string() + "_" + std::to_string(k) + ".toml");
      cli_test::write_text(file, text);
      const auto r = cli_test::Child("timeout", {"-k", "5", kTimeoutSeconds, PARTICULA_BINARY, "info", "--no-timing",
                                                 file.string()})
                         .wait();
      ++codes[r.code];
      ++total;
      // timeout(1) exits 124 on a hang and 128 + N when the program died of signal N.
      EXPECT_TRUE(r.code == 0 || r.code == 2)
          << cases[ci].filename().string() << ": " << what << " (kept in " << file.string() << "): exit code "
          << r.code << (r.code == 124 ? " (timeout)" : r.code > 128 ? " (signal)" : "") << "\n"
          << r.output;
      if (r.code == 0 || r.code == 2) fs::remove(file);
    }
  }
  EXPECT_GE(total, 500);
  EXPECT_GT(codes[2], total / 4) << "most mutants should be refused";
  EXPECT_GT(codes[0], 0) << "some mutants are still valid cases";
  std::string summary;
  for (const auto& [code, n] : codes) summary += " exit " + std::to_string(code) + ": " + std::to_string(n) + ";";
  std::printf("%d mutants:%s\n", total, summary.c_str());
}
