#include "base/toml_table_reader.h"

#include <cmath>
#include <sstream>
#include <utility>

#include "base/diagnostic.h"

namespace radfarm {
namespace {

std::string FormatNumber(double x) {
  std::ostringstream text;
  text << x;
  return text.str();
}

uint32_t LineOf(const toml::source_region& region) { return region.begin.line; }

// The node as a real number, if it is a number at all.
std::optional<double> AsReal(const toml::node& node) {
  if (const auto* i = node.as_integer()) return static_cast<double>(i->get());
  if (const auto* f = node.as_floating_point()) return f->get();
  return std::nullopt;
}

}  // namespace

std::string TomlTypeName(const toml::node& node) {
  switch (node.type()) {
    case toml::node_type::table:
      return "a table";
    case toml::node_type::array:
      return "an array";
    case toml::node_type::string:
      return "a string";
    case toml::node_type::integer:
      return "an integer";
    case toml::node_type::floating_point:
      return "a real number";
    case toml::node_type::boolean:
      return "a boolean";
    default:
      return "a date or time";
  }
}

bool Interval::Contains(double x) const {
  const bool above = lo_open ? x > lo : x >= lo;
  const bool below = hi_open ? x < hi : x <= hi;
  return above && below;
}

std::string Interval::Describe() const {
  if (std::isinf(hi)) return (lo_open ? "> " : ">= ") + FormatNumber(lo);
  return (lo_open ? "in (" : "in [") + FormatNumber(lo) + ", " + FormatNumber(hi) +
         (hi_open ? ")" : "]");
}

const toml::node* TomlTableReader::Find(std::string_view key) {
  read_.emplace(key);
  return table_.get(key);
}

Error TomlTableReader::ErrorFor(std::string_view key, std::string_view what) const {
  const toml::node* node = table_.get(key);
  const uint32_t line = node != nullptr ? LineOf(node->source()) : LineOf(table_.source());
  return ErrorAt(file_, line, "'" + DottedKey(key) + "' " + std::string(what));
}

Status TomlTableReader::Real(std::string_view key, Interval range, double* out, bool* present) {
  const toml::node* node = Find(key);
  if (present != nullptr) *present = node != nullptr;
  if (node == nullptr) return Ok{};
  std::optional<double> value = AsReal(*node);
  if (!value) return ErrorFor(key, "must be a number, not " + TomlTypeName(*node));
  if (!std::isfinite(*value)) return ErrorFor(key, "must be finite");
  if (!range.Contains(*value)) {
    return ErrorFor(key, "must be " + range.Describe() + ", got " + FormatNumber(*value));
  }
  *out = *value;
  return Ok{};
}

Status TomlTableReader::Integer(std::string_view key, int64_t lo, int64_t hi, int64_t* out,
                                bool* present) {
  const toml::node* node = Find(key);
  if (present != nullptr) *present = node != nullptr;
  if (node == nullptr) return Ok{};
  const auto* value = node->as_integer();
  if (value == nullptr) return ErrorFor(key, "must be an integer, not " + TomlTypeName(*node));
  if (value->get() < lo || value->get() > hi) {
    const std::string range = hi == std::numeric_limits<int64_t>::max()
                                  ? ">= " + std::to_string(lo)
                                  : "in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]";
    return ErrorFor(key, "must be " + range + ", got " + std::to_string(value->get()));
  }
  *out = value->get();
  return Ok{};
}

Status TomlTableReader::String(std::string_view key, std::string* out, bool* present) {
  const toml::node* node = Find(key);
  if (present != nullptr) *present = node != nullptr;
  if (node == nullptr) return Ok{};
  const auto* value = node->as_string();
  if (value == nullptr) return ErrorFor(key, "must be a string, not " + TomlTypeName(*node));
  *out = value->get();
  return Ok{};
}

Status TomlTableReader::Bool(std::string_view key, bool* out) {
  const toml::node* node = Find(key);
  if (node == nullptr) return Ok{};
  const auto* value = node->as_boolean();
  if (value == nullptr) return ErrorFor(key, "must be true or false, not " + TomlTypeName(*node));
  *out = value->get();
  return Ok{};
}

Status TomlTableReader::Triple(std::string_view key, std::array<double, 3>* out, bool* present) {
  const toml::node* node = Find(key);
  if (present != nullptr) *present = node != nullptr;
  if (node == nullptr) return Ok{};
  const toml::array* array = node->as_array();
  std::array<double, 3> xyz{};
  bool ok = array != nullptr && array->size() == 3;
  for (size_t i = 0; ok && i < 3; ++i) {
    std::optional<double> value = AsReal(*array->get(i));
    ok = value && std::isfinite(*value);
    if (ok) xyz[i] = *value;
  }
  if (!ok) return ErrorFor(key, "must be an array of 3 finite numbers, e.g. [0, 1, 0]");
  *out = xyz;
  return Ok{};
}

Result<const toml::table*> TomlTableReader::Table(std::string_view key) {
  const toml::node* node = Find(key);
  if (node == nullptr) return static_cast<const toml::table*>(nullptr);
  if (!node->is_table()) return ErrorFor(key, "must be a table, not " + TomlTypeName(*node));
  return node->as_table();
}

Status TomlTableReader::Strings(std::string_view key, std::vector<std::string>* out,
                                bool* present) {
  const toml::node* node = Find(key);
  if (present != nullptr) *present = node != nullptr;
  if (node == nullptr) return Ok{};
  const toml::array* array = node->as_array();
  std::vector<std::string> strings;
  bool ok = array != nullptr;
  for (size_t i = 0; ok && i < array->size(); ++i) {
    const auto* value = array->get(i)->as_string();
    ok = value != nullptr;
    if (ok) strings.push_back(value->get());
  }
  if (!ok) return ErrorFor(key, "must be an array of strings, e.g. [\"Desk*\"]");
  *out = std::move(strings);
  return Ok{};
}

Result<std::vector<const toml::table*>> TomlTableReader::Tables(std::string_view key) {
  const toml::node* node = Find(key);
  std::vector<const toml::table*> tables;
  if (node == nullptr) return tables;
  const toml::array* array = node->as_array();
  bool ok = array != nullptr;
  for (size_t i = 0; ok && i < array->size(); ++i) {
    ok = array->get(i)->is_table();
    if (ok) tables.push_back(array->get(i)->as_table());
  }
  if (!ok) return ErrorFor(key, "must be an array of tables ([[" + std::string(key) + "]])");
  return tables;
}

Status TomlTableReader::CheckNoUnknownKeys() const {
  const toml::key* unknown = nullptr;
  for (const auto& [key, node] : table_) {
    if (read_.contains(key.str())) continue;
    if (unknown == nullptr || LineOf(key.source()) < LineOf(unknown->source())) unknown = &key;
  }
  if (unknown == nullptr) return Ok{};
  return ErrorAt(file_, LineOf(unknown->source()),
                 "unknown key '" + DottedKey(unknown->str()) + "'");
}

}  // namespace radfarm
