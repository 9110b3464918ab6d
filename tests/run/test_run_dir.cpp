// Run directories (run/run_dir.hpp): the marker, the lock, the names particula writes and those
// a case writes, what --overwrite may replace, replacing with the old run kept aside until commit
// (or put back on rollback), and the removal of temporary files a killed particula left.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <regex>
#include <string>

#include "cli_process.hpp"
#include "particula/io/atomic_file.hpp"
#include "particula/run/plots.hpp"
#include "particula/run/run_dir.hpp"

using namespace particula;
namespace fs = std::filesystem;
using cli_test::fresh_dir;
using cli_test::read_text;
using cli_test::write_text;

namespace {

/// A directory that looks like a finished run of a case with the probe "profile": marker,
/// case.toml, outputs, a snapshot, a checkpoint, plots.
void make_run(const fs::path& dir, std::uint64_t hash = 42) {
  fs::create_directories(dir / "particles");
  fs::create_directories(dir / "checkpoint");
  fs::create_directories(dir / "plots");
  write_marker(dir, RunMarker{MarkedKind::Run, hash});
  write_text(dir / "case.toml", "name = \"old\"\n\n[[probe]]\nname = \"profile\"\nkind = \"line\"\n");
  for (const char* f : {"log.txt", "summary.json", "bodies.csv", "walls.csv", "probe_profile.csv", "flow_profile.csv",
                        "particles.pvd", "particles/step_00000000.vtp", "checkpoint/state.bin", "plots/bodies.png",
                        "plots/probe_profile_profiles.png"})
    write_text(dir / f, std::string("old ") + f);
}

/// Restores the working directory when a test changed it.
struct InDirectory {
  fs::path old = fs::current_path();
  explicit InDirectory(const fs::path& d) { fs::current_path(d); }
  ~InDirectory() { fs::current_path(old); }
};

}  // namespace

TEST(RunDir, MarkerRoundTripAndRefusals) {
  const fs::path dir = fresh_dir("rundir_marker");
  EXPECT_FALSE(read_marker(dir).has_value());
  write_marker(dir, RunMarker{MarkedKind::Run, 0xfedcba9876543210ull});
  const auto m = read_marker(dir);
  ASSERT_TRUE(m.has_value());
  EXPECT_EQ(m->kind, MarkedKind::Run);
  EXPECT_EQ(m->case_hash, 0xfedcba9876543210ull);
  write_text(dir / kRunMarker, "format = 2\nkind = \"run\"\ncase_hash = \"0000000000000001\"\n");
  EXPECT_THROW(read_marker(dir), io::IoError);
  write_text(dir / kRunMarker, "format = 1\nkind = \"run\"\n");
  EXPECT_THROW(read_marker(dir), io::IoError);  // a run marker without its case
}

TEST(RunDir, NamesParticulaWrites) {
  for (const char* f : {"case.toml", "log.txt", "probe_a.csv", ".particula-run", ".particula-lock",
                        "checkpoint/state.bin", "checkpoint/failure.bin", "particles/step_00000012.vtp",
                        "plots/bodies.png",
                        "checkpoint/state.bin.tmp.123", ".resume/bodies.csv", ".resume/particles/step_1.vtp"})
    EXPECT_TRUE(particula_run_entry(f, false)) << f;
  for (const char* d : {"particles", "checkpoint", "plots", ".resume"}) EXPECT_TRUE(particula_run_entry(d, true)) << d;
  for (const char* f : {"thesis.tex", "probe_.csv", "checkpoint/other.bin", "particles/step_x.vtp", "plots/notes.txt",
                        "case.toml.tmp.abc", "case.toml.tmp.0123", "sub/case.toml", "particles/step_1.vtp/x"})
    EXPECT_FALSE(particula_run_entry(f, false)) << f;
  EXPECT_FALSE(particula_run_entry("particles/more", true));
  EXPECT_FALSE(particula_run_entry("data", true));
  const auto t = io::atomic_temp_target("state.bin.tmp.4711");
  ASSERT_TRUE(t.has_value());
  EXPECT_EQ(t->target, "state.bin");
  EXPECT_EQ(t->pid, 4711);
  EXPECT_FALSE(io::atomic_temp_target("state.bin.tmp.99999999999").has_value());
}

