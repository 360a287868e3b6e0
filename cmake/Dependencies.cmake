# Every dependency comes from Debian packages (scripts/setup installs them).
find_package(PkgConfig REQUIRED)

# toml++ and CLI11 are used header-only: nothing to ship beside the binaries.
find_path(TOMLPP_INCLUDE_DIR toml++/toml.h REQUIRED)
find_package(CLI11 CONFIG REQUIRED)
# Eigen (header-only) for the haptics' host-side geometry.
find_package(Eigen3 3.3 REQUIRED NO_MODULE)
find_path(STB_INCLUDE_DIR stb/stb_image_write.h REQUIRED)
find_path(TINYOBJLOADER_INCLUDE_DIR tiny_obj_loader.h REQUIRED)   # tissue meshes (OBJ), header-only use

# HDF5 (C API). For the GPU machine, which has no HDF5, link the static archives Debian ships.
if(BLEEDSIM_STATIC)
  find_library(HDF5_STATIC_LIB libhdf5.a PATHS /usr/lib/x86_64-linux-gnu/hdf5/serial REQUIRED NO_DEFAULT_PATH)
  find_library(SZ_STATIC_LIB libsz.a REQUIRED)
  find_library(AEC_STATIC_LIB libaec.a REQUIRED)
  find_library(Z_STATIC_LIB libz.a REQUIRED)
  add_library(bleedsim_hdf5 INTERFACE)
  target_include_directories(bleedsim_hdf5 INTERFACE /usr/include/hdf5/serial)
  target_link_libraries(bleedsim_hdf5 INTERFACE ${HDF5_STATIC_LIB} ${SZ_STATIC_LIB} ${AEC_STATIC_LIB}
                        ${Z_STATIC_LIB} ${CMAKE_DL_LIBS} m pthread)
else()
  pkg_check_modules(HDF5 REQUIRED IMPORTED_TARGET hdf5-serial)
  add_library(bleedsim_hdf5 INTERFACE)
  target_link_libraries(bleedsim_hdf5 INTERFACE PkgConfig::HDF5)
endif()

# zlib, to check a texture's compressed image data before stb inflates it (core/io/tissue_png.cpp):
# static for the GPU machine, as HDF5's is.
add_library(bleedsim_zlib INTERFACE)
if(BLEEDSIM_STATIC)
  target_link_libraries(bleedsim_zlib INTERFACE ${Z_STATIC_LIB})
else()
  find_package(ZLIB REQUIRED)
  target_link_libraries(bleedsim_zlib INTERFACE ZLIB::ZLIB)
endif()

find_package(Threads REQUIRED)
if(BLEEDSIM_TESTS)
  find_package(GTest REQUIRED)
endif()
if(BLEEDSIM_BENCH)
  find_package(benchmark REQUIRED)
endif()
