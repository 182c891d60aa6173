// json_node.hpp (private) — a JSON value together with its path in the document, so that every
// check can say where it failed ("objects[2].shape.radius: must be > 0"). Each accessor either
// returns a valid value or throws SceneError with "<file>: <path>: <what>".
#pragma once

#include <nlohmann/json.hpp>

#include <filesystem>
#include <initializer_list>
#include <optional>
#include <string>

#include "shadowref/conventions.hpp"
#include "shadowref/scene/load_scene.hpp"

namespace shadowref::scene::detail {

class JsonNode {
 public:
  JsonNode(const nlohmann::json& value, std::string path, const std::filesystem::path& file)
      : value_(value), path_(std::move(path)), file_(file) {}

  const nlohmann::json& value() const { return value_; }
  const std::string& path() const { return path_; }

  [[noreturn]] void fail(const std::string& what) const;
  // The same, for a key of this object that is absent (its path is path.key).
  [[noreturn]] void fail_at(const std::string& key, const std::string& what) const;

  // This value must be an object whose keys are all in `allowed`.
  void expect_object(std::initializer_list<const char*> allowed) const;
  bool has(const char* key) const { return value_.is_object() && value_.contains(key); }
  JsonNode child(const char* key) const;  // precondition: has(key)
  JsonNode required(const char* key) const;
  std::optional<JsonNode> optional(const char* key) const;
  std::size_t array_size() const;  // the value must be an array
  JsonNode element(std::size_t i) const;

  double number() const;           // finite
  long long integer() const;       // a whole number
  bool boolean() const;
  std::string string() const;
  Vec3<double> vec3() const;       // [x, y, z], finite
  Vec2<double> vec2() const;

  // Convenience: required / optional members with a range check.
  double positive(const char* key) const;  // required, > 0
  long long integer_in(const char* key, long long lo, long long hi, long long fallback) const;

 private:
  const nlohmann::json& value_;
  std::string path_;
  const std::filesystem::path& file_;
};

}  // namespace shadowref::scene::detail
