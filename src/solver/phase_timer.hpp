// Wall-clock timing of the step's phases (PhaseTimes), shared by the solver and the CPU backend.
#pragma once

#include <chrono>

namespace particula {

/// Adds the wall-clock time of a scope to one PhaseTimes entry.
class PhaseTimer {
 public:
  explicit PhaseTimer(double& slot) : slot_(slot), t0_(std::chrono::steady_clock::now()) {}
  ~PhaseTimer() { slot_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0_).count(); }
  PhaseTimer(const PhaseTimer&) = delete;
  PhaseTimer& operator=(const PhaseTimer&) = delete;

 private:
  double& slot_;
  std::chrono::steady_clock::time_point t0_;
};

}  // namespace particula
