// Mutation test of the command line: malformed case files derived from the shipped cases
// (deleted and duplicated lines, numbers replaced by strings, negative numbers, 0, 1e308, nan,
// random bytes, truncation) each make `particula info` end with exit code 2 (bad input) or 0
// (the mutant is still a valid case) - never another code, a signal or a hang. Targeted mutants
// of a small case (below) are run with `particula run`: exit 0, 2 or 3, nothing left behind on 2.
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iterator>
#include <map>
#include <random>
#include <regex>
#include <string>
#include <vector>

#include "cli_process.hpp"

namespace fs = std::filesystem;

namespace {

constexpr int kMutantsTotal = 520;  // spread over the shipped cases

/// The share of the mutants to run: all, or 1/N with PARTICULA_MUTANT_SHARE=N (the sanitizer build's
/// test preset sets 4: each mutant run costs about 10x more under AddressSanitizer, and the full set
/// runs in the release build; the seeds are the same, so the sanitizer build runs the first ones).
int mutant_count(int full) {
  const char* share = std::getenv("PARTICULA_MUTANT_SHARE");
  const int n = share ? std::atoi(share) : 1;
  return n > 1 ? std::max(1, full / n) : full;
}
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
    const int per_case = static_cast<int>((mutant_count(kMutantsTotal) + cases.size() - 1) / cases.size());
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
  EXPECT_GE(total, mutant_count(kMutantsTotal) - 20);
  EXPECT_GT(codes[2], total / 4) << "most mutants should be refused";
  EXPECT_GT(codes[0], 0) << "some mutants are still valid cases";
  std::string summary;
  for (const auto& [code, n] : codes) summary += " exit " + std::to_string(code) + ": " + std::to_string(n) + ";";
  std::printf("%d mutants:%s\n", total, summary.c_str());
}

// ---- targeted mutants, run -------------------------------------------------------------------
//
// The kinds of input a fault-injection pass found accepted at load and then crashing, hanging or
// writing NaN: extreme numbers (one, or the whole case scaled), long names, probes (outside the
// domain, too many points, 200 of them), near-duplicate polygon vertices, walls on a periodic
// axis, duplicated, tiny or sliding walls, absurd time steps and output intervals. Each mutant of
// a small case is run with `particula run`: it must end with 0, 2 or 3 (exactly 2 where the
// mutation makes the case invalid), never a signal or a hang; exit 2 leaves no run directory, and
// a completed run wrote no NaN or Inf.

namespace {

/// A closed 0.2 m box at d0 = 5 mm (1600 particles): a free disc above a fixed plate, one probe.
const std::string kRunBase = R"(name = "fuzz"

[domain]
min = [0.0, 0.0]
max = [0.2, 0.2]

[resolution]
d0 = 0.005

[fluid]
rho0 = 1000.0
nu = 1.0e-4
c = 2.0
gravity = [0.0, -9.81]

[time]
end = 0.01

[output]
interval = 0.005
snapshot_interval = 0.01

[[wall]]
name = "bottom"
from = [0.0, 0.0]
to = [0.2, 0.0]

[[wall]]
name = "right"
from = [0.2, 0.0]
to = [0.2, 0.2]

[[wall]]
name = "top"
from = [0.2, 0.2]
to = [0.0, 0.2]

[[wall]]
name = "left"
from = [0.0, 0.2]
to = [0.0, 0.0]

[[probe]]
name = "column"
from = [0.1, 0.0]
to = [0.1, 0.2]
points = 21
interval = 0.005

[[body]]
name = "disc"
shape = "circle"
center = [0.1, 0.13]
radius = 0.025
density = 1200.0

[[body]]
name = "plate"
shape = "polygon"
motion = "fixed"
vertices = [[0.04, 0.02], [0.16, 0.02], [0.16, 0.07], [0.04, 0.07]]
)";

/// One mutant: the case text, what was done, and whether it must be refused (exit 2).
struct Mutant {
  std::string text, what;
  bool invalid = false;
};

/// `text` with the first `from` replaced by `to` (which must be there).
std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const auto p = text.find(from);
  EXPECT_NE(p, std::string::npos) << from;
  if (p != std::string::npos) text.replace(p, from.size(), to);
  return text;
}

/// x with round-trip precision.
std::string num(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", x);
  return buf;
}

