# Every CTest TIMEOUT in this project is a hang guard, never a performance check (speed is
# measured in bench/): ten times the test's quiet time on this project's 2-core machine, and never
# below ten minutes, so that a machine busy with other work (two renders and a build beside the
# suite: load 5-6, measured) cannot fail a test that passes alone. Each call site names the test's
# quiet time, measured with `ctest --preset release` and read from its per-test times.
#
#   shadowref_hang_guard(<var> <quiet seconds>)   sets <var> to the TIMEOUT for such a test
set(SHADOWREF_HANG_GUARD_FACTOR 10)
set(SHADOWREF_HANG_GUARD_FLOOR 600)
function(shadowref_hang_guard var quiet_seconds)
  math(EXPR t "${quiet_seconds} * ${SHADOWREF_HANG_GUARD_FACTOR}")
  if(t LESS SHADOWREF_HANG_GUARD_FLOOR)
    set(t ${SHADOWREF_HANG_GUARD_FLOOR})
  endif()
  set(${var} ${t} PARENT_SCOPE)
endfunction()

# The heavy tests start first under `ctest -j` (COST: their quiet time in seconds; CTest replaces it
# with its own measured cost once a build tree has run them), so that a fresh checkout's first run
# does not end with one core working through a long test alone.
#
#   shadowref_run_early(<quiet seconds> <test>...)
function(shadowref_run_early quiet_seconds)
  set_tests_properties(${ARGN} PROPERTIES COST ${quiet_seconds})
endfunction()
