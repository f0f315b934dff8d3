#include "cli/json_fields.h"

#include <limits>

namespace radfarm {

using nlohmann::json;

namespace {

bool IsInt64(const json& v) {
  return v.is_number_integer() &&
         (!v.is_number_unsigned() ||
          v.get<uint64_t>() <= uint64_t(std::numeric_limits<int64_t>::max()));
}

}  // namespace

FieldReader::FieldReader(const json& object, std::string where)
    : object_(object), where_(std::move(where)) {
  if (!object_.is_object()) {
    problem_ = "'" + where_ + "' is " + std::string(object_.type_name()) + ", expected an object";
  }
}

Status FieldReader::status() const {
  if (problem_) return Error{*problem_};
  return Ok{};
}

std::string FieldReader::Path(const char* key) const { return where_ + "." + key; }

const json* FieldReader::Field(const char* key) {
  if (problem_) return nullptr;
  const auto it = object_.find(key);
  if (it == object_.end()) {
    problem_ = "missing key '" + Path(key) + "'";
    return nullptr;
  }
  return &*it;
}

bool FieldReader::Expect(bool ok, const char* key, const json& value, const char* expected) {
  if (!ok && !problem_) {
    problem_ =
        "'" + Path(key) + "' is " + std::string(value.type_name()) + ", expected " + expected;
  }
  return ok;
}

int64_t FieldReader::Int(const char* key) {
  const json* v = Field(key);
  if (!v) return 0;
  return Expect(IsInt64(*v), key, *v, "an integer") ? v->get<int64_t>() : 0;
}

uint64_t FieldReader::Count(const char* key) {
  const json* v = Field(key);
  if (!v) return 0;
  const bool ok = v->is_number_unsigned() || (v->is_number_integer() && v->get<int64_t>() >= 0);
  return Expect(ok, key, *v, "an integer >= 0") ? v->get<uint64_t>() : 0;
}

double FieldReader::Number(const char* key) {
  const json* v = Field(key);
  if (!v) return 0;
  return Expect(v->is_number(), key, *v, "a number") ? v->get<double>() : 0;
}

std::string FieldReader::String(const char* key) {
  const json* v = Field(key);
  if (!v) return "";
  return Expect(v->is_string(), key, *v, "a string") ? v->get<std::string>() : "";
}

bool FieldReader::Bool(const char* key) {
  const json* v = Field(key);
  if (!v) return false;
  return Expect(v->is_boolean(), key, *v, "true or false") && v->get<bool>();
}

std::string FieldReader::OneOf(const char* key, const std::vector<std::string_view>& allowed) {
  std::string value = String(key);
  if (problem_) return value;
  for (std::string_view a : allowed) {
    if (value == a) return value;
  }
  std::string list;
  for (std::string_view a : allowed) list += (list.empty() ? "" : ", ") + std::string(a);
  problem_ = "'" + Path(key) + "' is '" + value + "', expected one of " + list;
  return value;
}

std::optional<int64_t> FieldReader::NullableInt(const char* key) {
  const json* v = Field(key);
  if (!v || v->is_null()) return std::nullopt;
  return Expect(IsInt64(*v), key, *v, "an integer or null") ? std::optional(v->get<int64_t>())
                                                            : std::nullopt;
}

std::optional<double> FieldReader::NullableNumber(const char* key) {
  const json* v = Field(key);
  if (!v || v->is_null()) return std::nullopt;
  return Expect(v->is_number(), key, *v, "a number or null") ? std::optional(v->get<double>())
                                                             : std::nullopt;
}

std::optional<std::string> FieldReader::NullableString(const char* key) {
  const json* v = Field(key);
  if (!v || v->is_null()) return std::nullopt;
  return Expect(v->is_string(), key, *v, "a string or null") ? std::optional(v->get<std::string>())
                                                             : std::nullopt;
}

}  // namespace radfarm