TEST(RunDir, OnlyAParticulaRunDirectoryMayBeReplaced) {
  const fs::path dir = fresh_dir("rundir_replaceable");
  make_run(dir / "run");
  EXPECT_FALSE(why_not_replaceable(dir / "run").has_value());
  EXPECT_FALSE(why_not_replaceable((dir / "run").string() + "/").has_value());
  fs::create_directories(dir / "mine");
  write_text(dir / "mine" / "thesis.tex", "x");
  EXPECT_NE(why_not_replaceable(dir / "mine")->find("not a particula run directory"), std::string::npos);
  write_text(dir / "file", "x");
  EXPECT_NE(why_not_replaceable(dir / "file")->find("is a file"), std::string::npos);
  fs::create_directory_symlink(dir / "run", dir / "link");
  EXPECT_NE(why_not_replaceable(dir / "link")->find("symbolic link"), std::string::npos);
  {
    InDirectory in(dir / "run");
    EXPECT_NE(why_not_replaceable(".")->find("working directory"), std::string::npos);
    EXPECT_NE(why_not_replaceable("..")->find("working directory"), std::string::npos);
    EXPECT_NE(why_not_replaceable(dir)->find("working directory"), std::string::npos);
  }
  write_text(dir / "run" / "notes.txt", "mine");
  fs::create_directories(dir / "run" / "analysis");
  const auto why = why_not_replaceable(dir / "run");
  ASSERT_TRUE(why.has_value());
  EXPECT_NE(why->find("notes.txt"), std::string::npos) << *why;
  EXPECT_NE(why->find("analysis/"), std::string::npos) << *why;
  fs::remove(dir / "run" / "notes.txt");
  fs::remove(dir / "run" / "analysis");
  fs::create_symlink(dir / "file", dir / "run" / "case.toml.link");
  EXPECT_TRUE(why_not_replaceable(dir / "run").has_value()) << "a link inside is not particula's";
}

TEST(RunDir, OnlyTheFilesOfItsCaseAreTheRuns) {
  const std::vector<std::string> probes{"profile"};
  for (const char* f : {"case.toml", ".particula-lock", "probe_profile.csv", "flow_profile.csv", "plots/bodies.png",
                        "plots/probe_profile_profiles.png", "plots/probe_profile_error.png",
                        "plots/probe_profile_points.png", "probe_profile.csv.tmp.123", ".resume/probe_profile.csv",
                        "particles/step_00000012.vtp", "checkpoint/state.bin"})
    EXPECT_TRUE(case_run_entry(f, false, probes)) << f;
  // Names that look like particula's (and match its patterns) but that this case never writes.
  for (const char* f : {"probe_mine.csv", "flow_mine.csv", "plots/figure_for_paper.png",
                        "plots/probe_mine_points.png", "probe_mine.csv.tmp.123", ".resume/flow_mine.csv"}) {
    EXPECT_FALSE(case_run_entry(f, false, probes)) << f;
    EXPECT_TRUE(particula_run_entry(f, false)) << f << " matches particula's patterns all the same";
  }
  EXPECT_FALSE(case_run_entry("probe_profile.csv", false, {}));
}

