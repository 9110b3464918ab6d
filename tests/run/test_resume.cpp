// Checkpoints and `particula resume` through the command line: a run 0 -> T and a run
// 0 -> T/2 resumed to T write bitwise identical bodies.csv, probe CSVs and snapshots (also when
// the first part is interrupted by SIGINT); damaged checkpoints, checkpoints of another case,
// tampered checkpoints (valid checksum) and disallowed overrides are refused with exit code 2.
#include <gtest/gtest.h>

#include <chrono>
#include <csignal>
#include <cstdint>
#include <filesystem>
#include <string>
#include <thread>
#include <vector>

#include "checkpoint_tamper.hpp"
#include "cli_process.hpp"
#include "particula/io/vtk.hpp"
#include "particula/run/checkpoint.hpp"

namespace fs = std::filesystem;
using cli_test::fresh_dir;
using cli_test::cli;
using cli_test::read_text;

namespace {

/// Waits (up to two minutes) until the running run has written a periodic checkpoint, one after
/// t = 0 (the run writes one of its initial state before its first step); false if it never does.
bool wait_for_periodic_checkpoint(const fs::path& state) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  while (std::chrono::steady_clock::now() < deadline) {
    std::error_code ec;
    if (fs::exists(state, ec)) {
      try {
        if (particula::read_checkpoint(state).time > 0) return true;
      } catch (const std::exception&) {  // replaced while read: try again
      }
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  return false;
}

const fs::path kCouette = fs::path(PARTICULA_SOURCE_DIR) / "cases" / "couette.toml";

/// `run` arguments for a coarse couette run into `out`, one thread (bitwise comparisons).
std::vector<std::string> couette(const fs::path& out, const std::string& t_end, std::vector<std::string> extra = {}) {
  std::vector<std::string> a{"run", kCouette.string(), "--out", out.string(), "--quiet", "--no-plots",
                             "--threads", "1", "--set", "time.end=" + t_end, "--set",
                             "output.snapshot_interval=0.05"};
  for (auto& e : extra) a.push_back(e);
  return a;
}

/// Every output stream of the two run directories is bitwise the same.
void expect_same_outputs(const fs::path& a, const fs::path& b) {
  for (const char* f : {"bodies.csv", "probe_profile.csv", "particles.pvd"}) {
    const std::string ta = read_text(a / f), tb = read_text(b / f);
    EXPECT_FALSE(ta.empty()) << f;
    EXPECT_TRUE(ta == tb) << f << " differs between " << a << " and " << b;
  }
  const auto index = particula::io::PvdIndex::read(a / "particles.pvd");
  for (const auto& e : index.entries()) EXPECT_TRUE(read_text(a / e.file) == read_text(b / e.file)) << e.file;
  std::size_t files_a = 0, files_b = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(a / "particles")) ++files_a;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(b / "particles")) ++files_b;
  EXPECT_EQ(files_a, index.entries().size());
  EXPECT_EQ(files_b, files_a) << "snapshots after the checkpoint are removed on resume";
}

/// A cylinder thrown at the floor with friction (spring-dashpot contact, in contact from about
/// t = 0.007 s), coarse, one thread, with `extra` overrides: run to 0.011 s into DIR/full and to
/// 0.008 s into DIR/half (the checkpoint taken while it is in contact).
void run_contact_case(const fs::path& dir, const std::vector<std::string>& extra) {
  const fs::path cylinder = fs::path(PARTICULA_SOURCE_DIR) / "cases" / "falling_cylinder.toml";
  const auto args = [&](const fs::path& out, const std::string& t_end) {
    std::vector<std::string> a{"run",        cylinder.string(), "--out", out.string(), "--quiet",
                               "--no-plots", "--threads",       "1",     "--set",      "time.end=" + t_end};
    std::vector<std::string> sets{"resolution.d0=2e-4",
                                  "domain.max=[0.02,0.01]",
                                  "wall.1.to=[0.02,0.01]",
                                  "wall.2.from=[0.02,0.01]",
                                  "wall.2.to=[0.0,0.01]",
                                  "wall.3.from=[0.0,0.01]",
                                  "collision.model=spring_dashpot",
                                  "collision.stiffness=0",
                                  "collision.friction=0.3",
                                  "body.0.center=[0.01,0.00137]",
                                  "body.0.velocity=[0.01,-0.01]",
                                  "output.interval=0.0005",
                                  "output.snapshots=false"};
    sets.insert(sets.end(), extra.begin(), extra.end());
    for (const std::string& s : sets) {
      a.push_back("--set");
      a.push_back(s);
    }
    return a;
  };
  const auto full = cli(args(dir / "full", "0.011"));
  ASSERT_EQ(full.code, 0) << full.output;
  const auto half = cli(args(dir / "half", "0.008"));
  ASSERT_EQ(half.code, 0) << half.output;
}

