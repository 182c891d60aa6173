// teeth_table.hpp — the suite's teeth as one table: each row is a deliberately wrong variant of a
// real technique (the technique with fault switches on, renderer/faults.hpp: no copy of any pass),
// a bug class engines have shipped, and the catalogue scenes that must catch it.
//
// A row is caught on a scene when, through the very conformance run users get (run_conform:
// cached references, renders, the catalogue's expectations, the thresholds), the variant is a FAIL
// there while its control — the same technique, no fault, same convention — is green there (PASS,
// or XFAIL where the catalogue expects the technique to fail). Every row must be caught on every
// scene it lists; every control must be green on every scene its rows list. Each row and each
// control is one CTest test labelled `teeth` (conformance/tests/CMakeLists.txt, teeth_test.cpp).
#pragma once

#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "shadowref/renderer/faults.hpp"

namespace shadowref::teeth {

struct Row {
  std::string_view name;         // conformance.teeth.<name>
  std::string_view technique;    // the renderer's technique, drawn with `faults` on
  renderer::Faults faults;
  std::string_view convention;   // the run convention (mathlib/convention.hpp)
  std::string_view scenes;       // default-catalogue scenes it must FAIL on, space-separated
  std::string_view field_class;  // the class of bug it stands for
  std::string_view why;          // why those scenes catch it
  // The technique whose expectations and threshold judge it; empty: `technique`. A name outside
  // the catalogue claims to be right everywhere (expected to pass, the strictest threshold).
  std::string_view judged_as = {};
  // Texels per side of every shadow map (`shadowref conform --shadow-map-size`); 0: automatic, like
  // the convention part of what the row (and its control) runs in.
  int shadow_map_size = 0;

  std::string_view judge() const { return judged_as.empty() ? technique : judged_as; }
  std::vector<std::string> scene_list() const;
};

// The no-fault run of one technique in one convention (and map size), on every scene of the rows
// that use it.
struct Control {
  std::string name;              // control.<technique>.<convention>[.map<size>]
  std::string technique, convention;
  int shadow_map_size = 0;
  std::vector<std::string> scenes;
};

std::span<const Row> rows();
std::vector<Control> controls();
// The control a row is measured against.
Control control_of(const Row& row);

}  // namespace shadowref::teeth
