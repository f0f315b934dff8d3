# radfarm_flatc_headers(<target> SCHEMAS <stem>... HEADERS <var> DIR <var> [COMMENT <text>])
#
# Runs flatc on schema/<stem>.fbs for each stem, writing <stem>_generated.h under the calling
# directory's build tree (generated code is never committed), and adds the custom target <target>
# that a library depends on to have them before it compiles. Sets <var> of HEADERS to the generated
# headers and <var> of DIR to their directory in the caller's scope.
find_package(FlatBuffers REQUIRED)

function(radfarm_flatc_headers target)
  cmake_parse_arguments(PARSE_ARGV 1 arg "" "HEADERS;DIR;COMMENT" "SCHEMAS")
  if(NOT arg_SCHEMAS OR NOT arg_HEADERS OR NOT arg_DIR)
    message(FATAL_ERROR "radfarm_flatc_headers(${target}): SCHEMAS, HEADERS and DIR are required")
  endif()
  set(schema_dir ${PROJECT_SOURCE_DIR}/schema)
  set(generated_dir ${CMAKE_CURRENT_BINARY_DIR}/generated)
  set(schema_files "")
  set(generated_headers "")
  foreach(schema IN LISTS arg_SCHEMAS)
    list(APPEND schema_files ${schema_dir}/${schema}.fbs)
    list(APPEND generated_headers ${generated_dir}/${schema}_generated.h)
  endforeach()
  if(NOT arg_COMMENT)
    set(arg_COMMENT "flatc: generating C++ headers for ${arg_SCHEMAS}")
  endif()
  add_custom_command(
    OUTPUT ${generated_headers}
    COMMAND flatbuffers::flatc --cpp --scoped-enums -I ${schema_dir} -o ${generated_dir}
            ${schema_files}
    DEPENDS ${schema_files}
    COMMENT "${arg_COMMENT}"
    VERBATIM)
  add_custom_target(${target} DEPENDS ${generated_headers})
  set(${arg_HEADERS} ${generated_headers} PARENT_SCOPE)
  set(${arg_DIR} ${generated_dir} PARENT_SCOPE)
endfunction()
