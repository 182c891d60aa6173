# SHADOWREF_TECHNIQUES: the technique names, read from their one definition,
# outputs/include/shadowref/outputs/techniques.hpp (one {"name", TechniqueFamily::...} entry per
# line), so that the CTest cases always cover exactly the contract's list.
set(_techniques_header ${PROJECT_SOURCE_DIR}/outputs/include/shadowref/outputs/techniques.hpp)
set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS ${_techniques_header})
file(STRINGS ${_techniques_header} _technique_lines REGEX "^ *\\{\"[a-z0-9-]+\", TechniqueFamily::")
set(SHADOWREF_TECHNIQUES "")
foreach(_line IN LISTS _technique_lines)
  string(REGEX REPLACE "^ *\\{\"([a-z0-9-]+)\".*" "\\1" _name "${_line}")
  list(APPEND SHADOWREF_TECHNIQUES ${_name})
endforeach()
list(LENGTH SHADOWREF_TECHNIQUES _count)
if(_count LESS 1)
  message(FATAL_ERROR "no technique names found in ${_techniques_header}")
endif()
