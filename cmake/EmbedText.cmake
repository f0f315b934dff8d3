# Writes a C++ source defining `std::string_view radfarm::web::FUNCTION()` that returns the bytes of
# INPUT, so a daemon serves a file it was built with (cmake -P, run at build time by
# radfarm_embed_text below; the output is rewritten whenever INPUT changes).
if(CMAKE_SCRIPT_MODE_FILE)
  file(READ "${INPUT}" hex HEX)
  string(LENGTH "${hex}" hex_length)
  math(EXPR size "${hex_length} / 2")
  string(REGEX REPLACE "([0-9a-f][0-9a-f])" "0x\\1," bytes "${hex}")
  file(WRITE "${OUTPUT}"
    "// Generated from ${INPUT} by cmake/EmbedText.cmake: do not edit.\n"
    "#include <string_view>\n"
    "namespace radfarm::web {\n"
    "namespace { constexpr unsigned char kBytes[] = {${bytes} 0}; }\n"
    "std::string_view ${FUNCTION}() {\n"
    "  return {reinterpret_cast<const char*>(kBytes), ${size}};\n"
    "}\n"
    "}  // namespace radfarm::web\n")
  return()
endif()

# radfarm_embed_text(TARGET INPUT FUNCTION): compiles INPUT's bytes into TARGET as FUNCTION().
function(radfarm_embed_text target input function)
  get_filename_component(name "${input}" NAME)
  set(output "${CMAKE_CURRENT_BINARY_DIR}/embedded_${name}.cc")
  add_custom_command(
    OUTPUT "${output}"
    COMMAND ${CMAKE_COMMAND} -DINPUT=${CMAKE_CURRENT_SOURCE_DIR}/${input} -DOUTPUT=${output}
            -DFUNCTION=${function} -P ${PROJECT_SOURCE_DIR}/cmake/EmbedText.cmake
    DEPENDS "${CMAKE_CURRENT_SOURCE_DIR}/${input}" "${PROJECT_SOURCE_DIR}/cmake/EmbedText.cmake"
    COMMENT "Embedding ${input}")
  target_sources(${target} PRIVATE "${output}")
endfunction()
