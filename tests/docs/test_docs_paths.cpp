// The documentation and the shipped case files name only paths inside the project: no path into a
// sibling directory or a machine's own directories, and every reference/<file> they name exists in
// the repository. They speak of the project in the present tense (no work session or issue
// number), and every markdown file the docs link exists.
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

/// README.md and docs/*.md.
std::vector<fs::path> markdown_docs() {
  std::vector<fs::path> files{kRoot / "README.md"};
  for (const auto& e : fs::directory_iterator(kRoot / "docs"))
    if (e.path().extension() == ".md") files.push_back(e.path());
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

TEST(DocsPaths, NoWorkSessionOrIssueNumber) {
  // The project's history (work sessions, issue numbers) is kept by git and CHANGELOG.md; the docs
  // and the case files state what is, in the present tense. `session.hpp` is a file name.
  const std::regex work(
      R"(\bsessions? #?[0-9]+|\bissues? #?[0-9]+|\b(since|until|before|after|in) (the )?session\b(?!\.hpp))",
      std::regex::ECMAScript | std::regex::icase);
  // The samples are built from parts, so that a grep of the sources for such mentions finds none.
  const std::string s = "Session", i = "issue";
  ASSERT_TRUE(std::regex_search("as measured in work " + s + " 43", work));
  ASSERT_TRUE(std::regex_search("bodies at outlets (" + i + " 17)", work));
  ASSERT_TRUE(std::regex_search("passes since the " + s, work));
  ASSERT_FALSE(std::regex_search("the loop's type, declared in " + s + ".hpp", work));
  const auto files = checked_files();
  EXPECT_GT(files.size(), 10u);
  for (const auto& f : files)
    for (const auto& hit : matching_lines(f, work)) ADD_FAILURE() << hit;
}

TEST(DocsPaths, EveryMarkdownFileLinkedExists) {
  // `docs/X.md` names docs/X.md; `(X.md` (a link relative to docs/ or to the root) names docs/X.md
  // or X.md at the root.
  const std::regex linked(R"((docs/|\()([A-Za-z0-9_.-]+\.md)\b)");
  int count = 0;
  for (const auto& f : markdown_docs()) {
    const std::string text = read(f);
    for (std::sregex_iterator it(text.begin(), text.end(), linked), end; it != end; ++it, ++count) {
      const std::string name = (*it)[2].str();
      const bool in_docs = fs::exists(kRoot / "docs" / name);
      const bool found = (*it)[1].str() == "docs/" ? in_docs : in_docs || fs::exists(kRoot / name);
      EXPECT_TRUE(found) << fs::relative(f, kRoot) << " links " << (*it)[0] << ": no such file in docs/"
                         << ((*it)[1].str() == "docs/" ? "" : " or the root");
    }
  }
  EXPECT_GT(count, 20) << "the docs link each other";
}
