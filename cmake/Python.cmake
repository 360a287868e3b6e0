# The Python module (python/), with Debian's pybind11 (nanobind is not packaged in Debian 12) for
# Debian's Python, which has NumPy and h5py. Skipped, saying so, where either is missing.
set(BLEEDSIM_HAVE_PYTHON OFF)
if(BLEEDSIM_PYTHON)
  if(NOT DEFINED Python3_EXECUTABLE AND EXISTS /usr/bin/python3)
    set(Python3_EXECUTABLE /usr/bin/python3)
  endif()
  find_package(Python3 COMPONENTS Interpreter Development.Module)
  set(PYBIND11_FINDPYTHON ON)
  find_package(pybind11 2.10 CONFIG QUIET)
  if(Python3_FOUND AND pybind11_FOUND)
    set(BLEEDSIM_HAVE_PYTHON ON)
    # The module is a shared object that the static libraries go into.
    set(CMAKE_POSITION_INDEPENDENT_CODE ON)
    message(NOTICE "bleedsim: Python module ON (Python ${Python3_VERSION}, pybind11 ${pybind11_VERSION})")
  else()
    message(NOTICE "bleedsim: Python module skipped: needs python3-dev and pybind11-dev (scripts/setup installs them)")
  endif()
endif()