/// Resumes DIR/half (run_contact_case) to 0.011 s: its bodies.csv and final checkpoint are those of DIR/full.
void expect_contact_resume_identical(const fs::path& dir) {
  const auto resumed = cli({"resume", (dir / "half").string(), "--set", "time.end=0.011", "--threads", "1",
                            "--quiet", "--no-plots"});
  ASSERT_EQ(resumed.code, 0) << resumed.output;
  const std::string bodies = read_text(dir / "full" / "bodies.csv");
  EXPECT_NE(bodies.find("0.008,0,"), std::string::npos);
  EXPECT_TRUE(bodies == read_text(dir / "half" / "bodies.csv"));
  EXPECT_TRUE(read_text(dir / "full" / "checkpoint" / "state.bin") ==
              read_text(dir / "half" / "checkpoint" / "state.bin"));
}

}  // namespace

TEST(Resume, HalfRunResumedToTheEndIsBitwiseIdentical) {
  const fs::path dir = fresh_dir("resume_half");
  const auto full = cli(couette(dir / "full", "0.2"));
  ASSERT_EQ(full.code, 0) << full.output;
  const auto half = cli(couette(dir / "half", "0.1"));
  ASSERT_EQ(half.code, 0) << half.output;
  ASSERT_TRUE(fs::exists(dir / "half" / "checkpoint" / "state.bin"));
  const auto resumed = cli({"resume", (dir / "half").string(), "--set", "time.end=0.2", "--threads", "1",
                                  "--quiet", "--no-plots"});
  ASSERT_EQ(resumed.code, 0) << resumed.output;
  expect_same_outputs(dir / "full", dir / "half");
  EXPECT_FALSE(fs::exists(dir / "half" / ".resume")) << "the scratch directory is removed";
  const std::string summary = read_text(dir / "half" / "summary.json");
  EXPECT_NE(summary.find("\"status\": \"completed\""), std::string::npos) << summary;
  EXPECT_NE(summary.find("\"resumed_from\": 0.1"), std::string::npos) << summary;
  EXPECT_NE(read_text(dir / "half" / "case.toml").find("end = 0.2"), std::string::npos);
  // The final checkpoints agree too (same state, same case).
  EXPECT_TRUE(read_text(dir / "full" / "checkpoint" / "state.bin") == read_text(dir / "half" / "checkpoint" / "state.bin"));
}

TEST(Resume, BodyInContactResumesBitwiseIdentical) {
  // The contact episode's held approach speed (RigidGroup::contact_speed) and the collision
  // torque travel with the checkpoint, taken while the cylinder is in contact.
  const fs::path dir = fresh_dir("resume_contact");
  run_contact_case(dir, {"numerics.rhie_chow_factor=2"});
  expect_contact_resume_identical(dir);
}

