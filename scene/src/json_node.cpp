// json_node.cpp — the path-tracking JSON accessors of json_node.hpp.
#include "json_node.hpp"

#include <cmath>

namespace shadowref::scene::detail {

namespace {
std::string type_name(const nlohmann::json& j) { return j.type_name(); }
}  // namespace

void JsonNode::fail(const std::string& what) const {
  throw SceneError(file_.string() + ": " + (path_.empty() ? std::string("(top level)") : path_) + ": " + what);
}

void JsonNode::fail_at(const std::string& key, const std::string& what) const {
  JsonNode(value_, path_.empty() ? key : path_ + "." + key, file_).fail(what);
}

void JsonNode::expect_object(std::initializer_list<const char*> allowed) const {
  if (!value_.is_object()) fail("must be an object, not " + type_name(value_));
  for (const auto& item : value_.items()) {
    bool known = false;
    for (const char* k : allowed) known = known || item.key() == k;
    if (!known) {
      std::string list;
      for (const char* k : allowed) list += (list.empty() ? "" : ", ") + std::string(k);
      fail_at(item.key(), "unknown key (allowed here: " + list + ")");
    }
  }
}

JsonNode JsonNode::child(const char* key) const {
  return JsonNode(value_.at(key), path_.empty() ? std::string(key) : path_ + "." + key, file_);
}

JsonNode JsonNode::required(const char* key) const {
  if (!value_.is_object()) fail("must be an object, not " + type_name(value_));
  if (!value_.contains(key)) fail_at(key, "is required");
  return child(key);
}

std::optional<JsonNode> JsonNode::optional(const char* key) const {
  if (!has(key)) return std::nullopt;
  return child(key);
}

std::size_t JsonNode::array_size() const {
  if (!value_.is_array()) fail("must be an array, not " + type_name(value_));
  return value_.size();
}

JsonNode JsonNode::element(std::size_t i) const {
  return JsonNode(value_.at(i), path_ + "[" + std::to_string(i) + "]", file_);
}

double JsonNode::number() const {
  if (!value_.is_number()) fail("must be a number, not " + type_name(value_));
  const double v = value_.get<double>();
  if (!std::isfinite(v)) fail("must be finite");
  return v;
}

long long JsonNode::integer() const {
  if (value_.is_number_integer()) return value_.get<long long>();
  if (value_.is_number_unsigned()) fail("is out of range");
  if (value_.is_number_float()) fail("must be a whole number");
  fail("must be an integer, not " + type_name(value_));
}

bool JsonNode::boolean() const {
  if (!value_.is_boolean()) fail("must be true or false, not " + type_name(value_));
  return value_.get<bool>();
}

std::string JsonNode::string() const {
  if (!value_.is_string()) fail("must be a string, not " + type_name(value_));
  return value_.get<std::string>();
}

Vec3<double> JsonNode::vec3() const {
  if (array_size() != 3) fail("must be an array of 3 numbers");
  return Vec3<double>(element(0).number(), element(1).number(), element(2).number());
}

Vec2<double> JsonNode::vec2() const {
  if (array_size() != 2) fail("must be an array of 2 numbers");
  return Vec2<double>(element(0).number(), element(1).number());
}

double JsonNode::positive(const char* key) const {
  const JsonNode n = required(key);
  const double v = n.number();
  if (!(v > 0)) n.fail("must be > 0");
  return v;
}

long long JsonNode::integer_in(const char* key, long long lo, long long hi, long long fallback) const {
  const auto n = optional(key);
  if (!n) return fallback;
  const long long v = n->integer();
  if (v < lo || v > hi) n->fail("must be in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
  return v;
}

}  // namespace shadowref::scene::detail
