// Outcome<T>: a value, or a failure that carries the exit code it ends the command with. The farm
// commands need more than Result<T> (base/result.h) gives: "the master is unreachable" (3), "no
// such job" (2) and "the master sent garbage" (1) all end a command, with different codes.
#pragma once

#include <string>
#include <utility>
#include <variant>

namespace radfarm {

struct Failure {
  int exit_code;        // cli/exit_codes.h
  std::string message;  // one line, without the "radfarm: " prefix
};

template <typename T>
class [[nodiscard]] Outcome {
 public:
  Outcome(T value) : state_(std::move(value)) {}            // NOLINT: implicit on purpose
  Outcome(Failure failure) : state_(std::move(failure)) {}  // NOLINT: implicit on purpose

  bool ok() const { return std::holds_alternative<T>(state_); }
  const T& value() const& { return std::get<T>(state_); }
  T& value() & { return std::get<T>(state_); }
  const T* operator->() const { return &value(); }
  T* operator->() { return &value(); }
  const T& operator*() const& { return value(); }
  T& operator*() & { return value(); }
  const Failure& failure() const { return std::get<Failure>(state_); }

 private:
  std::variant<T, Failure> state_;
};

}  // namespace radfarm