class TargetedMutator {
 public:
  explicit TargetedMutator(std::uint64_t seed) : rng_(seed) {
    static const std::regex real(R"((^|[^\w.])([-+]?\d+\.\d*(?:[eE][-+]?\d+)?))");
    for (auto it = std::sregex_iterator(kRunBase.begin(), kRunBase.end(), real); it != std::sregex_iterator(); ++it)
      reals_.emplace_back(static_cast<std::size_t>(it->position(2)), static_cast<std::size_t>(it->length(2)));
  }

  Mutant next() {
    switch (pick(10)) {
      case 0: return extreme_number();
      case 1: return scaled();
      case 2: return long_name();
      case 3: return probe();
      case 4: return near_duplicate_vertex();
      case 5: return periodic_walls();
      case 6: return duplicated_wall();
      case 7: return tiny_wall();
      case 8: return time_steps();
      default: return sliding_wall();
    }
  }

 private:
  std::size_t pick(std::size_t n) { return static_cast<std::size_t>(rng_() % n); }
  int between(int lo, int hi) { return lo + static_cast<int>(pick(static_cast<std::size_t>(hi - lo + 1))); }

  Mutant extreme_number() {
    const auto [pos, len] = reals_[pick(reals_.size())];
    const std::string original = kRunBase.substr(pos, len);
    const double x = std::stod(original);
    const std::string choices[] = {"1e150", "1e-150", "1e300", "-1e300", "1e-300", "5e-324", "1.7976931348623157e308",
                                   "2.2250738585072014e-308", "1e20", "-1e20", num(x * std::pow(10.0, between(-300, 300))),
                                   num(x * std::pow(10.0, between(-40, 40)))};
    const std::string r = choices[pick(std::size(choices))];
    std::string t = kRunBase;
    t.replace(pos, len, r);
    return {t, "number " + original + " at byte " + std::to_string(pos) + " -> " + r, false};
  }

  Mutant scaled() {
    const int exponents[] = {150, -150, 200, -200, 100, -100, 50, -50, 20, -20, between(-149, 149)};
    const int e = exponents[pick(std::size(exponents))];
    std::string t = kRunBase;
    for (auto it = reals_.rbegin(); it != reals_.rend(); ++it)
      t.replace(it->first, it->second, num(std::stod(kRunBase.substr(it->first, it->second)) * std::pow(10.0, e)));
    return {t, "every real times 1e" + std::to_string(e), std::abs(e) >= 150};
  }

  Mutant long_name() {
    const char* names[] = {"name = \"fuzz\"", "name = \"column\"", "name = \"bottom\"", "name = \"disc\""};
    const std::size_t lengths[] = {64, 65, 255, 300, 5000};
    const std::string which = names[pick(std::size(names))];
    const std::size_t n = lengths[pick(std::size(lengths))];
    return {replaced(kRunBase, which, "name = \"" + std::string(n, 'x') + "\""),
            which + " of " + std::to_string(n) + " characters", n > 64};
  }

  Mutant probe() {
    switch (pick(5)) {
      case 0: {  // 4001 points fit the 0.2 m line at d0/100 spacing
        const int points[] = {4001, 4002, 100000, 1000000};
        const int n = points[pick(std::size(points))];
        return {replaced(kRunBase, "points = 21", "points = " + std::to_string(n)), "probe of " + std::to_string(n) +
                " points", n > 4001};
      }
      case 1: {
        const double x = (static_cast<double>(pick(2001)) - 1000) / 1000, y = -0.01 - static_cast<double>(pick(1000)) / 1000;
        return {replaced(kRunBase, "from = [0.1, 0.0]", "from = [" + num(x) + ", " + num(y) + "]"),
                "probe from [" + num(x) + ", " + num(y) + "]", true};
      }
      case 2: {
        const int points[] = {1000, 6000, 1000000};
        const int n = points[pick(std::size(points))];
        std::string t = kRunBase;
        for (int k = 0; k < 200; ++k)
          t += "\n[[probe]]\nname = \"p" + std::to_string(k) + "\"\nfrom = [0.01, 0.01]\nto = [0.19, 0.19]\npoints = " +
               std::to_string(n) + "\ninterval = 0.005\n";
        return {t, "200 more probes of " + std::to_string(n) + " points", n > 1000};
      }
      case 3:
        return {replaced(kRunBase, "to = [0.1, 0.2]", "to = [0.1, 0.0]"), "probe of length 0 with 21 points", true};
      default: {
        const char* intervals[] = {"1e-300", "1e-9", "0.02", "1e6"};
        const std::string v = intervals[pick(std::size(intervals))];
        return {replaced(kRunBase, "interval = 0.005\n\n[[body]]", "interval = " + v + "\n\n[[body]]"),
                "probe interval " + v, v == "1e-300" || v == "1e-9"};
      }
    }
  }

