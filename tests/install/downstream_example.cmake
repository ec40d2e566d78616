# install_downstream_example (tests/install/CMakeLists.txt): examples/downstream/ configured against
# the installed package alone, built, and its ctest run: both its tests must pass, and the
# certificate of its delcert_add_certificate_test() test must say CERTIFIED.
cmake_minimum_required(VERSION 3.20)
include(${CMAKE_CURRENT_LIST_DIR}/common.cmake)

set(build ${WORK_DIR}/downstream-example)
delcert_configure_and_build(${DELCERT_SOURCE_DIR}/examples/downstream ${build})
delcert_run(${CTEST} --test-dir ${build} --output-on-failure)
delcert_certificate_verdict(${build}/octahedron_certified.certificate.json verdict)
if(NOT verdict STREQUAL "CERTIFIED")
  message(FATAL_ERROR "the example's certificate says ${verdict}")
endif()
message("examples/downstream: built against ${PREFIX}, its tests pass, its certificate says CERTIFIED")
