// A numerical failure detected in a step (exit code 3): what, and where.
#pragma once

#include <cstdint>
#include <string>

#include "particula/core/types.hpp"

namespace particula {

struct Failure {
  std::string what;
  std::int64_t particle_id = -1;
  Vec2 position;
};

}  // namespace particula