  Mutant near_duplicate_vertex() {
    const int k = between(3, 16);  // 1e-3 .. 1e-16 m, all below d0/2
    const double e = std::pow(10.0, -k);
    const double vx[] = {0.04, 0.16, 0.16, 0.04}, vy[] = {0.02, 0.02, 0.07, 0.07};
    const std::size_t i = pick(4);
    std::string v = "vertices = [";
    for (std::size_t j = 0; j < 4; ++j) {
      v += (j ? ", [" : "[") + num(vx[j]) + ", " + num(vy[j]) + "]";
      if (j == i) v += ", [" + num(vx[j] + e * (pick(2) ? 1 : -1)) + ", " + num(vy[j] + 0.5 * e) + "]";
    }
    v += "]";
    return {replaced(kRunBase, "vertices = [[0.04, 0.02], [0.16, 0.02], [0.16, 0.07], [0.04, 0.07]]", v),
            "vertex " + std::to_string(i) + " doubled 1e-" + std::to_string(k) + " m away", true};
  }

  Mutant periodic_walls() {
    const char* axes[] = {"[true, false]", "[false, true]", "[true, true]"};
    const std::string a = axes[pick(std::size(axes))];
    return {replaced(kRunBase, "max = [0.2, 0.2]", "max = [0.2, 0.2]\nperiodic = " + a), "periodic = " + a +
            " with walls on that axis", true};
  }

  Mutant duplicated_wall() {
    const char* walls[][2] = {{"[0.0, 0.0]", "[0.2, 0.0]"}, {"[0.2, 0.0]", "[0.2, 0.2]"},
                              {"[0.2, 0.2]", "[0.0, 0.2]"}, {"[0.0, 0.2]", "[0.0, 0.0]"}};
    const std::size_t w = pick(4), variant = pick(4);
    std::string from = walls[w][0], to = walls[w][1];
    if (variant == 1) std::swap(from, to);
    if (variant == 2) to = w == 0 ? "[0.1, 0.0]" : w == 1 ? "[0.2, 0.1]" : w == 2 ? "[0.1, 0.2]" : "[0.0, 0.1]";
    if (variant == 3) from = w == 0 ? "[1e-9, 0.0]" : w == 1 ? "[0.2, 1e-9]" : w == 2 ? "[0.199999999, 0.2]" : "[0.0, 0.199999999]";
    return {kRunBase + "\n[[wall]]\nname = \"again\"\nfrom = " + from + "\nto = " + to + "\n",
            "wall " + std::to_string(w) + " again (variant " + std::to_string(variant) + ")", true};
  }

  Mutant tiny_wall() {
    const int k = between(3, 16);
    const double x = 0.02 + static_cast<double>(pick(1600)) / 10000;
    return {kRunBase + "\n[[wall]]\nname = \"tiny\"\nfrom = [" + num(x) + ", 0.19]\nto = [" +
                num(x + std::pow(10.0, -k)) + ", 0.19]\n",
            "a wall 1e-" + std::to_string(k) + " m long", true};
  }

  Mutant time_steps() {
    switch (pick(5)) {
      case 0: {
        const char* v[] = {"5e-324", "1e-300", "1e-12"};
        const std::string s = v[pick(3)];
        return {replaced(kRunBase, "end = 0.01", "end = 0.01\ndt_max = " + s), "time.dt_max = " + s, true};
      }
      case 1: {
        const char* v[] = {"1e-300", "1e-12"};
        const std::string s = v[pick(2)];
        return {replaced(kRunBase, "interval = 0.005\nsnapshot", "interval = " + s + "\nsnapshot"),
                "output.interval = " + s, true};
      }
      case 2: {
        const char* v[] = {"1e300", "1e9"};
        const std::string s = v[pick(2)];
        return {replaced(kRunBase, "end = 0.01", "end = " + s), "time.end = " + s, true};
      }
      case 3:
        return {replaced(kRunBase, "end = 0.01", "end = 1e9\nmax_steps = 5"), "time.end = 1e9, max_steps = 5", false};
      default:
        return {replaced(kRunBase, "snapshot_interval = 0.01", "snapshot_interval = 0.01\ncheckpoint_interval = 1e-300"),
                "output.checkpoint_interval = 1e-300", true};
    }
  }

