# install_consumer_checks (tests/install/CMakeLists.txt): tests/install/consumer/ configured against
# the installed package alone and built (every installed public header compiles on its own, each
# target links on its own), then:
#   * its tests not named must_fail_* pass (a certificate test with every option among them);
#   * each must_fail_* test fails, for the reason it is there (REFUTED, UNDECIDED, bad input),
#     and the certificate is kept when delcert-certify wrote one; a REFUTED one's output lists the
#     failed checks with their witnesses (the simplex indices), an UNDECIDED one's the reason;
#   * the test command fails when the exit status is 0 but the last line is not
#     "verdict: CERTIFIED", and when the last line is but the exit status is not 0 (fake certifiers);
#   * delcert_add_certificate_test() refuses a missing required argument, naming it.
cmake_minimum_required(VERSION 3.20)
include(${CMAKE_CURRENT_LIST_DIR}/common.cmake)

set(build ${WORK_DIR}/consumer)
delcert_configure_and_build(${CMAKE_CURRENT_LIST_DIR}/consumer ${build}
                            -DDELCERT_FIXTURES_DIR=${DELCERT_SOURCE_DIR}/fixtures)
delcert_run(${CTEST} --test-dir ${build} --output-on-failure -E ^must_fail_)
delcert_certificate_verdict(${build}/certified_with_options.certificate.json verdict)
if(NOT verdict STREQUAL "CERTIFIED")
  message(FATAL_ERROR "certified_with_options: the certificate says ${verdict}")
endif()

# Runs a command that must fail, with `reason` in its output (whitespace runs count as one space:
# CMake wraps long error messages).
function(delcert_expect_failure what reason)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE status OUTPUT_VARIABLE output ERROR_VARIABLE output)
  string(REGEX REPLACE "[ \t\n]+" " " flat "${output}")
  string(FIND "${flat}" "${reason}" found)
  if(status STREQUAL "0")
    message(FATAL_ERROR "${what} passed; it must fail with '${reason}'. Its output:\n${output}")
  elseif(found EQUAL -1)
    message(FATAL_ERROR "${what} failed, but not with '${reason}'. Its output:\n${output}")
  endif()
  message("${what} fails as it must: ${reason}")
  set(failure_output "${output}" PARENT_SCOPE)
endfunction()

# name | why it fails | the certificate's verdict (none: no certificate) | lines its output must hold
# (the runner's list of the failed checks: the witness simplex of the triangle left out, of the
# first thin face; the reason of an undecided check; none on bad input).
set(expected
    "must_fail_refuted_complex|REFUTED (exit status 1)|REFUTED|check 3 stars REFUTED: 3 of 6 stars verified|  witness missing_simplex simplex=[0,3,5] at_vertex=0: its ball"
    "must_fail_refuted_claims|REFUTED (exit status 1)|REFUTED|check 5 thickness REFUTED: 8 face(s) thinner|  witness thin_face simplex=[0,2,4] dimension=2"
    "must_fail_undecided|UNDECIDED (exit status 3)|UNDECIDED|check 11 covering UNDECIDED: not computed: the certified restricted Voronoi diagram is built for m <= 3"
    "must_fail_bad_input|bad input or usage (exit status 2)|")
foreach(case ${expected})
  string(REPLACE "|" ";" case "${case}")
  list(GET case 0 name)
  list(GET case 1 reason)
  delcert_expect_failure("test ${name}" "certificate test ${name} is not CERTIFIED: ${reason}"
                         ${CTEST} --test-dir ${build} --output-on-failure -R ^${name}$)
  list(LENGTH case fields)
  set(lines "")
  if(fields GREATER 3)
    list(SUBLIST case 3 -1 lines)
  endif()
  string(FIND "${failure_output}" "the checks that failed, with their witnesses" listed)
  if(lines AND listed EQUAL -1)
    message(FATAL_ERROR "${name}: its output does not list the failed checks:\n${failure_output}")
  elseif(NOT lines AND NOT listed EQUAL -1)
    message(FATAL_ERROR "${name}: failed checks listed without a certificate:\n${failure_output}")
  endif()
  foreach(line ${lines})
    string(FIND "${failure_output}" "\n${line}" found)
    if(found EQUAL -1)
      message(FATAL_ERROR "${name}: its output has no line '${line}':\n${failure_output}")
    endif()
  endforeach()
  set(certificate ${build}/${name}.certificate.json)
  list(GET case 2 certificate_verdict)
  if(certificate_verdict STREQUAL "")
    if(EXISTS ${certificate})
      message(FATAL_ERROR "${name}: a certificate was written on bad input")
    endif()
  else()
    delcert_certificate_verdict(${certificate} verdict)
    if(NOT verdict STREQUAL certificate_verdict)
      message(FATAL_ERROR "${name}: the certificate says ${verdict}, not ${certificate_verdict}")
    endif()
  endif()
