# Runs ffrsim on every scene of tests/bad_scenes/ and checks the exit code (2) and that the
# one-line error names the file, the line and the key. Each case file starts with a comment
# line "# expect: TEXT" giving a text the message must contain. Also checks usage errors.
file(GLOB cases "${CASES_DIR}/*.yaml")
function(expect_error args expected what)
  execute_process(COMMAND ${FFRSIM} ${args} -o ${OUT_DIR}/bad_scene_result.h5
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  string(STRIP "${err}" err)
  string(FIND "${err}" "${expected}" pos)
  string(REGEX MATCHALL "\n" newlines "${err}")
  list(LENGTH newlines nlines)
  if(NOT rc EQUAL 2 OR pos EQUAL -1 OR nlines GREATER 0)
    message(SEND_ERROR "${what}: exit code ${rc}, message '${err}', expected exit 2 and one line containing '${expected}'")
  else()
    message(STATUS "ok ${what}: ${err}")
  endif()
endfunction()
foreach(case IN LISTS cases)
  file(STRINGS "${case}" first LIMIT_COUNT 1)
  string(REGEX REPLACE "^# expect: " "" expected "${first}")
  expect_error("${case}" "${expected}" "${case}")
endforeach()
expect_error("${CASES_DIR}/does_not_exist.yaml" "does_not_exist.yaml: cannot open file" "missing scene")
expect_error("${CASES_DIR}/a.yaml;${CASES_DIR}/b.yaml" "expected one scene file" "usage")
