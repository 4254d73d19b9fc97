# Runs PROGRAM on every file of CASES_DIR and checks the exit code (2) and that the one-line
# error names the file, the line and, where there is one, the key. Used for igaprep (body
# files, tests/bad_input/), ffrsim (scenes, tests/bad_scenes/) and the study workflow (study
# files, tests/bad_studies/).
# Each case file starts with a comment line "# expect: TEXT" giving a text the message must
# contain. A case may be a folder named like a case file (the program is given the folder);
# its expectations are then in the file README inside it. Optional lines "# output: yes" (run with -o OUT: the error comes from the
# pipeline, and no output or temporary file may be left behind) and "# exit: N" (expected
# exit code, default 2); "# also: TEXT" (a second text the message must contain).
# Variables: PROGRAM, CASES_DIR, OUT_DIR; PROGRAM_ARGS (put before every run's arguments,
# '|'-separated: a script and its command); ALWAYS_ARGS (appended to every run, '|'-separated);
# USAGE_ARGS / USAGE_EXPECT (a usage error to check, arguments '|'-separated).
# Also checks a missing input file.
file(GLOB cases "${CASES_DIR}/*.yaml")
string(REPLACE "|" ";" always "${ALWAYS_ARGS}")
string(REPLACE "|" ";" program_args "${PROGRAM_ARGS}")
function(expect_error args expected what)
  if(NOT DEFINED expected_rc)
    set(expected_rc 2)
  endif()
  if(NOT DEFINED also)
    set(also "")
  endif()
  execute_process(COMMAND ${PROGRAM} ${program_args} ${args} ${always}
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  string(STRIP "${err}" err)
  string(FIND "${err}" "${expected}" pos)
  string(FIND "${err}" "${also}" pos_also)
  if(pos_also EQUAL -1)
    set(pos -1)
  endif()
  string(REGEX MATCHALL "\n" newlines "${err}")
  list(LENGTH newlines nlines)
  file(GLOB leftovers "${OUT_DIR}/bad_input_case.sid.h5*")
  if(NOT rc EQUAL expected_rc OR pos EQUAL -1 OR nlines GREATER 0 OR leftovers)
    message(SEND_ERROR "${what}: exit code ${rc}, message '${err}', files left: '${leftovers}', expected exit ${expected_rc}, one line containing '${expected}' and no output file")
  else()
    message(STATUS "ok ${what}: ${err}")
  endif()
endfunction()
foreach(case IN LISTS cases)
  if(IS_DIRECTORY "${case}")
    file(STRINGS "${case}/README" head LIMIT_COUNT 4)
  else()
    file(STRINGS "${case}" head LIMIT_COUNT 4)
  endif()
  list(GET head 0 first)
  string(REGEX REPLACE "^# expect: " "" expected "${first}")
  set(args "${case}")
  set(expected_rc 2)
  set(also "")
  foreach(line IN LISTS head)
    if(line MATCHES "^# output: yes")
      list(APPEND args -q -o "${OUT_DIR}/bad_input_case.sid.h5")
    elseif(line MATCHES "^# exit: ([0-9]+)")
      set(expected_rc ${CMAKE_MATCH_1})
    elseif(line MATCHES "^# also: (.*)")
      set(also "${CMAKE_MATCH_1}")
    endif()
  endforeach()
  expect_error("${args}" "${expected}" "${case}")
endforeach()
set(expected_rc 2)
set(also "")
expect_error("${CASES_DIR}/does_not_exist.yaml" "does_not_exist.yaml: cannot open file" "missing file")
if(USAGE_ARGS)
  string(REPLACE "|" ";" usage "${USAGE_ARGS}")
  expect_error("${usage}" "${USAGE_EXPECT}" "usage error")
endif()