TEST(Resume, RunInterruptedBySigintResumesBitwiseIdentical) {
  const fs::path dir = fresh_dir("resume_sigint");
  const auto full = cli(couette(dir / "full", "1.5"));
  ASSERT_EQ(full.code, 0) << full.output;

  cli_test::Child child(PARTICULA_BINARY, couette(dir / "cut", "1.5", {"--set", "output.checkpoint_interval=0.02"}));
  const fs::path state = dir / "cut" / "checkpoint" / "state.bin";
  ASSERT_TRUE(wait_for_periodic_checkpoint(state)) << "no periodic checkpoint";
  child.signal(SIGINT);
  const auto cut = child.wait();
  ASSERT_EQ(cut.code, 130) << cut.output;
  const std::string summary = read_text(dir / "cut" / "summary.json");
  EXPECT_NE(summary.find("\"status\": \"interrupted\""), std::string::npos) << summary;
  const auto k = particula::read_checkpoint(state);
  EXPECT_GT(k.time, 0.0);
  EXPECT_LT(k.time, 1.5);

  const auto resumed = cli({"resume", (dir / "cut").string(), "--threads", "1", "--quiet", "--no-plots"});
  ASSERT_EQ(resumed.code, 0) << resumed.output;
  expect_same_outputs(dir / "full", dir / "cut");
}

TEST(Resume, SigtermAlsoInterruptsWithACheckpoint) {
  const fs::path dir = fresh_dir("resume_sigterm");
  cli_test::Child child(PARTICULA_BINARY, couette(dir / "run", "1.5", {"--set", "output.checkpoint_interval=0.02"}));
  const fs::path state = dir / "run" / "checkpoint" / "state.bin";
  ASSERT_TRUE(wait_for_periodic_checkpoint(state)) << "no periodic checkpoint";
  child.signal(SIGTERM);
  const auto r = child.wait();
  EXPECT_EQ(r.code, 130) << r.output;
  EXPECT_NE(r.output.find("particula resume"), std::string::npos) << r.output;
}

TEST(Resume, DamagedCheckpointIsRefusedWithExitTwo) {
  const fs::path dir = fresh_dir("resume_damaged");
  const auto run = cli(couette(dir / "run", "0.02"));
  ASSERT_EQ(run.code, 0) << run.output;
  const fs::path state = dir / "run" / "checkpoint" / "state.bin";
  const std::string good = read_text(state);
  ASSERT_GT(good.size(), 1000u);
  struct Damage {
    std::string name, bytes, expect;
  };
  std::string flipped = good;
  flipped[good.size() / 2] = static_cast<char>(flipped[good.size() / 2] ^ 0x01);
  std::string magic = good;
  magic[1] = '?';
  std::string version = good;
  version[8] = static_cast<char>(version[8] + 1);
  const std::vector<Damage> damages{{"flipped byte", flipped, "checksum mismatch"},
                                    {"truncated", good.substr(0, good.size() / 2), "truncated"},
                                    {"empty", "", "truncated"},
                                    {"wrong magic", magic, "not a particula checkpoint"},
                                    {"other version", version, "format version"}};
  for (const auto& d : damages) {
    cli_test::write_text(state, d.bytes);
    const auto r = cli({"resume", (dir / "run").string(), "--quiet", "--no-plots"});
    EXPECT_EQ(r.code, 2) << d.name << ": " << r.output;
    EXPECT_NE(r.output.find(state.string()), std::string::npos) << d.name << ": " << r.output;
    EXPECT_NE(r.output.find(d.expect), std::string::npos) << d.name << ": " << r.output;
  }
  cli_test::write_text(state, good);
  const auto r = cli({"resume", (dir / "run").string(), "--quiet", "--no-plots", "--set", "time.end=0.03"});
  EXPECT_EQ(r.code, 0) << r.output;
}

TEST(Resume, OnlyTimeEndAndOutputKeysMayChange) {
  const fs::path dir = fresh_dir("resume_keys");
  const auto run = cli(couette(dir / "run", "0.02"));
  ASSERT_EQ(run.code, 0) << run.output;
  auto r = cli({"resume", (dir / "run").string(), "--set", "fluid.nu=2e-6"});
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("fluid.nu"), std::string::npos) << r.output;
  r = cli({"resume", (dir / "run").string(), "--set", "time.end=0.01"});
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("time.end"), std::string::npos) << r.output;
  r = cli({"resume", (dir / "run").string(), "--set", "output.interval=-1"});
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("output.interval"), std::string::npos) << r.output;
  r = cli({"resume", (dir / "nowhere").string()});
  EXPECT_EQ(r.code, 2) << r.output;
  fs::remove(dir / "run" / "checkpoint" / "state.bin");
  r = cli({"resume", (dir / "run").string()});
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("state.bin"), std::string::npos) << r.output;
}