TEST(RunDir, PlotNamesAreThoseThePlotScriptDraws) {
  const std::string script = read_text(fs::path(PARTICULA_SOURCE_DIR) / "tools" / "plot_run.py");
  const std::regex save(R"re(save\(fig, out, "([^"]+)")re");
  const std::vector<std::string> names = plot_file_names({"p"});
  std::size_t n = 0;
  for (std::sregex_iterator it(script.begin(), script.end(), save), end; it != end; ++it, ++n) {
    std::string stem = (*it)[1];
    if (const auto k = stem.find("%s"); k != std::string::npos) stem.replace(k, 2, "p");
    for (const std::string& format : plot_formats())
      EXPECT_NE(std::find(names.begin(), names.end(), stem + "." + format), names.end())
          << stem << "." << format << " is drawn by plot_run.py --format " << format;
  }
  EXPECT_EQ(n * plot_formats().size(), names.size()) << "every name plot_file_names gives is drawn by plot_run.py";
  // The script's formats are plot_formats(), in the same order (the first the default).
  std::smatch formats;
  ASSERT_TRUE(std::regex_search(script, formats, std::regex(R"re(FORMATS = \(([^)]*)\))re")));
  std::string expected;
  for (const std::string& f : plot_formats()) expected += (expected.empty() ? "\"" : ", \"") + f + "\"";
  EXPECT_EQ(formats[1].str(), expected);
}

TEST(RunDir, OverwriteRefusesFilesThatOnlyLookLikeOutputs) {
  const fs::path dir = fresh_dir("rundir_lookalike");
  make_run(dir / "run");
  EXPECT_EQ(run_probe_names(dir / "run"), std::vector<std::string>{"profile"});
  EXPECT_FALSE(why_not_replaceable(dir / "run").has_value());
  const std::vector<std::string> mine{"plots/figure_for_paper.png", "probe_mine.csv", "flow_mine.csv"};
  for (const auto& f : mine) write_text(dir / "run" / f, "mine");
  const auto why = why_not_replaceable(dir / "run");
  ASSERT_TRUE(why.has_value());
  for (const auto& f : mine) EXPECT_NE(why->find(f), std::string::npos) << *why;
  EXPECT_THROW(RunDirectory(dir / "run", true, RunMarker{MarkedKind::Run, 2}), RunDirRefused);
  for (const auto& f : mine) EXPECT_EQ(read_text(dir / "run" / f), "mine") << f;
  EXPECT_EQ(read_marker(dir / "run")->case_hash, 42u);
  // Without a readable case.toml, only particula's fixed names are the run's: its probe's file is
  // named, and the reason given.
  for (const auto& f : mine) fs::remove(dir / "run" / f);
  write_text(dir / "run" / "case.toml", "not = = toml");
  EXPECT_FALSE(run_probe_names(dir / "run").has_value());
  const auto unreadable = why_not_replaceable(dir / "run");
  ASSERT_TRUE(unreadable.has_value());
  EXPECT_NE(unreadable->find("probe_profile.csv"), std::string::npos) << *unreadable;
  EXPECT_NE(unreadable->find("case.toml is missing or unreadable"), std::string::npos) << *unreadable;
}

TEST(RunDir, ALockedRunDirectoryIsRefusedNamingTheProcess) {
  const fs::path dir = fresh_dir("rundir_lock");
  make_run(dir / "run");
  const std::string pid = "pid " + std::to_string(::getpid());
  {
    RunDirLock held(dir / "run");
    ASSERT_TRUE(held.held());
    EXPECT_EQ(run_dir_user(dir / "run"), static_cast<long>(::getpid()));
    try {
      RunDirLock second(dir / "run");
      ADD_FAILURE() << "a second lock of a locked run directory";
    } catch (const RunDirBusy& e) {
      EXPECT_NE(std::string(e.what()).find(pid), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find((dir / "run").string()), std::string::npos) << e.what();
    }
    for (const bool overwrite : {false, true}) {
      try {
        RunDirectory rd(dir / "run", overwrite, RunMarker{MarkedKind::Run, 2});
        ADD_FAILURE() << "a run into a locked run directory, overwrite " << overwrite;
      } catch (const RunDirBusy& e) {
        EXPECT_NE(std::string(e.what()).find(pid), std::string::npos) << e.what();
      }
    }
    EXPECT_EQ(read_marker(dir / "run")->case_hash, 42u);
    EXPECT_EQ(read_text(dir / "run" / "log.txt"), "old log.txt");
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
    EXPECT_EQ(names, std::vector<std::string>{"run"}) << "nothing moved aside or staged";
  }
  EXPECT_FALSE(run_dir_user(dir / "run").has_value()) << "a released lock file names nobody";
  EXPECT_TRUE(RunDirLock(dir / "run").held());
  // A lock file that is a link is not opened (nor what it points to created).
  fs::create_directories(dir / "linked");
  fs::create_symlink(dir / "elsewhere", dir / "linked" / kRunLock);
  EXPECT_THROW(RunDirLock(dir / "linked"), RunDirRefused);
  EXPECT_FALSE(fs::exists(dir / "elsewhere"));
}

TEST(RunDir, ReplacingKeepsTheOldRunAsideUntilCommit) {
  const fs::path dir = fresh_dir("rundir_commit");
  make_run(dir / "run", 1);
  {
    RunDirectory rd(dir / "run", true, RunMarker{MarkedKind::Run, 2});
    ASSERT_TRUE(rd.replacing());
    EXPECT_EQ(read_text(rd.aside() / "log.txt"), "old log.txt");
    EXPECT_EQ(read_marker(dir / "run")->case_hash, 2u);
    EXPECT_FALSE(fs::exists(dir / "run" / "log.txt"));
    EXPECT_FALSE(rd.commit().has_value());
    EXPECT_FALSE(fs::exists(rd.aside()));
    EXPECT_THROW(RunDirLock(dir / "run"), RunDirBusy) << "locked while it is used";
  }
  EXPECT_TRUE(fs::exists(dir / "run" / kRunMarker)) << "a committed run stays";
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
  EXPECT_EQ(names, std::vector<std::string>{"run"}) << "nothing left aside or staged";
  // Without overwrite, an existing directory is refused and left alone.
  EXPECT_THROW(RunDirectory(dir / "run", false, RunMarker{}), RunDirRefused);
  EXPECT_EQ(read_marker(dir / "run")->case_hash, 2u);
}

TEST(RunDir, RollbackPutsTheOldRunBack) {
  const fs::path dir = fresh_dir("rundir_rollback");
  make_run(dir / "run", 1);
  fs::path aside;
  {
    RunDirectory rd(dir / "run", true, RunMarker{MarkedKind::Run, 2});
    aside = rd.aside();
    write_text(dir / "run" / "log.txt", "new");
    // destroyed without commit: rolled back
  }
  EXPECT_FALSE(fs::exists(aside));
  EXPECT_EQ(read_text(dir / "run" / "log.txt"), "old log.txt");
  EXPECT_EQ(read_marker(dir / "run")->case_hash, 1u);
  // A fresh run directory is removed with the parents it created, not with the ones that existed.
  write_text(dir / "keep.txt", "mine");
  {
    RunDirectory rd(dir / "a" / "b" / "run", false, RunMarker{MarkedKind::Run, 3});
    EXPECT_TRUE(fs::exists(dir / "a" / "b" / "run" / kRunMarker));
    EXPECT_FALSE(rd.rollback().has_value());
  }
  EXPECT_FALSE(fs::exists(dir / "a"));
  EXPECT_EQ(read_text(dir / "keep.txt"), "mine");
}

TEST(RunDir, AnOldRunLeftAsideByAKilledParticulaIsNotedAndKept) {
  const fs::path dir = fresh_dir("rundir_stale_aside");
  const fs::path left = dir / (".run.old." + std::to_string(cli_test::dead_pid()));
  make_run(left);
  RunDirectory rd(dir / "run", false, RunMarker{MarkedKind::Run, 1});
  ASSERT_EQ(rd.notes().size(), 1u);
  EXPECT_NE(rd.notes()[0].find(left.filename().string()), std::string::npos) << rd.notes()[0];
  EXPECT_TRUE(fs::exists(left / "case.toml"));
  rd.commit();
}

TEST(RunDir, StaleTemporaryFilesOfParticulaAreRemoved) {
  const fs::path dir = fresh_dir("rundir_temp");
  make_run(dir);
  const std::string dead = std::to_string(cli_test::dead_pid());
  write_text(dir / "checkpoint" / ("state.bin.tmp." + dead), "x");
  write_text(dir / "particles" / ("step_00000001.vtp.tmp." + dead), "x");
  write_text(dir / ("thesis.tex.tmp." + dead), "mine");
  write_text(dir / ("case.toml.tmp." + std::to_string(::getpid())), "running");
  fs::create_directories(dir / ("summary.json.tmp." + dead));  // not a regular file
  const auto removed = remove_stale_temp_files(dir);
  EXPECT_EQ(removed.size(), 2u);
  EXPECT_FALSE(fs::exists(dir / "checkpoint" / ("state.bin.tmp." + dead)));
  EXPECT_TRUE(fs::exists(dir / ("thesis.tex.tmp." + dead)));
  EXPECT_TRUE(fs::exists(dir / ("case.toml.tmp." + std::to_string(::getpid()))));
  EXPECT_TRUE(fs::exists(dir / ("summary.json.tmp." + dead)));
}

TEST(RunDir, ValidationDirectoryIsParticulasOrNewOrEmpty) {
  const fs::path dir = fresh_dir("rundir_validate");
  prepare_validation_dir(dir / "new");
  EXPECT_EQ(read_marker(dir / "new")->kind, MarkedKind::Validation);
  prepare_validation_dir(dir / "new");  // again: its own
  fs::create_directories(dir / "empty");
  prepare_validation_dir(dir / "empty");
  fs::create_directories(dir / "mine");
  write_text(dir / "mine" / "report.md", "mine");
  EXPECT_THROW(prepare_validation_dir(dir / "mine"), RunDirRefused);
  make_run(dir / "run");
  EXPECT_THROW(prepare_validation_dir(dir / "run"), RunDirRefused);
  write_text(dir / "file", "x");
  EXPECT_THROW(prepare_validation_dir(dir / "file"), RunDirRefused);
  EXPECT_EQ(read_text(dir / "mine" / "report.md"), "mine");
}
