// Run directories (run/run_dir.hpp): the marker, the names particula writes, what --overwrite
// may replace, replacing with the old run kept aside until commit (or put back on rollback), and
// the removal of temporary files a killed particula left.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <string>

#include "cli_process.hpp"
#include "particula/io/atomic_file.hpp"
#include "particula/run/run_dir.hpp"

using namespace particula;
namespace fs = std::filesystem;
using cli_test::fresh_dir;
using cli_test::read_text;
using cli_test::write_text;

namespace {

/// A directory that looks like a finished run: marker, outputs, a snapshot, a checkpoint, a plot.
void make_run(const fs::path& dir, std::uint64_t hash = 42) {
  fs::create_directories(dir / "particles");
  fs::create_directories(dir / "checkpoint");
  fs::create_directories(dir / "plots");
  write_marker(dir, RunMarker{MarkedKind::Run, hash});
  for (const char* f : {"case.toml", "log.txt", "summary.json", "bodies.csv", "walls.csv", "probe_profile.csv",
                        "particles.pvd", "particles/step_00000000.vtp", "checkpoint/state.bin", "plots/bodies.png"})
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
  for (const char* f : {"case.toml", "log.txt", "probe_a.csv", ".particula-run", "checkpoint/state.bin",
                        "checkpoint/failure.bin", "particles/step_00000012.vtp", "plots/bodies.png",
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

TEST(RunDir, ReplacingKeepsTheOldRunAsideUntilCommit) {
  const fs::path dir = fresh_dir("rundir_commit");
  make_run(dir / "run", 1);
  {
    RunDirectory rd(dir / "run", true, RunMarker{MarkedKind::Run, 2});
    ASSERT_TRUE(rd.replacing());
    EXPECT_EQ(read_text(rd.aside() / "case.toml"), "old case.toml");
    EXPECT_EQ(read_marker(dir / "run")->case_hash, 2u);
    EXPECT_FALSE(fs::exists(dir / "run" / "case.toml"));
    EXPECT_FALSE(rd.commit().has_value());
    EXPECT_FALSE(fs::exists(rd.aside()));
  }
  EXPECT_TRUE(fs::exists(dir / "run" / kRunMarker)) << "a committed run stays";
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
    write_text(dir / "run" / "case.toml", "new");
    // destroyed without commit: rolled back
  }
  EXPECT_FALSE(fs::exists(aside));
  EXPECT_EQ(read_text(dir / "run" / "case.toml"), "old case.toml");
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