TEST(Resume, NumericalFailureWritesADiagnosticCheckpoint) {
  const fs::path dir = fresh_dir("resume_failure");
  const auto r = cli({"run", (fs::path(PARTICULA_SOURCE_DIR) / "cases" / "hydrostatic.toml").string(), "--out",
                            (dir / "run").string(), "--quiet", "--no-plots", "--set", "fluid.c=0.05", "--set",
                            "resolution.d0=0.005"});
  ASSERT_EQ(r.code, 3) << r.output;
  const fs::path diag = dir / "run" / "checkpoint" / "failure.bin";
  ASSERT_TRUE(fs::exists(diag)) << r.output;
  const auto k = particula::read_checkpoint(diag);
  EXPECT_GT(k.step, 0);
  EXPECT_NE(r.output.find("failure.bin"), std::string::npos) << r.output;
}

TEST(Resume, CheckpointOfAnotherCaseIsRefused) {
  // Another case's state.bin copied into a run directory.
  const fs::path dir = fresh_dir("resume_other_case");
  ASSERT_EQ(cli(couette(dir / "couette", "0.02")).code, 0);
  const auto other = cli({"run", (fs::path(PARTICULA_SOURCE_DIR) / "cases" / "hydrostatic.toml").string(), "--out",
                          (dir / "hydro").string(), "--quiet", "--no-plots", "--set", "time.end=0.005", "--set",
                          "resolution.d0=0.01"});
  ASSERT_EQ(other.code, 0) << other.output;
  const std::string case_before = read_text(dir / "couette" / "case.toml");
  const std::string walls_before = read_text(dir / "couette" / "walls.csv");
  fs::copy_file(dir / "hydro" / "checkpoint" / "state.bin", dir / "couette" / "checkpoint" / "state.bin",
                fs::copy_options::overwrite_existing);
  const auto r = cli({"resume", (dir / "couette").string(), "--quiet", "--no-plots", "--set", "time.end=0.04"});
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("written for another case"), std::string::npos) << r.output;
  EXPECT_EQ(read_text(dir / "couette" / "case.toml"), case_before) << "nothing is written";
  EXPECT_EQ(read_text(dir / "couette" / "walls.csv"), walls_before);

  // A directory particula did not make is not resumed either.
  fs::create_directories(dir / "made_by_hand" / "checkpoint");
  fs::copy_file(dir / "hydro" / "checkpoint" / "state.bin", dir / "made_by_hand" / "checkpoint" / "state.bin");
  const auto h = cli({"resume", (dir / "made_by_hand").string(), "--quiet", "--no-plots"});
  EXPECT_EQ(h.code, 2) << h.output;
  EXPECT_NE(h.output.find("not a particula run directory"), std::string::npos) << h.output;
}

TEST(Resume, KeptLoadBandResumesBitwiseIdentical) {
  // numerics.load_band_motion keeps the band of the momentum loads over steps: the checkpoint at
  // t = 0.008 s falls between two of its builds (its build state is older than the particles), and
  // the resumed run builds it again from that state. The contact case above.
  const fs::path dir = fresh_dir("resume_kept_band");
  run_contact_case(dir, {"numerics.load_band_motion=0.2"});
  const fs::path state = dir / "half" / "checkpoint" / "state.bin";
  const particula::Checkpoint k = particula::decode_checkpoint(read_text(state), state);
  ASSERT_TRUE(k.load_band.held());
  bool older = false;  // the band at the checkpoint was built at an earlier step
  for (std::size_t i = 0; i < k.particles.x.size(); ++i)
    older = older || k.load_band.x[i].x != k.particles.x[i].x || k.load_band.x[i].y != k.particles.x[i].y;
  EXPECT_TRUE(older);
  expect_contact_resume_identical(dir);
  // kept: fewer builds than steps
  const std::string summary = read_text(dir / "full" / "summary.json");
  const auto builds = summary.find("\"load_band_builds\": "), steps = summary.find("\"steps\": ");
  ASSERT_NE(builds, std::string::npos) << summary;
  ASSERT_NE(steps, std::string::npos) << summary;
  EXPECT_LT(std::stol(summary.substr(builds + 20)), std::stol(summary.substr(steps + 9)) / 2) << summary;
}

