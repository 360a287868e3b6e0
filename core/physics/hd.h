#pragma once
// BLEEDSIM_HD marks the physics functions both backends share: __host__ __device__ under nvcc,
// nothing for the host compiler. Each effect's per-element math is written once with it, in core/.
#if defined(__CUDACC__)
#define BLEEDSIM_HD __host__ __device__
#else
#define BLEEDSIM_HD
#endif

#include <cstddef>

// fmaxf and fminf, inline on the host as well. GCC calls libm for them (it may not assume away NaNs
// and signed zeros), and such a call in the particle step's pair loop spills the pair sums to the
// stack around it. On the host: the larger (smaller) of two numbers, the number when the other is a
// NaN, as libm and CUDA give them; where C leaves the result open they return y for +0 against −0
// (libm gave either zero, as GCC ordered the call's arguments) and x for two NaNs. On the GPU, CUDA's.
BLEEDSIM_HD inline float max_float(float x, float y) {
#if defined(__CUDA_ARCH__)
  return fmaxf(x, y);
#else
  return x > y || y != y ? x : y;
#endif
}

BLEEDSIM_HD inline float min_float(float x, float y) {
#if defined(__CUDA_ARCH__)
  return fminf(x, y);
#else
  return x < y || y != y ? x : y;
#endif
}

// The (x, y) pair i of an interleaved array (x0, y0, x1, y1, ...). On the GPU one 8-byte access (the
// arrays start 256-byte aligned), where two 4-byte ones cost two load or store instructions and, for
// a scattered pair, two trips to memory; the same two floats either way.
struct FloatPair {
  float x, y;
};

BLEEDSIM_HD inline FloatPair pair_at(const float* xy, std::size_t i) {
#if defined(__CUDA_ARCH__)
  const float2 v = reinterpret_cast<const float2*>(xy)[i];
  return {v.x, v.y};
#else
  return {xy[2 * i], xy[2 * i + 1]};
#endif
}

BLEEDSIM_HD inline void set_pair(float* xy, std::size_t i, FloatPair v) {
#if defined(__CUDA_ARCH__)
  reinterpret_cast<float2*>(xy)[i] = make_float2(v.x, v.y);
#else
  xy[2 * i] = v.x;
  xy[2 * i + 1] = v.y;
#endif
}