  Mutant sliding_wall() {
    const char* walls[] = {"to = [0.2, 0.0]\n", "to = [0.2, 0.2]\n", "to = [0.0, 0.2]\n", "to = [0.0, 0.0]\n"};
    const char* velocities[] = {"[0.01, 0.0]", "[0.0, 0.01]", "[-0.01, 0.0]", "[0.0, -0.01]"};
    const std::size_t w = pick(4);
    return {replaced(kRunBase, walls[w], std::string(walls[w]) + "velocity = " + velocities[w] + "\n"),
            "wall " + std::to_string(w) + " sliding in the closed box", true};
  }

  std::mt19937_64 rng_;
  std::vector<std::pair<std::size_t, std::size_t>> reals_;
};

}  // namespace

TEST(CliMutation, RunOnTargetedMutantsEndsWithZeroTwoOrThree) {
  const int kMutants = mutant_count(400);
  const fs::path dir = cli_test::fresh_dir("cli_run_mutation");
  {  // the base case itself runs
    cli_test::write_text(dir / "base.toml", kRunBase);
    const auto r = cli_test::cli({"run", (dir / "base.toml").string(), "--out", (dir / "base").string(), "--quiet",
                                  "--no-plots"});
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_EQ(cli_test::csv_with_non_finite(dir / "base"), "");
  }
  TargetedMutator mutator(0x15f022);
  std::map<int, int> codes;
  int crashes = 0, leftovers = 0, non_finite = 0, wrongly_accepted = 0;
  for (int k = 0; k < kMutants; ++k) {
    const Mutant m = mutator.next();
    const std::string id = std::to_string(k);
    fs::path file = dir / "mutant", out = dir / "run";
    file += id + ".toml";
    out += id;
    cli_test::write_text(file, m.text);
    const auto r = cli_test::Child("timeout", {"-k", "5", kTimeoutSeconds, PARTICULA_BINARY, "run", file.string(),
                                               "--out", out.string(), "--quiet", "--no-plots"})
                       .wait();
    ++codes[r.code];
    const std::string where = m.what + " (kept in " + file.string() + "): exit code " + std::to_string(r.code) + "\n" +
                              r.output;
    const bool crashed = !(r.code == 0 || r.code == 2 || r.code == 3);
    crashes += crashed;
    EXPECT_FALSE(crashed) << (r.code == 124 ? "timeout: " : r.code > 128 ? "signal: " : "") << where;
    if (m.invalid) {
      wrongly_accepted += r.code != 2;
      EXPECT_EQ(r.code, 2) << "must be refused at load: " << where;
    }
    if (r.code == 2) {
      leftovers += fs::exists(out);
      EXPECT_FALSE(fs::exists(out)) << "exit 2 left a run directory behind: " << where;
    }
    if (r.code == 3) {  // a run that went unstable: allowed, shown
      const std::size_t from = r.output.rfind("error: ");
      std::printf("exit 3: %s: %s\n", m.what.c_str(),
                  from == std::string::npos ? "" : r.output.substr(from, 160).c_str());
    }
    if (r.code == 0) {
      const std::string bad = cli_test::csv_with_non_finite(out);
      non_finite += !bad.empty();
      EXPECT_EQ(bad, "") << "completed with NaN or Inf in " << bad << ": " << where;
    }
    if (!HasFailure()) {
      fs::remove(file);
      fs::remove_all(out);
    }
  }
  std::string summary;
  for (const auto& [code, n] : codes) summary += " exit " + std::to_string(code) + ": " + std::to_string(n) + ";";
  std::printf("%d run mutants:%s crashes or hangs: %d; left behind after exit 2: %d; completed with NaN/Inf: %d; "
              "invalid but not refused: %d\n",
              kMutants, summary.c_str(), crashes, leftovers, non_finite, wrongly_accepted);
  EXPECT_GT(codes[2], kMutants / 2) << "most targeted mutants are invalid";
  EXPECT_GT(codes[0], 0) << "some still run";
  if (!HasFailure()) fs::remove_all(dir);
}
