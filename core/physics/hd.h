#pragma once
// BLEEDSIM_HD marks the physics functions both backends share: __host__ __device__ under nvcc,
// nothing for the host compiler. Each effect's per-element math is written once with it, in core/.
#if defined(__CUDACC__)
#define BLEEDSIM_HD __host__ __device__
#else
#define BLEEDSIM_HD
#endif
