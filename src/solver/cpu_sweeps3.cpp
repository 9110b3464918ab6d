// The host's particle passes for D = 3 (cpu_sweeps_impl.hpp).
#include "cpu_sweeps_impl.hpp"

namespace particula {

template class CpuSweepsOf<3>;

}  // namespace particula
