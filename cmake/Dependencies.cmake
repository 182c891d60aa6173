# Every external dependency, found once, from Debian 12 packages (scripts/setup.sh installs them).
# Facts about these packages are in docs/dependencies.md; the workarounds below cite it.
find_package(Eigen3 3.4 REQUIRED CONFIG)
find_package(glm REQUIRED CONFIG)
find_package(nlohmann_json REQUIRED CONFIG)
find_package(CLI11 REQUIRED CONFIG)
find_package(tinyobjloader REQUIRED CONFIG)
find_package(TinyGLTF REQUIRED CONFIG)
find_package(meshoptimizer REQUIRED CONFIG)
find_package(embree 3 REQUIRED CONFIG)
find_package(TBB REQUIRED CONFIG)
find_package(Threads REQUIRED)

find_package(OpenImageIO REQUIRED CONFIG)
find_package(PNG REQUIRED)  # libpng writes the PNGs (outputs/src/image_io.cpp)
# Debian's OpenImageIO target names /usr/include/opencv4 as an include directory although the
# package does not depend on OpenCV; CMake refuses a non-existent include path at generate time.
get_target_property(_oiio_includes OpenImageIO::OpenImageIO INTERFACE_INCLUDE_DIRECTORIES)
if(_oiio_includes)
  list(FILTER _oiio_includes EXCLUDE REGEX "opencv4")
  set_target_properties(OpenImageIO::OpenImageIO PROPERTIES INTERFACE_INCLUDE_DIRECTORIES "${_oiio_includes}")
endif()

find_package(PkgConfig REQUIRED)
# OSMesa ships no CMake config, only a pkg-config file.
pkg_check_modules(OSMESA REQUIRED IMPORTED_TARGET osmesa)
pkg_check_modules(EGL REQUIRED IMPORTED_TARGET egl)
# RE2 (libre2-dev: pkg-config only) matches the regexes a user writes (expectations files) in linear time.
pkg_check_modules(RE2 REQUIRED IMPORTED_TARGET re2)

if(SHADOWREF_BUILD_TESTS)
  find_package(GTest REQUIRED)
  find_package(rapidcheck REQUIRED CONFIG)
  find_package(ZLIB REQUIRED)  # the bad-input table deflates its own PNGs
endif()
if(SHADOWREF_BUILD_BENCH)
  find_package(benchmark REQUIRED CONFIG)
endif()
