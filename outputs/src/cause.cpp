// cause.cpp — the error classes as text (cause.hpp).
#include "shadowref/outputs/cause.hpp"

namespace shadowref::outputs {

std::string rgb_text(const Rgb& c) {
  return "rgb(" + std::to_string(c[0]) + ", " + std::to_string(c[1]) + ", " + std::to_string(c[2]) + ")";
}

std::string error_colours_line() {
  std::string t;
  for (const ErrorClassRow& r : kErrorClasses)
    t += (t.empty() ? "" : ", ") + std::string(r.colour_name) + " = " + std::string(r.legend);
  return t + "; grey: the dimmed reference";
}

}  // namespace shadowref::outputs
