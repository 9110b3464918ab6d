// Device memory and kernel launches for the CUDA backend: a growing device array with host
// transfers, and `each`, which runs a device lambda once per index. Shared by the backend's
// translation units (cuda_backend.cu, cuda_passes.cu, cuda_bodies.cu).
#pragma once

#include <cuda_runtime.h>
#include <thrust/device_ptr.h>

#include <algorithm>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

namespace particula::gpu {

inline void check(cudaError_t e, const char* what) {
  if (e != cudaSuccess)
    throw std::runtime_error(std::string("CUDA error in ") + what + ": " + cudaGetErrorString(e));
}

/// A device array that only grows (no allocation once the sizes have settled).
template <class T>
class DArray {
 public:
  DArray() = default;
  DArray(const DArray&) = delete;
  DArray& operator=(const DArray&) = delete;
  ~DArray() {
    if (p_) cudaFree(p_);
  }
  void resize(std::size_t n) {
    if (n > cap_) {
      if (p_) check(cudaFree(p_), "cudaFree");
      p_ = nullptr;
      check(cudaMalloc(&p_, std::max<std::size_t>(n, 1) * sizeof(T)), "cudaMalloc");
      cap_ = n;
    }
    n_ = n;
  }
  T* data() { return p_; }
  const T* data() const { return p_; }
  std::size_t size() const { return n_; }
  void upload(const std::vector<T>& v) {
    resize(v.size());
    if (!v.empty()) check(cudaMemcpy(p_, v.data(), v.size() * sizeof(T), cudaMemcpyHostToDevice), "upload");
  }
  void download(std::vector<T>& v) const {
    v.resize(n_);
    if (n_) check(cudaMemcpy(v.data(), p_, n_ * sizeof(T), cudaMemcpyDeviceToHost), "download");
  }
  void copy_from(const DArray& o) {
    resize(o.n_);
    if (n_) check(cudaMemcpy(p_, o.p_, n_ * sizeof(T), cudaMemcpyDeviceToDevice), "copy");
  }
  thrust::device_ptr<T> begin() { return thrust::device_pointer_cast(p_); }
  thrust::device_ptr<T> end() { return thrust::device_pointer_cast(p_ + n_); }

 private:
  T* p_ = nullptr;
  std::size_t n_ = 0, cap_ = 0;
};

template <class F>
__global__ void each_kernel(std::size_t first, std::size_t last, F f) {
  const std::size_t i = first + static_cast<std::size_t>(blockIdx.x) * blockDim.x + threadIdx.x;
  if (i < last) f(i);
}

/// Runs f(i) for i in [first, last), one thread each.
template <class F>
void each(std::size_t first, std::size_t last, F f) {
  if (last <= first) return;
  const std::size_t n = last - first;
  constexpr unsigned block = 128;
  each_kernel<<<static_cast<unsigned>((n + block - 1) / block), block>>>(first, last, f);
  check(cudaGetLastError(), "kernel launch");
}

}  // namespace particula::gpu
