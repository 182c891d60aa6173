# report.json's JSON Schema (conformance/record/report.schema.json) holds for every report.json the
# tests leave in the build tree: `record.report_schema` (conformance/record/check_reports.py) walks the build
# folder once the tests that write them have ended, and tries its teeth on the first judged report.
# The order is a CTest fixture, `shadowref_reports`, which the check cleans up after: a folder whose
# tests write report.json calls shadowref_writes_reports() at its end, and each of its add_test
# tests then requires the fixture. (Tests a GoogleTest discovery adds are not in the folder's list
# until CTest runs; those that leave a report.json in the build tree would pass
# `PROPERTIES FIXTURES_REQUIRED shadowref_reports` to gtest_discover_tests. A report.json is written
# whole under its final name or not at all, so a test that ends after the check is never seen half
# written: it is only missed.)
#
#   shadowref_writes_reports()   every test this folder's add_test calls made ends before the check
function(shadowref_writes_reports)
  get_property(_tests DIRECTORY PROPERTY TESTS)
  foreach(_test IN LISTS _tests)
    set_property(TEST ${_test} APPEND PROPERTY FIXTURES_REQUIRED shadowref_reports)
  endforeach()
endfunction()
