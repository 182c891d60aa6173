# Install.cmake — what `cmake --install build/release --prefix P` puts in place:
#   P/bin/shadowref                                  (cmd/CMakeLists.txt)
#   P/share/shadowref/conformance/scenes/            the catalogue, meshes included
#   P/share/shadowref/goldens/images/                the reference masks `shadowref goldens` checks
#   P/share/shadowref/pack/README.template.md        the pack README's template `shadowref export` fills
#   P/share/shadowref/report.schema.json             report.json's JSON Schema (docs/output-contract.md)
#   P/include/shadowref/*.hpp                        the header-only math (mathlib/CMakeLists.txt)
#   P/share/cmake/shadowref/                         find_package(shadowref): shadowref::mathlib, with
#                                                    Eigen3 found by find_dependency, and
#                                                    shadowref_add_math_properties() for an engine's tree
#   P/share/shadowref/property_tests/                the sources that function compiles
#   P/share/pkgconfig/shadowref.pc                   pkg-config: the include folder and eigen3's
# The data keeps its source-tree layout under share/shadowref, so that the binary has one rule for
# finding it (conform::data_dir()). The math is header-only, so its package files are
# architecture-independent and live under share/.
include(CMakePackageConfigHelpers)

set(SHADOWREF_INSTALL_DATADIR ${CMAKE_INSTALL_DATADIR}/shadowref)
set(SHADOWREF_INSTALL_CMAKEDIR ${CMAKE_INSTALL_DATADIR}/cmake/shadowref)

install(DIRECTORY ${PROJECT_SOURCE_DIR}/conformance/scenes DESTINATION ${SHADOWREF_INSTALL_DATADIR}/conformance)
install(DIRECTORY ${PROJECT_SOURCE_DIR}/goldens/images DESTINATION ${SHADOWREF_INSTALL_DATADIR}/goldens)
install(FILES ${PROJECT_SOURCE_DIR}/pack/README.template.md DESTINATION ${SHADOWREF_INSTALL_DATADIR}/pack)
install(FILES ${PROJECT_SOURCE_DIR}/conformance/record/report.schema.json DESTINATION ${SHADOWREF_INSTALL_DATADIR})

install(EXPORT shadowrefTargets NAMESPACE shadowref:: DESTINATION ${SHADOWREF_INSTALL_CMAKEDIR})
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/shadowrefConfig.cmake.in
  ${PROJECT_BINARY_DIR}/shadowrefConfig.cmake INSTALL_DESTINATION ${SHADOWREF_INSTALL_CMAKEDIR})
write_basic_package_version_file(${PROJECT_BINARY_DIR}/shadowrefConfigVersion.cmake
  COMPATIBILITY SameMinorVersion ARCH_INDEPENDENT)
configure_file(${PROJECT_SOURCE_DIR}/property_tests/shadowrefProperties.cmake.in
  ${PROJECT_BINARY_DIR}/shadowrefProperties.cmake @ONLY)
install(FILES ${PROJECT_BINARY_DIR}/shadowrefConfig.cmake ${PROJECT_BINARY_DIR}/shadowrefConfigVersion.cmake
  ${PROJECT_BINARY_DIR}/shadowrefProperties.cmake DESTINATION ${SHADOWREF_INSTALL_CMAKEDIR})

install(FILES
  ${PROJECT_SOURCE_DIR}/property_tests/math_properties_test.cpp ${PROJECT_SOURCE_DIR}/property_tests/property_main.cpp
  ${PROJECT_SOURCE_DIR}/property_tests/math_properties.hpp ${PROJECT_SOURCE_DIR}/property_tests/math_adapter.hpp
  ${PROJECT_SOURCE_DIR}/property_tests/generators.hpp ${PROJECT_SOURCE_DIR}/property_tests/property_support.hpp
  DESTINATION ${SHADOWREF_INSTALL_DATADIR}/property_tests)
install(DIRECTORY ${PROJECT_SOURCE_DIR}/property_tests/adapters DESTINATION ${SHADOWREF_INSTALL_DATADIR}/property_tests)

configure_file(${PROJECT_SOURCE_DIR}/cmake/shadowref.pc.in ${PROJECT_BINARY_DIR}/shadowref.pc @ONLY)
install(FILES ${PROJECT_BINARY_DIR}/shadowref.pc DESTINATION ${CMAKE_INSTALL_DATADIR}/pkgconfig)

# Tests (label `install`): install to a prefix in the build tree, then build consumers against it and
# run the installed binary from outside the source tree, with the source tree hidden
# (cmake/install_test/install_test.sh says what each mode proves).
if(SHADOWREF_BUILD_TESTS)
  set(_install_test ${PROJECT_SOURCE_DIR}/cmake/install_test/install_test.sh)
  set(_install_work ${PROJECT_BINARY_DIR}/install-test)
  add_test(NAME install.prefix COMMAND ${_install_test} prefix ${PROJECT_BINARY_DIR} ${_install_work})
  shadowref_hang_guard(_install_guard 50)  # install.properties builds a consumer: 46 s beside the suite
  set_tests_properties(install.prefix PROPERTIES FIXTURES_SETUP shadowref_installed LABELS install TIMEOUT ${_install_guard})
  foreach(mode cmake pkgconfig properties standalone)
    add_test(NAME install.${mode} COMMAND ${_install_test} ${mode} ${PROJECT_BINARY_DIR} ${_install_work})
    set_tests_properties(install.${mode} PROPERTIES FIXTURES_REQUIRED shadowref_installed LABELS install TIMEOUT ${_install_guard})
  endforeach()
  # The consumers build in folders of their own; the properties consumer is the slow one (one
  # RapidCheck translation unit), so it must not run beside another build on a 2-core machine.
  set_tests_properties(install.cmake install.pkgconfig install.properties PROPERTIES RESOURCE_LOCK shadowref_install_builds)
  shadowref_run_early(46 install.properties)
endif()
