# What built this binary goes into every output file: version, git sha, backend set, flags.
# The sha is read at build time (not configure time), so a rebuild after a commit records the new one.
string(JOIN " " BLEEDSIM_BUILD_FLAGS
  "build=${CMAKE_BUILD_TYPE}"
  "cxx=${CMAKE_CXX_COMPILER_ID}-${CMAKE_CXX_COMPILER_VERSION}"
  "cxxflags=${CMAKE_CXX_FLAGS} ${CMAKE_CXX_FLAGS_${CMAKE_BUILD_TYPE}}"
  "fp=${BLEEDSIM_HOST_FP_FLAGS}")
if(BLEEDSIM_HAVE_CUDA)
  string(APPEND BLEEDSIM_BUILD_FLAGS
    " nvcc=${CMAKE_CUDA_COMPILER_VERSION} cuda_arch=${CMAKE_CUDA_ARCHITECTURES} cuda_fp=${BLEEDSIM_CUDA_FP_FLAGS}")
endif()
string(REPLACE ";" " " BLEEDSIM_BUILD_FLAGS "${BLEEDSIM_BUILD_FLAGS}")

set(BLEEDSIM_GIT_SHA_FILE ${CMAKE_BINARY_DIR}/generated/git_sha.cpp)
add_custom_target(bleedsim_git_sha
  COMMAND ${CMAKE_COMMAND} -DSOURCE_DIR=${CMAKE_SOURCE_DIR} -DOUT=${BLEEDSIM_GIT_SHA_FILE}
          -P ${CMAKE_SOURCE_DIR}/cmake/WriteGitSha.cmake
  BYPRODUCTS ${BLEEDSIM_GIT_SHA_FILE}
  COMMENT "Reading the git sha"
  VERBATIM)
configure_file(${CMAKE_SOURCE_DIR}/core/runtime/build_info.cpp.in ${CMAKE_BINARY_DIR}/generated/build_info.cpp @ONLY)
