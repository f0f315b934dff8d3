# Writes a program's manual page from its --help with help2man, gzipped as Debian wants it
# (gzip -9n: best compression, no name or timestamp in the header).
#
#   cmake -DHELP2MAN=help2man -DPROGRAM=/path/to/radfarm -DDESCRIPTION="..." \
#         -DINCLUDE=radfarm.h2m -DWORK_DIR=dir -DOUT=dir/radfarm.1.gz -P help_to_man.cmake
#
# The program runs by its bare name from PATH, so the page says "radfarm", not the build path.
# A program with subcommands (CLI11's "Subcommands:" list) gets a SUBCOMMANDS section holding
# each one's --help, so `man radfarm` documents `radfarm render` and the rest.
cmake_minimum_required(VERSION 3.20)
foreach(var HELP2MAN PROGRAM DESCRIPTION INCLUDE WORK_DIR OUT)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "help_to_man.cmake: -D${var}=... is required")
  endif()
endforeach()

get_filename_component(name "${PROGRAM}" NAME)
get_filename_component(dir "${PROGRAM}" DIRECTORY)
set(ENV{PATH} "${dir}:$ENV{PATH}")
file(MAKE_DIRECTORY "${WORK_DIR}")

# roff text: backslashes escaped, a leading . or ' made literal.
function(roff_lines text out_var)
  string(REPLACE "\\" "\\e" text "${text}")
  string(REGEX REPLACE "(^|\n)([.'])" "\\1\\\\&\\2" text "${text}")
  set(${out_var} "${text}" PARENT_SCOPE)
endfunction()

execute_process(COMMAND "${name}" --help OUTPUT_VARIABLE help RESULT_VARIABLE failed)
if(failed)
  message(FATAL_ERROR "${name} --help failed: ${failed}")
endif()
set(subcommands "")
string(FIND "${help}" "\nSubcommands:\n" at)
if(at GREATER -1)
  string(SUBSTRING "${help}" ${at} -1 list)
  string(REGEX MATCHALL "\n  [a-z][a-z0-9-]*" names "${list}")
  foreach(line IN LISTS names)
    string(STRIP "${line}" sub)
    list(APPEND subcommands "${sub}")
  endforeach()
endif()

set(include "${WORK_DIR}/${name}.h2m")
file(READ "${INCLUDE}" text)
if(subcommands)
  string(APPEND text "\n[SUBCOMMANDS]\n")
  foreach(sub IN LISTS subcommands)
    execute_process(COMMAND "${name}" ${sub} --help OUTPUT_VARIABLE sub_help RESULT_VARIABLE failed)
    if(failed)
      message(FATAL_ERROR "${name} ${sub} --help failed: ${failed}")
    endif()
    roff_lines("${sub_help}" sub_help)
    string(APPEND text ".SS ${name} ${sub}\n.nf\n${sub_help}.fi\n")
  endforeach()
endif()
file(WRITE "${include}" "${text}")

set(page "${WORK_DIR}/${name}.1")
execute_process(
  COMMAND "${HELP2MAN}" --no-info --name=${DESCRIPTION} --include=${include} --output=${page}
          "${name}"
  RESULT_VARIABLE failed)
if(failed)
  message(FATAL_ERROR "help2man ${name} failed: ${failed}")
endif()
file(REMOVE "${OUT}")
execute_process(COMMAND gzip -9n "${page}" RESULT_VARIABLE failed)
if(failed OR NOT EXISTS "${page}.gz")
  message(FATAL_ERROR "gzip -9n ${page} failed: ${failed}")
endif()
file(RENAME "${page}.gz" "${OUT}")
