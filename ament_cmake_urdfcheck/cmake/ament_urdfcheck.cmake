#
# Add a test that checks the package's robot descriptions with urdfcheck (ament_urdfcheck).
#
# :param TESTNAME: the name of the test, default: "urdfcheck"
# :type TESTNAME: string
# :param FAIL_ON: the lowest severity that fails the test: error, warning or info (default: the
#   package's urdfcheck.yaml, else warning)
# :type FAIL_ON: string
# :param CONFIG: a urdfcheck config file (default: urdfcheck.yaml found upward from the package)
# :type CONFIG: string
# :param TIMEOUT: seconds (default 120)
# :type TIMEOUT: integer
# :param EXCLUDE: file or folder names to leave out
# :type EXCLUDE: list
# :param ARGN: the files or folders to check (default: the package)
# :type ARGN: list of strings
#
# @public
#
function(ament_urdfcheck)
  cmake_parse_arguments(ARG "" "TESTNAME;FAIL_ON;CONFIG;TIMEOUT" "EXCLUDE" ${ARGN})
  if(NOT ARG_TESTNAME)
    set(ARG_TESTNAME "urdfcheck")
  endif()
  if(NOT ARG_TIMEOUT)
    set(ARG_TIMEOUT 120)
  endif()

  find_program(ament_urdfcheck_BIN NAMES "ament_urdfcheck")
  if(NOT ament_urdfcheck_BIN)
    message(FATAL_ERROR "ament_urdfcheck() could not find program 'ament_urdfcheck' "
      "(pip install urdfcheck)")
  endif()

  set(result_file "${AMENT_TEST_RESULTS_DIR}/${PROJECT_NAME}/${ARG_TESTNAME}.xunit.xml")
  set(cmd "${ament_urdfcheck_BIN}" "--xunit-file" "${result_file}")
  if(ARG_FAIL_ON)
    list(APPEND cmd "--fail-on" "${ARG_FAIL_ON}")
  endif()
  if(ARG_CONFIG)
    list(APPEND cmd "--config" "${ARG_CONFIG}")
  endif()
  # the package itself: $(find ${PROJECT_NAME}) and package://${PROJECT_NAME} resolve to the sources
  list(APPEND cmd "--package" "${PROJECT_NAME}=${CMAKE_CURRENT_SOURCE_DIR}")
  if(ARG_EXCLUDE)
    list(APPEND cmd "--exclude" ${ARG_EXCLUDE})
  endif()
  if(ARG_UNPARSED_ARGUMENTS)
    list(APPEND cmd "--" ${ARG_UNPARSED_ARGUMENTS})
  endif()

  file(MAKE_DIRECTORY "${CMAKE_BINARY_DIR}/ament_urdfcheck")
  ament_add_test(
    "${ARG_TESTNAME}"
    COMMAND ${cmd}
    OUTPUT_FILE "${CMAKE_BINARY_DIR}/ament_urdfcheck/${ARG_TESTNAME}.txt"
    RESULT_FILE "${result_file}"
    WORKING_DIRECTORY "${CMAKE_CURRENT_SOURCE_DIR}"
    TIMEOUT ${ARG_TIMEOUT}
  )
  set_tests_properties(
    "${ARG_TESTNAME}"
    PROPERTIES
    LABELS "urdfcheck;linter"
  )
endfunction()
