// Strict, path-aware reading of JSON objects for scene files: every key must be known, every
// value of the expected type, and an error names the JSON path ("$.colliders[2].shape.radius").
#pragma once

#include <initializer_list>
#include <optional>
#include <nlohmann/json.hpp>
#include <string>

#include "core/collision_filter.h"
#include "core/math_types.h"
#include "core/status.h"

namespace vp {

class JsonObject {
 public:
  JsonObject(const nlohmann::json& value, std::string path) : value_(value), path_(std::move(path)) {}

  // Fails if the value is not an object or has a key outside `allowed`.
  Status checkKeys(std::initializer_list<const char*> allowed) const;

  bool has(const char* key) const { return value_.contains(key); }
  std::string pathOf(const char* key) const { return path_ + "." + key; }
  const std::string& path() const { return path_; }
  const nlohmann::json& at(const char* key) const { return value_.at(key); }
  const nlohmann::json& value() const { return value_; }

  // Optional fields: leave *out unchanged when the key is absent.
  Status number(const char* key, double* out) const;
  Status integer(const char* key, int* out) const;
  Status boolean(const char* key, bool* out) const;
  Status string(const char* key, std::string* out) const;
  Status vec3(const char* key, Vec3* out) const;
  Status object(const char* key, std::optional<JsonObject>* out, bool required) const;

 private:
  const nlohmann::json& value_;
  std::string path_;
};

const char* jsonTypeName(const nlohmann::json& value);

// The optional "collisionFilter": {"category": bits, "mask": bits}, each an integer in
// [0, 2^32 - 1]; a missing one keeps *out's.
Status parseCollisionFilter(const JsonObject& obj, CollisionFilter* out);

// An optional string field that must be one of `names`; *out = its position in the list.
Status parseEnum(const JsonObject& obj, const char* key, std::initializer_list<const char*> names, int* out);

}  // namespace vp
