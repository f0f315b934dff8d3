# libFuzzer targets (docs/FUZZING.md), built only with -DRADFARM_FUZZ=ON and clang:
#
#   radfarm_add_fuzzer(<name> SOURCES <file>... LIBRARIES <target>... CORPUS <dir>...
#                      SMOKE_TEST <test name> [SMOKE_SECONDS <n>])
#
# adds the fuzzer executable <name> (part of the target `fuzzers`) and the ctest <test name>: a
# short run over a copy of the files of the CORPUS directories (the seeds, and the findings kept as
# regressions; copied so new inputs do not land in the source tree), with leak detection on,
# labelled `fuzz` (ctest -L fuzz runs them all).
# With RADFARM_FUZZ every target of the build is compiled with coverage feedback
# (fuzzer-no-link), ASan and UBSan, so the libraries under test report what the fuzzer reaches.
option(RADFARM_FUZZ "Build the libFuzzer targets and their smoke tests (needs clang)" OFF)

if(RADFARM_FUZZ)
  if(NOT CMAKE_CXX_COMPILER_ID MATCHES "Clang")
    message(FATAL_ERROR "RADFARM_FUZZ needs clang (libFuzzer): -DCMAKE_CXX_COMPILER=clang++")
  endif()
  add_compile_options(-fsanitize=fuzzer-no-link,address,undefined -fno-omit-frame-pointer
                      -fno-sanitize-recover=undefined)
  add_link_options(-fsanitize=address,undefined)
  # The smoke tests are ctests even when the GoogleTest suite is not built.
  enable_testing()
  # `cmake --build DIR --target fuzzers` builds every fuzzer of the configured components.
  add_custom_target(fuzzers)
endif()

function(radfarm_add_fuzzer name)
  cmake_parse_arguments(PARSE_ARGV 1 arg "" "SMOKE_TEST;SMOKE_SECONDS" "SOURCES;LIBRARIES;CORPUS")
  if(NOT arg_SOURCES OR NOT arg_CORPUS OR NOT arg_SMOKE_TEST)
    message(FATAL_ERROR "radfarm_add_fuzzer(${name}): SOURCES, CORPUS and SMOKE_TEST are required")
  endif()
  if(NOT arg_SMOKE_SECONDS)
    set(arg_SMOKE_SECONDS 10)
  endif()
  add_executable(${name} ${arg_SOURCES})
  add_dependencies(fuzzers ${name})
  target_link_options(${name} PRIVATE -fsanitize=fuzzer)
  target_link_libraries(${name} PRIVATE ${arg_LIBRARIES})
  set(work ${CMAKE_CURRENT_BINARY_DIR}/${name}_work)
  add_test(NAME ${arg_SMOKE_TEST}
           COMMAND ${CMAKE_COMMAND} -E env ASAN_OPTIONS=detect_leaks=1
                   sh -c "w=\"$1\" f=\"$2\" s=\"$3\"; shift 3; rm -rf \"$w\" && mkdir -p \"$w\" && for d in \"$@\"; do cp \"$d\"/* \"$w\"/; done && \"$f\" -max_total_time=$s -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 \"$w\""
                   fuzz_smoke ${work} $<TARGET_FILE:${name}> ${arg_SMOKE_SECONDS} ${arg_CORPUS})
  math(EXPR timeout "${arg_SMOKE_SECONDS} * 6 + 60")
  set_tests_properties(${arg_SMOKE_TEST} PROPERTIES TIMEOUT ${timeout} LABELS fuzz)
endfunction()
