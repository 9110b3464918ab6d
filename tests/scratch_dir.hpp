// Scratch directories of the tests under the system's temporary directory: one helper, so that
// every test binary removes what it made when it ends and all its tests passed (a failing run
// keeps them for inspection; the failure message names them).
#pragma once

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <string>
#include <system_error>
#include <vector>

namespace test_scratch {

/// The directories made by this process, removed at its end if no test failed.
class Registry {
 public:
  static Registry& instance() {
    static Registry r;
    return r;
  }
  void add(const std::filesystem::path& p) { paths_.push_back(p); }
  ~Registry() {
    const ::testing::UnitTest* u = ::testing::UnitTest::GetInstance();
    if (u == nullptr || u->Failed()) return;
    std::error_code ec;
    for (const auto& p : paths_) std::filesystem::remove_all(p, ec);
  }

 private:
  Registry() = default;
  std::vector<std::filesystem::path> paths_;
};

/// TMPDIR/particula_<name>_<pid>, emptied (made if `create`), and removed when the binary ends
/// with every test passed.
inline std::filesystem::path scratch_dir(const std::string& name, bool create = true) {
  (void)::testing::UnitTest::GetInstance();  // constructed first, so destroyed after the registry
  Registry& r = Registry::instance();
  const auto d =
      std::filesystem::temp_directory_path() / ("particula_" + name + "_" + std::to_string(::getpid()));
  std::filesystem::remove_all(d);
  if (create) std::filesystem::create_directories(d);
  r.add(d);
  return d;
}

}  // namespace test_scratch
