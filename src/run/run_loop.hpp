// What `particula run` (runner.cpp) and `particula resume` (resume.cpp) share: the time loop,
// the stop flag SIGINT and SIGTERM set, the run's messages, and the exit codes of bad input,
// I/O failures and a stop before the loop.
#pragma once

#include <cstdio>
#include <exception>
#include <filesystem>
#include <string>

#include "particula/io/error.hpp"
#include "particula/io/log.hpp"
#include "session.hpp"

namespace particula::run_detail {

/// Whether SIGINT or SIGTERM asked the run to stop (polled between steps and by long outputs).
bool stop_requested();

/// Installs SIGINT/SIGTERM handlers for the lifetime of a command; the loop checks the flag
/// between steps, so a step is never left half-done, and long outputs poll it.
struct SignalGuard {
  SignalGuard();
  ~SignalGuard();
  SignalGuard(const SignalGuard&) = delete;
  SignalGuard& operator=(const SignalGuard&) = delete;

 private:
  void (*old_int)(int);
  void (*old_term)(int);
};

/// The log file and the messages of a run (echoed to stderr unless quiet).
struct Reporter {
  io::RunLog log;
  bool quiet;
  Reporter(const std::filesystem::path& file, bool q) : log(file, false), quiet(q) {}
  void say(const std::string& text) {
    log.line(text);
    if (!quiet) std::fprintf(stderr, "%s\n", text.c_str());
  }
  /// Printed even with --quiet.
  void tell(const std::string& text) {
    log.line(text);
    std::fprintf(stderr, "%s\n", text.c_str());
  }
};

/// Writes the initial state (unless resumed), steps to time.end with the outputs on their
/// schedule and checkpoints every output.checkpoint_interval, stops on a signal (exit 130),
/// max_steps or a numerical failure (exit 3), then writes the final state, a checkpoint,
/// summary.json and the plots. Returns the exit code.
int run_loop(Session& s, Reporter& rep, bool plots);

/// Bad input (exit code 2): the message on standard error.
int bad_input(const std::exception& e);

/// A file-system failure (exit code kExitIoFailure): a run that had not started is undone, one
/// that had keeps its last checkpoint and says how to resume.
int io_failure(const io::WriteError& e, Session& s, Reporter* rep);

/// A stop request before the time loop: nothing is run (exit 130).
int interrupted_before_start(Session& s, Reporter& rep, const char* what);

/// Whether the requested backend exists here (says why not; checked before anything is written).
bool backend_usable(const std::string& backend);

}  // namespace particula::run_detail
