# The suite's two tiers. The default tier (`ctest --preset release`, what the Quick start and CI
# run) exercises every check at least once; the deep tier (`ctest --preset deep`, label "deep") runs
# the same checks again where they cost most: more scenes of one grid, the same variants at more
# map sizes and resolutions, each convention's copy of a sweep that gl runs by default. Run it
# before resolving work that touched the judge, the renderer's techniques or the cause model, and
# nightly (docs/testing.md says which check each deep test repeats and where the default tier runs it).
#
#   shadowref_deep_tier(<test>...)   adds the label "deep" to each test (after its LABELS are set)
function(shadowref_deep_tier)
  foreach(_test IN LISTS ARGN)
    set_property(TEST ${_test} APPEND PROPERTY LABELS deep)
  endforeach()
endfunction()
