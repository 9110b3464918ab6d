// The CUDA backend's entry points in a build without the CUDA toolkit (PARTICULA_CUDA off or
// nvcc not found): they say so, and `--backend cuda` ends with a clear error.
#ifndef PARTICULA_HAVE_CUDA

#include <stdexcept>

#include "particula/solver/backend.hpp"

namespace particula {

bool cuda_backend_available(std::string* why) {
  if (why) *why = "this particula was built without CUDA (nvcc not found, or -DPARTICULA_CUDA=OFF)";
  return false;
}

std::unique_ptr<Backend> make_cuda_backend(const PhysicsParams&, const GridGeometry&, const WendlandC2&,
                                                 const Particles&) {
  std::string why;
  cuda_backend_available(&why);
  throw std::runtime_error(why);
}

}  // namespace particula

#endif
