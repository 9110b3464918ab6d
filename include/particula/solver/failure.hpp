// A numerical failure detected in a step (exit code 3): what, and where.
#pragma once

#include <cstdint>
#include <string>

#include "particula/core/types.hpp"
#include "particula/core/types3.hpp"

namespace particula {

/// In D dimensions (`Failure` the 2D solver's).
template <int D>
struct FailureOf {
  std::string what;
  std::int64_t particle_id = -1;
  Vec<D> position;
};
using Failure = FailureOf<2>;

}  // namespace particula
