# The command of a test added by delcert_add_certificate_test() (delcertCertificateTest.cmake):
#
#   cmake -DDELCERT_TEST_NAME=... -DDELCERT_CERTIFY=<delcert-certify> -DDELCERT_MANIFOLD=...
#         -DDELCERT_POINTS=... -DDELCERT_COMPLEX=... -DDELCERT_OUT=<certificate.json>
#         [-DDELCERT_CLAIMS=...] [-DDELCERT_KIND=...] [-DDELCERT_THREADS=...]
#         [-DDELCERT_SKIP_RESTRICTED=ON] -P delcert-run-certificate-test.cmake
#
# Runs delcert-certify, shows its output, and exits with status 0 only when delcert-certify exited
# with 0 and printed "verdict: CERTIFIED" last; otherwise it fails (status 1) saying why.
cmake_minimum_required(VERSION 3.20)

foreach(required DELCERT_TEST_NAME DELCERT_CERTIFY DELCERT_MANIFOLD DELCERT_POINTS DELCERT_COMPLEX DELCERT_OUT)
  if(NOT DEFINED ${required} OR "${${required}}" STREQUAL "")
    message(FATAL_ERROR "delcert-run-certificate-test.cmake: -D${required}=... is missing; "
                        "this script is run by tests that delcert_add_certificate_test() adds")
  endif()
endforeach()

set(command "${DELCERT_CERTIFY}" --manifold "${DELCERT_MANIFOLD}" --points "${DELCERT_POINTS}"
    --complex "${DELCERT_COMPLEX}" --out "${DELCERT_OUT}")
if(DEFINED DELCERT_CLAIMS)
  list(APPEND command --claims "${DELCERT_CLAIMS}")
endif()
if(DEFINED DELCERT_KIND)
  list(APPEND command --kind "${DELCERT_KIND}")
endif()
if(DEFINED DELCERT_THREADS)
  list(APPEND command --threads "${DELCERT_THREADS}")
endif()
if(DELCERT_SKIP_RESTRICTED)
  list(APPEND command --skip-restricted)
endif()

# A certificate left by an earlier run must not outlive a run that writes none (bad input).
file(REMOVE "${DELCERT_OUT}")
list(JOIN command " " shown)
message("${shown}")
execute_process(COMMAND ${command} RESULT_VARIABLE status OUTPUT_VARIABLE output
                ECHO_OUTPUT_VARIABLE)

string(STRIP "${output}" stripped)
string(FIND "${stripped}" "\n" newline REVERSE)
math(EXPR start "${newline} + 1")  # 0 when there is a single line (or none)
string(SUBSTRING "${stripped}" ${start} -1 last_line)
if(status STREQUAL "0" AND last_line STREQUAL "verdict: CERTIFIED")
  return()
endif()

if(status STREQUAL "1")
  set(why "REFUTED (exit status 1): a check failed; its witnesses are in the lines above and in the certificate")
elseif(status STREQUAL "3")
  set(why "UNDECIDED (exit status 3): a check could not be decided; the lines above say which and why")
elseif(status STREQUAL "2")
  set(why "bad input or usage (exit status 2): fix what delcert-certify says above; no certificate was written")
elseif(status STREQUAL "0")
  set(why "exit status 0 but the last line is '${last_line}', not 'verdict: CERTIFIED'")
else()
  set(why "delcert-certify did not finish normally (${status})")
endif()
if(EXISTS "${DELCERT_OUT}")
  string(APPEND why "\n  certificate: ${DELCERT_OUT}")
endif()
message(FATAL_ERROR "certificate test ${DELCERT_TEST_NAME} is not CERTIFIED: ${why}")
