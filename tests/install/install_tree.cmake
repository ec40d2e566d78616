# install_tree (tests/install/CMakeLists.txt): installs this build into a fresh PREFIX, and checks
# that the programs, the libraries, the headers and the package config are where the README says.
cmake_minimum_required(VERSION 3.20)
include(${CMAKE_CURRENT_LIST_DIR}/common.cmake)

file(REMOVE_RECURSE ${PREFIX})
delcert_run(${CMAKE_COMMAND} --install ${DELCERT_BINARY_DIR} --prefix ${PREFIX})
foreach(file ${BINDIR}/delcert ${BINDIR}/delcert-certify
             ${LIBDIR}/libdelcert_exact.a ${LIBDIR}/libdelcert_io.a ${LIBDIR}/libdelcert_certify.a
             ${LIBDIR}/libdelcert_topology.a
             ${INCLUDEDIR}/delcert/exact/interval.hpp ${INCLUDEDIR}/delcert/io/spec.hpp
             ${INCLUDEDIR}/delcert/certify/certify.hpp
             ${LIBDIR}/cmake/delcert/delcertConfig.cmake ${LIBDIR}/cmake/delcert/delcertConfigVersion.cmake
             ${LIBDIR}/cmake/delcert/delcertCertificateTest.cmake
             ${LIBDIR}/cmake/delcert/delcert-run-certificate-test.cmake
             ${LIBDIR}/cmake/delcert/delcertTargets.cmake ${LIBDIR}/cmake/delcert/delcertProgramTargets.cmake
             ${DATADIR}/delcert/examples/octahedron.off ${DATADIR}/delcert/examples/octahedron.complex
             ${DATADIR}/delcert/examples/octahedron-claims.json)
  if(NOT EXISTS ${PREFIX}/${file})
    message(FATAL_ERROR "cmake --install did not install ${file}")
  endif()
endforeach()
# Nothing of the producer's library, and no path of the build tree in the package config.
if(EXISTS ${PREFIX}/${LIBDIR}/libdelcert_core.a OR EXISTS ${PREFIX}/${INCLUDEDIR}/delcert/core)
  message(FATAL_ERROR "delcert_core (the producer) is installed; the package is the certifier's libraries")
endif()
file(GLOB configs ${PREFIX}/${LIBDIR}/cmake/delcert/*.cmake)
foreach(config ${configs})
  file(READ ${config} text)
  string(FIND "${text}" "${DELCERT_BINARY_DIR}" at_build)
  string(FIND "${text}" "${DELCERT_SOURCE_DIR}" at_source)
  if(NOT at_build EQUAL -1 OR NOT at_source EQUAL -1)
    message(FATAL_ERROR "${config} names a path of delcert's source or build tree")
  endif()
endforeach()
message("installed into ${PREFIX}")
