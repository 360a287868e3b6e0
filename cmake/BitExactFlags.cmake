# The CPU reference and the CUDA kernels must give the same bytes (docs/bit-exactness.md).
# Contraction into FMA and fast-math would let each compiler round differently, so both are off
# everywhere, also in the host pass of .cu files.
set(BLEEDSIM_HOST_FP_FLAGS -ffp-contract=off -fno-fast-math)
set(BLEEDSIM_CUDA_FP_FLAGS -fmad=false -prec-div=true -prec-sqrt=true -ftz=false)

add_library(bleedsim_flags INTERFACE)
target_compile_options(bleedsim_flags INTERFACE
  $<$<COMPILE_LANGUAGE:CXX>:${BLEEDSIM_HOST_FP_FLAGS} -Wall -Wextra -Wpedantic>
  $<$<COMPILE_LANGUAGE:CUDA>:${BLEEDSIM_CUDA_FP_FLAGS} -Xcompiler=-ffp-contract=off,-fno-fast-math>)

if(BLEEDSIM_STATIC)
  target_link_options(bleedsim_flags INTERFACE -static-libstdc++ -static-libgcc)
endif()
