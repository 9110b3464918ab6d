// The documentation and the shipped case files name only paths inside the project (issue 16,
// item 6): no path into a sibling directory or a machine's own directories, and every
// reference/<file> they name exists in the repository.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace {

const fs::path kRoot = PARTICULA_SOURCE_DIR;

/// README.md, docs/*.md, reference/README.md and every case file (cases/ and its subdirectories).
std::vector<fs::path> checked_files() {
  std::vector<fs::path> files{kRoot / "README.md", kRoot / "reference" / "README.md"};
  for (const auto& e : fs::directory_iterator(kRoot / "docs"))
    if (e.path().extension() == ".md") files.push_back(e.path());
  for (const auto& e : fs::recursive_directory_iterator(kRoot / "cases"))
    if (e.path().extension() == ".toml") files.push_back(e.path());
  return files;
}

std::string read(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

/// "file:line: text" of each line of `file` that matches `pattern`.
std::vector<std::string> matching_lines(const fs::path& file, const std::regex& pattern) {
  std::vector<std::string> hits;
  std::istringstream in(read(file));
  std::string line;
  for (int n = 1; std::getline(in, line); ++n)
    if (std::regex_search(line, pattern)) hits.push_back(fs::relative(file, kRoot).string() + ":" + std::to_string(n) + ": " + line);
  return hits;
}

}  // namespace

TEST(DocsPaths, NoPathOutsideTheProject) {
  // ../x (a sibling of the checkout) and a machine's directories (/work, /tmp, /home, /root, ~/).
  const std::regex outside(R"((^|[\s`'"(=])(\.\./|/work/|/tmp/|/home/|/root/|/mnt/|~/))");
  const auto files = checked_files();
  EXPECT_GT(files.size(), 10u);
  for (const auto& f : files)
    for (const auto& hit : matching_lines(f, outside)) ADD_FAILURE() << hit;
}

TEST(DocsPaths, EveryReferenceFileNamedExists) {
  const std::regex named(R"(reference/([A-Za-z0-9_.-]+\.(csv|md)))");
  int count = 0;
  for (const auto& f : checked_files()) {
    const std::string text = read(f);
    for (std::sregex_iterator it(text.begin(), text.end(), named), end; it != end; ++it, ++count)
      EXPECT_TRUE(fs::exists(kRoot / "reference" / (*it)[1].str())) << fs::relative(f, kRoot) << " names " << (*it)[0];
  }
  EXPECT_GT(count, 5) << "the case files name their reference data";
}
