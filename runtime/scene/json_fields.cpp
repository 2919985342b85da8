#include "scene/json_fields.h"

#include <cmath>

namespace vp {

const char* jsonTypeName(const nlohmann::json& v) {
  // nlohmann's type_name() says "number" for all numeric kinds; that is what users write.
  return v.type_name();
}

Status JsonObject::checkKeys(std::initializer_list<const char*> allowed) const {
  if (!value_.is_object())
    return fail(Status::ParseError, "%s: expected an object, got %s", path_.c_str(), jsonTypeName(value_));
  for (auto it = value_.begin(); it != value_.end(); ++it) {
    bool known = false;
    for (const char* key : allowed) known = known || it.key() == key;
    if (!known) {
      std::string list;
      for (const char* key : allowed) list += std::string(list.empty() ? "" : ", ") + key;
      return fail(Status::ParseError, "%s.%s: unknown key (expected one of: %s)", path_.c_str(), it.key().c_str(),
                  list.c_str());
    }
  }
  return Status::Ok;
}

Status JsonObject::number(const char* key, double* out) const {
  if (!has(key)) return Status::Ok;
  const auto& v = value_.at(key);
  if (!v.is_number())
    return fail(Status::ParseError, "%s: expected a number, got %s", pathOf(key).c_str(), jsonTypeName(v));
  *out = v.get<double>();
  return Status::Ok;
}

Status JsonObject::integer(const char* key, int* out) const {
  if (!has(key)) return Status::Ok;
  const auto& v = value_.at(key);
  if (!v.is_number_integer())
    return fail(Status::ParseError, "%s: expected an integer, got %s", pathOf(key).c_str(), v.dump().c_str());
  auto x = v.get<int64_t>();
  if (x < -(int64_t(1) << 31) || x >= (int64_t(1) << 31))
    return fail(Status::ParseError, "%s = %lld: out of the integer range", pathOf(key).c_str(), (long long)x);
  *out = static_cast<int>(x);
  return Status::Ok;
}

Status JsonObject::boolean(const char* key, bool* out) const {
  if (!has(key)) return Status::Ok;
  const auto& v = value_.at(key);
  if (!v.is_boolean())
    return fail(Status::ParseError, "%s: expected true or false, got %s", pathOf(key).c_str(), jsonTypeName(v));
  *out = v.get<bool>();
  return Status::Ok;
}

Status JsonObject::string(const char* key, std::string* out) const {
  if (!has(key)) return Status::Ok;
  const auto& v = value_.at(key);
  if (!v.is_string())
    return fail(Status::ParseError, "%s: expected a string, got %s", pathOf(key).c_str(), jsonTypeName(v));
  *out = v.get<std::string>();
  return Status::Ok;
}

Status JsonObject::vec3(const char* key, Vec3* out) const {
  if (!has(key)) return Status::Ok;
  const auto& v = value_.at(key);
  if (!v.is_array() || v.size() != 3 || !v[0].is_number() || !v[1].is_number() || !v[2].is_number())
    return fail(Status::ParseError, "%s: expected an array of 3 numbers, got %s", pathOf(key).c_str(),
                v.dump().substr(0, 80).c_str());
  *out = Vec3(v[0].get<double>(), v[1].get<double>(), v[2].get<double>());
  return Status::Ok;
}

Status JsonObject::object(const char* key, std::optional<JsonObject>* out, bool required) const {
  if (!has(key)) {
    if (required) return fail(Status::ParseError, "%s: missing required key", pathOf(key).c_str());
    return Status::Ok;
  }
  const auto& v = value_.at(key);
  if (!v.is_object())
    return fail(Status::ParseError, "%s: expected an object, got %s", pathOf(key).c_str(), jsonTypeName(v));
  out->emplace(v, pathOf(key));
  return Status::Ok;
}

Status parseEnum(const JsonObject& obj, const char* key, std::initializer_list<const char*> names, int* out) {
  std::string value;
  VP_TRY(obj.string(key, &value));
  if (!obj.has(key)) return Status::Ok;
  int i = 0;
  for (const char* name : names) {
    if (value == name) {
      *out = i;
      return Status::Ok;
    }
    ++i;
  }
  std::string list;
  for (const char* name : names) list += std::string(list.empty() ? "" : ", ") + name;
  return fail(Status::ParseError, "%s = \"%s\": expected one of: %s", obj.pathOf(key).c_str(), value.c_str(),
              list.c_str());
}


namespace {

Status bits32(const JsonObject& obj, const char* key, uint32_t* out) {
  if (!obj.has(key)) return Status::Ok;
  const nlohmann::json& v = obj.at(key);
  if (!v.is_number_integer() || v.get<int64_t>() < 0 || v.get<int64_t>() > int64_t(0xFFFFFFFF))
    return fail(Status::ParseError, "%s = %s: expected an integer in [0, 4294967295] (32 bits)", obj.pathOf(key).c_str(),
                v.dump().substr(0, 40).c_str());
  *out = static_cast<uint32_t>(v.get<int64_t>());
  return Status::Ok;
}

}  // namespace

Status parseCollisionFilter(const JsonObject& obj, CollisionFilter* out) {
  std::optional<JsonObject> filter;
  VP_TRY(obj.object("collisionFilter", &filter, false));
  if (!filter) return Status::Ok;
  VP_TRY(filter->checkKeys({"category", "mask"}));
  VP_TRY(bits32(*filter, "category", &out->category));
  return bits32(*filter, "mask", &out->mask);
}

}  // namespace vp
