# SHADOWREF_CONVENTIONS: the run conventions' names, read from their one definition,
# mathlib/include/shadowref/convention.hpp (one {"name", {Handedness::...}, ...} entry per line of
# kRunConventions), so that the CTest cases cover exactly the conventions the code has.
set(_conventions_header ${PROJECT_SOURCE_DIR}/mathlib/include/shadowref/convention.hpp)
set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS ${_conventions_header})
file(STRINGS ${_conventions_header} _convention_lines REGEX "^ *\\{\"[a-z0-9-]+\", \\{Handedness::")
set(SHADOWREF_CONVENTIONS "")
foreach(_line IN LISTS _convention_lines)
  string(REGEX REPLACE "^ *\\{\"([a-z0-9-]+)\".*" "\\1" _name "${_line}")
  list(APPEND SHADOWREF_CONVENTIONS ${_name})
endforeach()
list(LENGTH SHADOWREF_CONVENTIONS _count)
if(_count LESS 1)
  message(FATAL_ERROR "no run conventions found in ${_conventions_header}")
endif()
