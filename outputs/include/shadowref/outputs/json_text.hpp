// shadowref/outputs/json_text.hpp — JSON as text, for every file and stream we write.
//
// The JSON we write carries paths and names someone gave us (a candidate folder, a scene file, a
// mesh), and a Linux path is bytes, not necessarily UTF-8. nlohmann::json refuses to serialise
// invalid UTF-8 (type_error 316), which would turn a legal folder name into an internal error after
// the work is done; here each invalid byte becomes U+FFFD instead, so the file is still valid JSON
// and every other character is kept. Cost: that of dump().
#pragma once

#include <nlohmann/json.hpp>
#include <string>

namespace shadowref::outputs {

// `j` as text; `indent` as in dump() (-1: one line).
inline std::string json_text(const nlohmann::json& j, int indent = -1) {
  return j.dump(indent, ' ', false, nlohmann::json::error_handler_t::replace);
}

}  // namespace shadowref::outputs
