# shadowref_read_contract_names(OUT HEADER ENTRY_REGEX): the quoted names of a C++ table that is the
# one definition of a concept (one `{"name", ...}` entry per line), so that CMake registers tests for
# exactly what the code has. Fails configuration when the header yields no name.
function(shadowref_read_contract_names out header entry_regex)
  set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS ${header})
  file(STRINGS ${header} _lines REGEX "${entry_regex}")
  set(_names "")
  foreach(_line IN LISTS _lines)
    string(REGEX REPLACE "^ *\\{\"([a-z0-9-]+)\".*" "\\1" _name "${_line}")
    list(APPEND _names ${_name})
  endforeach()
  if(NOT _names)
    message(FATAL_ERROR "no names found in ${header}")
  endif()
  set(${out} ${_names} PARENT_SCOPE)
endfunction()

# SHADOWREF_TECHNIQUES: outputs/include/shadowref/outputs/techniques.hpp (outputs::kTechniques).
shadowref_read_contract_names(SHADOWREF_TECHNIQUES
  ${PROJECT_SOURCE_DIR}/outputs/include/shadowref/outputs/techniques.hpp "^ *\\{\"[a-z0-9-]+\", TechniqueFamily::")
# SHADOWREF_CONVENTIONS: mathlib/include/shadowref/convention.hpp (kRunConventions).
shadowref_read_contract_names(SHADOWREF_CONVENTIONS
  ${PROJECT_SOURCE_DIR}/mathlib/include/shadowref/convention.hpp "^ *\\{\"[a-z0-9-]+\", \\{Handedness::")
