# delcert_add_certificate_test(): a certificate as a regression test (included by the package
# config, so find_package(delcert) defines it).
#
#   delcert_add_certificate_test(NAME <test>
#                                MANIFOLD <builtin:NAME | spec.json>
#                                POINTS <points file>
#                                COMPLEX <complex file>
#                                [CLAIMS <claims.json>]
#                                [KIND tangential|restricted|intrinsic]
#                                [THREADS <n>]
#                                [SKIP_RESTRICTED])
#
# Adds the ctest test <test>, which runs delcert-certify on the inputs and passes only when its exit
# status is 0 and its last line is "verdict: CERTIFIED": REFUTED (exit status 1), UNDECIDED (3) and
# bad input (2) fail the test; a failing test's output lists each REFUTED or UNDECIDED check of the
# certificate with its first witnesses (the simplex or vertex indices and why) or its reason.
# Relative paths are relative to the calling CMakeLists.txt's folder.
# The certificate is written to <build folder of the caller>/<test>.certificate.json, whatever the
# verdict, so that a failing CI run keeps it. KIND, THREADS and SKIP_RESTRICTED are delcert-certify's
# --kind, --threads and --skip-restricted (`delcert-certify --help`); without THREADS it uses every
# core. Set other test properties (TIMEOUT, LABELS, ...) with set_tests_properties(<test> ...).
# Call enable_testing() (or include(CTest)) in the top-level CMakeLists.txt for ctest to see it.
# No language is needed: a project(x LANGUAGES NONE) can add these tests. delcert_EXAMPLES_DIR (set by
# the package config) holds example inputs: octahedron.off, octahedron.complex, octahedron-claims.json.
if(CMAKE_VERSION VERSION_LESS 3.20)
  message(FATAL_ERROR "delcert_add_certificate_test needs CMake 3.20 or later (this is ${CMAKE_VERSION})")
endif()

function(delcert_add_certificate_test)
  cmake_parse_arguments(PARSE_ARGV 0 arg "SKIP_RESTRICTED" "NAME;MANIFOLD;POINTS;COMPLEX;CLAIMS;KIND;THREADS" "")
  if(arg_UNPARSED_ARGUMENTS)
    message(FATAL_ERROR "delcert_add_certificate_test: unknown arguments '${arg_UNPARSED_ARGUMENTS}'; "
                        "the arguments are NAME, MANIFOLD, POINTS, COMPLEX, CLAIMS, KIND, THREADS and SKIP_RESTRICTED")
  endif()
  if(arg_KEYWORDS_MISSING_VALUES)
    message(FATAL_ERROR "delcert_add_certificate_test: ${arg_KEYWORDS_MISSING_VALUES} given without a value")
  endif()
  foreach(required NAME MANIFOLD POINTS COMPLEX)
    if(NOT DEFINED arg_${required} OR arg_${required} STREQUAL "")
      message(FATAL_ERROR "delcert_add_certificate_test: ${required} is required; "
                          "call it as delcert_add_certificate_test(NAME <test> MANIFOLD <builtin:NAME or spec.json> "
                          "POINTS <file> COMPLEX <file> [CLAIMS <file>])")
    endif()
  endforeach()
  if(DEFINED arg_KIND AND NOT arg_KIND MATCHES "^(tangential|restricted|intrinsic)$")
    message(FATAL_ERROR "delcert_add_certificate_test(${arg_NAME}): KIND is '${arg_KIND}'; "
                        "give tangential, restricted or intrinsic (what the complex is claimed to be)")
  endif()
  if(DEFINED arg_THREADS AND NOT arg_THREADS MATCHES "^[0-9]+$")
    message(FATAL_ERROR "delcert_add_certificate_test(${arg_NAME}): THREADS is '${arg_THREADS}'; "
                        "give a number of threads (0: all cores)")
  endif()
  if(NOT TARGET delcert::delcert-certify)
    message(FATAL_ERROR "delcert_add_certificate_test(${arg_NAME}): the target delcert::delcert-certify does not "
                        "exist; call find_package(delcert REQUIRED) first")
  endif()

  # Input paths relative to the caller's source folder; a built-in manifold is not a path.
  foreach(input MANIFOLD POINTS COMPLEX CLAIMS)
    if(DEFINED arg_${input} AND NOT arg_${input} MATCHES "^builtin:")
      cmake_path(ABSOLUTE_PATH arg_${input} BASE_DIRECTORY "${CMAKE_CURRENT_SOURCE_DIR}" NORMALIZE)
    endif()
  endforeach()

  # The runner (delcert-run-certificate-test.cmake, beside this file) checks the exit status and
  # the verdict line; ctest alone could check one or the other but not both.
  set(runner "${CMAKE_CURRENT_FUNCTION_LIST_DIR}/delcert-run-certificate-test.cmake")
  set(command "${CMAKE_COMMAND}"
      "-DDELCERT_TEST_NAME=${arg_NAME}"
      "-DDELCERT_CERTIFY=$<TARGET_FILE:delcert::delcert-certify>"
      "-DDELCERT_MANIFOLD=${arg_MANIFOLD}"
      "-DDELCERT_POINTS=${arg_POINTS}"
      "-DDELCERT_COMPLEX=${arg_COMPLEX}"
      "-DDELCERT_OUT=${CMAKE_CURRENT_BINARY_DIR}/${arg_NAME}.certificate.json")
  foreach(option CLAIMS KIND THREADS)
    if(DEFINED arg_${option})
      list(APPEND command "-DDELCERT_${option}=${arg_${option}}")
    endif()
  endforeach()
  if(arg_SKIP_RESTRICTED)
    list(APPEND command "-DDELCERT_SKIP_RESTRICTED=ON")
  endif()
  add_test(NAME ${arg_NAME} COMMAND ${command} -P "${runner}")
endfunction()
