// The host's particle passes for D = 2 (cpu_sweeps_impl.hpp).
#include "cpu_sweeps_impl.hpp"

namespace particula {

template class CpuSweepsOf<2>;

}  // namespace particula
