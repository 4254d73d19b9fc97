# Writes ${OUT}: the git revision of the source tree ${SRC} (with "-dirty" when tracked
# files differ from it; "unknown" outside a git checkout). Run at every build; the file is
# rewritten only when the revision changes, so that nothing recompiles needlessly.
execute_process(COMMAND git -C ${SRC} rev-parse HEAD
                OUTPUT_VARIABLE rev RESULT_VARIABLE status OUTPUT_STRIP_TRAILING_WHITESPACE
                ERROR_QUIET)
if(NOT status EQUAL 0 OR rev STREQUAL "")
  set(rev "unknown")
else()
  execute_process(COMMAND git -C ${SRC} diff --quiet HEAD -- RESULT_VARIABLE dirty ERROR_QUIET)
  if(NOT dirty EQUAL 0)
    set(rev "${rev}-dirty")
  endif()
endif()
set(text "// Generated at build time by common/cmake/GitRevision.cmake: do not edit.\n#pragma once\n\nnamespace ffriga {\n\nconstexpr const char* kGitRevision = \"${rev}\";\n\n}  // namespace ffriga\n")
if(EXISTS ${OUT})
  file(READ ${OUT} old)
else()
  set(old "")
endif()
if(NOT old STREQUAL text)
  file(WRITE ${OUT} "${text}")
endif()