TEST(Resume, TamperedCheckpointWithAValidChecksumIsRefusedWithExitTwo) {
  // Every index, count, kind, id, size and identity edited in turn (tests/checkpoint_tamper.hpp),
  // written with a valid checksum: `resume` refuses each with exit code 2 and never crashes.
  const fs::path dir = fresh_dir("resume_tampered");
  cli_test::write_text(dir / "tamper.toml", tamper::kCase);
  const auto run = cli({"run", (dir / "tamper.toml").string(), "--out", (dir / "run").string(), "--quiet",
                        "--no-plots", "--threads", "1"});
  ASSERT_EQ(run.code, 0) << run.output;
  const fs::path state = dir / "run" / "checkpoint" / "state.bin";
  const std::string good = read_text(state);
  const particula::Checkpoint k0 = particula::decode_checkpoint(good, state);
  int refused = 0, crashed = 0, total = 0;
  for (const auto& t : tamper::structured()) {
    particula::Checkpoint k = k0;
    t.apply(k);
    cli_test::write_text(state, particula::encode_checkpoint(k));
    const auto r = cli({"resume", (dir / "run").string(), "--quiet", "--no-plots", "--threads", "1", "--set",
                        "time.end=0.002"});
    ++total;
    refused += r.code == 2 ? 1 : 0;
    crashed += r.signal != 0 ? 1 : 0;
    EXPECT_EQ(r.code, 2) << t.name << ": " << r.output;
    EXPECT_EQ(r.signal, 0) << t.name << ": " << r.output;
    EXPECT_NE(r.output.find("state.bin"), std::string::npos) << t.name << ": " << r.output;
  }
  std::printf("tampered checkpoints through 'particula resume': %d, exit 2: %d, crashes: %d\n", total, refused, crashed);
  cli_test::write_text(state, good);
  const auto r = cli({"resume", (dir / "run").string(), "--quiet", "--no-plots", "--threads", "1", "--set",
                      "time.end=0.002"});
  EXPECT_EQ(r.code, 0) << r.output;
}

TEST(Resume, TurningWallResumesBitwiseIdentical) {
  // The spin-up container (an arc wall turning about its centre), coarse: its pose,
  // its particles running round the circle and its torque continue exactly.
  const fs::path dir = fresh_dir("resume_turning_wall");
  const fs::path spin = fs::path(PARTICULA_SOURCE_DIR) / "cases" / "spin_up.toml";
  auto run = [&](const fs::path& out, const char* t_end) {
    return cli({"run", spin.string(), "--out", out.string(), "--quiet", "--no-plots", "--threads", "1", "--set",
                "resolution.d0=1e-3", "--set", std::string("time.end=") + t_end});
  };
  ASSERT_EQ(run(dir / "full", "0.1").code, 0);
  ASSERT_EQ(run(dir / "half", "0.05").code, 0);
  const auto resumed = cli({"resume", (dir / "half").string(), "--set", "time.end=0.1", "--threads", "1", "--quiet",
                            "--no-plots"});
  ASSERT_EQ(resumed.code, 0) << resumed.output;
  for (const char* f : {"walls.csv", "probe_radius.csv"}) {
    EXPECT_FALSE(read_text(dir / "full" / f).empty()) << f;
    EXPECT_TRUE(read_text(dir / "full" / f) == read_text(dir / "half" / f)) << f;
  }
  EXPECT_TRUE(read_text(dir / "full" / "checkpoint" / "state.bin") == read_text(dir / "half" / "checkpoint" / "state.bin"));
}
