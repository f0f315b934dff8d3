// Internal to the store's .cc files: early return of the error of a Status or Result<T>, as an
// Error (which converts to any Result<U>).
#pragma once

#define STORE_RETURN_IF_ERROR(expr)                                \
  do {                                                             \
    if (const auto& store_status_ = (expr); !store_status_.ok()) { \
      return ::radfarm::Error{store_status_.error()};              \
    }                                                              \
  } while (false)
