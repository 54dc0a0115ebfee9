# Runs a command and fails unless both its exit code and its output are as
# expected (a ctest PASS_REGULAR_EXPRESSION alone ignores the exit code).
#   cmake -DCOMMAND="prog|arg|..." -DEXIT_CODE=<n> -DREGEX=<regex> -P expect_run.cmake
# COMMAND's words are separated by "|" (a ";" would split the -D argument).
string(REPLACE "|" ";" command "${COMMAND}")
execute_process(COMMAND ${command} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
message("${out}${err}")
if(NOT "${rc}" STREQUAL "${EXIT_CODE}")
  message(FATAL_ERROR "exit code ${rc}, expected ${EXIT_CODE}")
endif()
if(NOT "${out}" MATCHES "${REGEX}")
  message(FATAL_ERROR "the output does not match '${REGEX}'")
endif()
