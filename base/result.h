// Result<T>: a value or an error message, for expected failures (bad input, unreadable files).
// Messages carry their own location ("scene.obj:12: ..."), so callers print them as they are.
//
// A function passes a callee's failure up unchanged with RADFARM_RETURN_IF_ERROR:
//
//   Result<Scene> Load(const std::string& path) {
//     Result<std::string> text = ReadTextFile(path);
//     RADFARM_RETURN_IF_ERROR(text);           // returns Error{text.error()} on failure
//     RADFARM_RETURN_IF_ERROR(Check(*text));   // any expression giving a Status or Result<U>
//     ...
//   }
//
// It is the one early-return helper: an error that gains words on the way up ("job 3: " + ...) is
// written out as `if (!x) return Error{"job 3: " + x.error(), x.error_kind()};`.
//
// An error's kind says what failed, for the few callers that decide by it rather than print it
// (the master holds a job on a store fault that may pass and fails it on any other error). It is
// set where the error is made (store/sqlite_error.cc classifies SQLite's result codes) and kept on
// the way up by RADFARM_RETURN_IF_ERROR.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <variant>

namespace radfarm {

enum class ErrorKind : uint8_t {
  kOther,       // nothing to decide by: a message for a person
  kDiskFull,    // storage full or at its size limit
  kIo,          // an I/O error reading or writing storage
  kBusy,        // storage locked by another user past the wait
  kCorrupt,     // stored data damaged, or not the format expected
  kConstraint,  // a write broke a rule of the stored data (a key, a reference, a check)
};

struct Error {
  std::string message;
  ErrorKind kind = ErrorKind::kOther;
};

template <typename T>
class [[nodiscard]] Result {
 public:
  Result(T value) : state_(std::move(value)) {}      // NOLINT: implicit on purpose
  Result(Error error) : state_(std::move(error)) {}  // NOLINT: implicit on purpose

  bool ok() const { return std::holds_alternative<T>(state_); }
  explicit operator bool() const { return ok(); }
  const T& value() const& { return std::get<T>(state_); }
  T& value() & { return std::get<T>(state_); }
  T&& value() && { return std::get<T>(std::move(state_)); }
  const T* operator->() const { return &value(); }
  T* operator->() { return &value(); }
  const T& operator*() const& { return value(); }
  T& operator*() & { return value(); }
  const std::string& error() const { return std::get<Error>(state_).message; }
  ErrorKind error_kind() const { return std::get<Error>(state_).kind; }

 private:
  std::variant<T, Error> state_;
};

// Result<void> stand-in.
struct Ok {};
using Status = Result<Ok>;

}  // namespace radfarm

// If `expr` (a Status or Result<T>, evaluated once) holds an error, returns Error{its message, its
// kind} from the enclosing function, whose return type is then any Result<U> or Status.
#define RADFARM_RETURN_IF_ERROR(expr)                                                 \
  do {                                                                                \
    if (const auto& radfarm_status_ = (expr); !radfarm_status_.ok()) {                \
      return ::radfarm::Error{radfarm_status_.error(), radfarm_status_.error_kind()}; \
    }                                                                                 \
  } while (false)
