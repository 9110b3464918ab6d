#include "particula/solver/time_step.hpp"

namespace particula {

const char* step_limit_name(StepLimit l) {
  switch (l) {
    case StepLimit::Acoustic:
      return "acoustic";
    case StepLimit::Viscous:
      return "viscous";
    case StepLimit::DtMax:
      return "dt_max";
    case StepLimit::BodyForce:
      return "body_force";
    case StepLimit::Contact:
      return "contact";
    case StepLimit::Landing:
      return "output_time";
  }
  return "";
}

}  // namespace particula
