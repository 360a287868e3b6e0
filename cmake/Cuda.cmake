# The CUDA backend is built when nvcc is found (or BLEEDSIM_CUDA=ON); without it the build is
# CPU-only and says so. Kernels are compiled in CI, where no GPU can run them.
set(BLEEDSIM_HAVE_CUDA OFF)
if(NOT BLEEDSIM_CUDA STREQUAL "OFF")
  if(NOT CMAKE_CUDA_COMPILER AND NOT DEFINED ENV{CUDACXX} AND EXISTS /usr/local/cuda/bin/nvcc)
    set(CMAKE_CUDA_COMPILER /usr/local/cuda/bin/nvcc)
  endif()
  include(CheckLanguage)
  check_language(CUDA)
  if(CMAKE_CUDA_COMPILER)
    # sm_90 machine code for the H100/H200, plus compute_75 PTX that the driver compiles for any
    # other GPU from Turing on. PTX keeps the -fmad=false rounding, so bytes do not change.
    if(NOT DEFINED CMAKE_CUDA_ARCHITECTURES)
      set(CMAKE_CUDA_ARCHITECTURES "75-virtual;90-real")
    endif()
    enable_language(CUDA)
    set(CMAKE_CUDA_STANDARD 17)
    set(CMAKE_CUDA_STANDARD_REQUIRED ON)
    find_package(CUDAToolkit REQUIRED)
    set(BLEEDSIM_HAVE_CUDA ON)
    message(NOTICE "bleedsim: CUDA backend ON (nvcc ${CMAKE_CUDA_COMPILER_VERSION}, architectures ${CMAKE_CUDA_ARCHITECTURES})")
  elseif(BLEEDSIM_CUDA STREQUAL "ON")
    message(FATAL_ERROR "bleedsim: BLEEDSIM_CUDA=ON but no CUDA compiler was found (set CUDACXX or install the CUDA toolkit)")
  endif()
endif()
if(NOT BLEEDSIM_HAVE_CUDA)
  message(NOTICE "bleedsim: nvcc not found or CUDA disabled: building CPU-only. "
                 "The 'cuda' backend will report that this build has none; GPU parity tests will skip.")
endif()
