# cmake -DCTEST=ctest -DBUILD_DIR=dir -P test-labels.cmake: every test of the
# build in BUILD_DIR carries exactly one of the labels unit and integration
# (userland/CMakeLists.txt). Lists the offenders and fails otherwise.
cmake_minimum_required(VERSION 3.25)

# ctest -N with extra arguments: sets <out>_count and <out>_names.
function(list_tests out)
  execute_process(COMMAND ${CTEST} --test-dir ${BUILD_DIR} -N ${ARGN}
                  OUTPUT_VARIABLE text RESULT_VARIABLE rc)
  string(REGEX MATCH "Total Tests: ([0-9]+)" total "${text}")
  if(NOT rc EQUAL 0 OR NOT total)
    message(FATAL_ERROR "ctest -N ${ARGN} in ${BUILD_DIR} failed (${rc}):\n${text}")
  endif()
  set(${out}_count ${CMAKE_MATCH_1} PARENT_SCOPE)
  string(REGEX MATCHALL "Test +#[0-9]+: [^\n]+" lines "${text}")
  list(TRANSFORM lines REPLACE "Test +#[0-9]+: " "")
  set(${out}_names "${lines}" PARENT_SCOPE)
endfunction()

list_tests(all)
list_tests(unit -L "^unit$")
list_tests(integration -L "^integration$")
list_tests(none -LE "^(unit|integration)$")
# Several -L: a test must match each of them.
list_tests(both -L "^unit$" -L "^integration$")
if(all_count EQUAL 0)
  message(FATAL_ERROR "no test in ${BUILD_DIR}: nothing was checked")
endif()
if(NOT none_count EQUAL 0)
  list(JOIN none_names "\n  " names)
  message(FATAL_ERROR "${none_count} test(s) without the label unit or integration:\n  ${names}")
endif()
if(NOT both_count EQUAL 0)
  list(JOIN both_names "\n  " names)
  message(FATAL_ERROR "${both_count} test(s) labelled both unit and integration:\n  ${names}")
endif()
math(EXPR sum "${unit_count} + ${integration_count}")
if(NOT sum EQUAL all_count)
  message(FATAL_ERROR "${all_count} tests, but ${unit_count} unit + ${integration_count} integration")
endif()
message("${all_count} tests: ${unit_count} unit, ${integration_count} integration")