endforeach()
# No other test of the consumer was expected to fail: the runs above and -E ^must_fail_ cover all.
execute_process(COMMAND ${CTEST} --test-dir ${build} -N -R ^must_fail_ OUTPUT_VARIABLE listed)
string(REGEX MATCHALL "Test +#[0-9]+: must_fail_" must_fail_tests "${listed}")
list(LENGTH must_fail_tests count)
list(LENGTH expected expected_count)
if(NOT count EQUAL expected_count)
  message(FATAL_ERROR "tests/install/consumer/ has ${count} must_fail_ tests; this script checks ${expected_count}")
endif()

# The test command itself, with fake certifiers: both the exit status and the last line count.
set(runner ${PREFIX}/${LIBDIR}/cmake/delcert/delcert-run-certificate-test.cmake)
set(fake_dir ${WORK_DIR}/fake-certifiers)
file(REMOVE_RECURSE ${fake_dir})
file(MAKE_DIRECTORY ${fake_dir})
function(delcert_fake name script)
  file(WRITE ${fake_dir}/${name}.in "#!/bin/sh\n${script}\n")
  file(COPY_FILE ${fake_dir}/${name}.in ${fake_dir}/${name})
  file(CHMOD ${fake_dir}/${name} PERMISSIONS OWNER_READ OWNER_WRITE OWNER_EXECUTE)
endfunction()
delcert_fake(certified-exit-1 "echo 'verdict: CERTIFIED'; exit 1")
delcert_fake(exit-0-other-last-line "echo 'verdict: CERTIFIED'; echo 'verdict: REFUTED'")
delcert_fake(exit-0-certified "echo 'check 1 ...'; echo 'verdict: CERTIFIED'")
set(inputs -DDELCERT_MANIFOLD=builtin:sphere-2 -DDELCERT_POINTS=p -DDELCERT_COMPLEX=c -DDELCERT_OUT=${fake_dir}/out.json)
delcert_expect_failure("a certifier printing CERTIFIED with exit status 1" "REFUTED (exit status 1)"
                       ${CMAKE_COMMAND} -DDELCERT_TEST_NAME=fake -DDELCERT_CERTIFY=${fake_dir}/certified-exit-1
                       ${inputs} -P ${runner})
delcert_expect_failure("a certifier exiting 0 without CERTIFIED last"
                       "exit status 0 but the last line is 'verdict: REFUTED'"
                       ${CMAKE_COMMAND} -DDELCERT_TEST_NAME=fake -DDELCERT_CERTIFY=${fake_dir}/exit-0-other-last-line
                       ${inputs} -P ${runner})
delcert_run(${CMAKE_COMMAND} -DDELCERT_TEST_NAME=fake -DDELCERT_CERTIFY=${fake_dir}/exit-0-certified
            ${inputs} -P ${runner})

# Arguments: a missing required one is named, a wrong KIND is refused. ARGS separates the
# arguments with commas (a semicolon would split the command line here).
set(call_script ${fake_dir}/call.cmake)
file(WRITE ${call_script} "include(${PREFIX}/${LIBDIR}/cmake/delcert/delcertCertificateTest.cmake)\n"
                          "string(REPLACE \",\" \";\" args \"\${ARGS}\")\n"
                          "delcert_add_certificate_test(\${args})\n")
delcert_expect_failure("a call without POINTS" "POINTS is required"
                       ${CMAKE_COMMAND} -DARGS=NAME,t,MANIFOLD,builtin:sphere-2,COMPLEX,c -P ${call_script})
delcert_expect_failure("a call with KIND wrong" "KIND is 'tangent'; give tangential, restricted or intrinsic"
                       ${CMAKE_COMMAND} -DARGS=NAME,t,MANIFOLD,m,POINTS,p,COMPLEX,c,KIND,tangent -P ${call_script})
message("tests/install/consumer: headers and targets stand alone; certificate tests fail exactly when they must")
