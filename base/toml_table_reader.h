// Typed, range-checked reads of one TOML table's keys, for the job file and the daemons' config
// files. The reader remembers which keys it read, so that every key it was never asked for can be
// reported as unknown. Messages name the file, the line and the dotted key:
// "job.toml:7: 'solver.tolerance' must be in (0, 1), got 2".
#pragma once

#include <toml++/toml.h>

#include <array>
#include <cstdint>
#include <limits>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include "base/result.h"

namespace radfarm {

// A range of allowed real values, each end open or closed (or unbounded).
struct Interval {
  double lo = -std::numeric_limits<double>::infinity();
  double hi = std::numeric_limits<double>::infinity();
  bool lo_open = false;
  bool hi_open = false;

  static Interval Any() { return {}; }
  static Interval Above(double lo) { return {lo, Interval().hi, true, false}; }
  static Interval AtLeast(double lo) { return {lo, Interval().hi, false, false}; }
  static Interval Closed(double lo, double hi) { return {lo, hi, false, false}; }
  static Interval Open(double lo, double hi) { return {lo, hi, true, true}; }
  static Interval OpenClosed(double lo, double hi) { return {lo, hi, true, false}; }
  static Interval ClosedOpen(double lo, double hi) { return {lo, hi, false, true}; }

  bool Contains(double x) const;
  std::string Describe() const;  // "in (0, 1)", "in (0, 90]", "> 0", ">= 0"
};

class TomlTableReader {
 public:
  // `prefix` is the dotted path of `table` ("" for the root, "solver." for [solver]). `file` and
  // `table` are borrowed and must outlive the reader.
  TomlTableReader(const std::string& file, const toml::table& table, std::string prefix)
      : file_(file), table_(table), prefix_(std::move(prefix)) {}

  // Each read leaves *out alone when the key is absent, and sets *present (when given) to whether
  // it was there. Integers are accepted where reals are expected, not the other way round.
  Status Real(std::string_view key, Interval range, double* out, bool* present = nullptr);
  Status Integer(std::string_view key, int64_t lo, int64_t hi, int64_t* out,
                 bool* present = nullptr);
  template <typename T>
  Status Integer(std::string_view key, int64_t lo, int64_t hi, T* out, bool* present = nullptr) {
    int64_t value = 0;
    bool found = false;
    Status s = Integer(key, lo, hi, &value, &found);
    if (s && found) *out = static_cast<T>(value);
    if (present != nullptr) *present = s && found;
    return s;
  }
  Status String(std::string_view key, std::string* out, bool* present = nullptr);
  Status Bool(std::string_view key, bool* out);
  Status Triple(std::string_view key, std::array<double, 3>* out, bool* present = nullptr);
  // A Triple into any type made from three doubles (e.g. Vec3).
  template <typename V>
  Status Vector(std::string_view key, V* out, bool* present = nullptr) {
    std::array<double, 3> xyz{};
    bool found = false;
    Status s = Triple(key, &xyz, &found);
    if (present != nullptr) *present = found;
    if (s && found) *out = V(xyz[0], xyz[1], xyz[2]);
    return s;
  }
  // An array of strings (each element a string; it may be empty).
  Status Strings(std::string_view key, std::vector<std::string>* out, bool* present = nullptr);
  // The sub-table at `key`, or null when absent.
  Result<const toml::table*> Table(std::string_view key);
  // The tables of an array of tables (`[[key]]`), in order; empty when absent.
  Result<std::vector<const toml::table*>> Tables(std::string_view key);

  // An error for the first (by line) key that no read asked for.
  Status CheckNoUnknownKeys() const;

  // "file:line: 'prefix.key' what", for checks that involve several keys.
  Error ErrorFor(std::string_view key, std::string_view what) const;
  std::string DottedKey(std::string_view key) const { return prefix_ + std::string(key); }

 private:
  // The node at `key`, marking the key as read; null when absent.
  const toml::node* Find(std::string_view key);

  const std::string& file_;
  const toml::table& table_;
  std::string prefix_;
  std::set<std::string, std::less<>> read_;
};

// "a string", "an integer", "a real number", ...: what a node is, for "must be X, not Y".
std::string TomlTypeName(const toml::node& node);

}  // namespace radfarm
