// FieldReader: typed, checked reads of a JSON object's fields. It remembers the first problem, so
// a whole object is read with straight-line code and checked once at the end; messages name the
// field by its path ("jobs[2].round").
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "base/result.h"

namespace radfarm {

class FieldReader {
 public:
  // `where` names `object` in messages ("job", "jobs[2]"). `object` must outlive the reader.
  FieldReader(const nlohmann::json& object, std::string where);

  int64_t Int(const char* key);
  uint64_t Count(const char* key);  // an integer >= 0
  double Number(const char* key);   // any JSON number
  std::string String(const char* key);
  bool Bool(const char* key);
  // A string that must be one of `allowed`.
  std::string OneOf(const char* key, const std::vector<std::string_view>& allowed);
  // These also accept null, returned as nullopt.
  std::optional<int64_t> NullableInt(const char* key);
  std::optional<double> NullableNumber(const char* key);
  std::optional<std::string> NullableString(const char* key);

  // Ok, or the first problem: "missing key 'job.round'", "'job.round' is a string, expected an
  // integer".
  Status status() const;

 private:
  // The field, or null after recording a problem (missing key, or the object is no object).
  const nlohmann::json* Field(const char* key);
  bool Expect(bool ok, const char* key, const nlohmann::json& value, const char* expected);
  std::string Path(const char* key) const;

  const nlohmann::json& object_;
  std::string where_;
  std::optional<std::string> problem_;
};

}  // namespace radfarm
