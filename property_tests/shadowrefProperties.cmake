# shadowrefProperties.cmake — shadowref_add_math_properties() for an engine's own tree, installed
# with the package config (find_package(shadowref) includes it):
#   shadowref_add_math_properties(NAME ADAPTER_SOURCE [LIBRARIES your_engine ...])
# builds NAME from shadowref's math properties and ADAPTER_SOURCE, which defines
# shadowref::prop::math_adapter_under_test() (examples: <prefix>/share/shadowref/property_tests/adapters/),
# and registers its GoogleTest cases with CTest, labelled `property`. It needs GoogleTest and
# RapidCheck (Debian: libgtest-dev, librapidcheck-dev), found when the function is first called.
# The in-tree twin of this function is in property_tests/CMakeLists.txt.
function(shadowref_add_math_properties name adapter_source)
  cmake_parse_arguments(ARG "" "" "LIBRARIES" ${ARGN})
  # <prefix>/share/cmake/shadowref → <prefix>/share/shadowref/property_tests
  set(_shadowref_property_sources ${CMAKE_CURRENT_FUNCTION_LIST_DIR}/../../shadowref/property_tests)
  find_package(GTest REQUIRED)
  find_package(rapidcheck REQUIRED CONFIG)
  include(GoogleTest)
  add_executable(${name} ${_shadowref_property_sources}/math_properties_test.cpp
                         ${_shadowref_property_sources}/property_main.cpp ${adapter_source})
  target_include_directories(${name} PRIVATE ${_shadowref_property_sources})
  target_link_libraries(${name} PRIVATE shadowref::mathlib rapidcheck rapidcheck_gtest GTest::gtest ${ARG_LIBRARIES})
  # The seed and case count shadowref's own run uses (property_tests/README.md); RC_PARAMS overrides.
  target_compile_definitions(${name} PRIVATE SHADOWREF_RC_DEFAULTS="seed=20261121 max_success=1000")
  gtest_discover_tests(${name} PROPERTIES LABELS property DISCOVERY_TIMEOUT 60)
endfunction()
