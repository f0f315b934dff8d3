// LOOP_CHECK: invariants of the loop layer (a broken one is a bug, not an expected failure). On
// failure it prints the condition and its location and aborts, in every build type.
#pragma once

#include <cstdio>
#include <cstdlib>

#define LOOP_CHECK(condition)                                                                 \
  do {                                                                                        \
    if (!(condition)) {                                                                       \
      std::fprintf(stderr, "%s:%d: LOOP_CHECK failed: %s\n", __FILE__, __LINE__, #condition); \
      std::abort();                                                                           \
    }                                                                                         \
  } while (false)
