# `cmake --install BUILD [--prefix PREFIX]` (README.md, "Using the library"; docs/design.md §4):
#
#   bin/delcert, bin/delcert-certify                 the two programs
#   lib/libdelcert_{exact,io,certify,topology}.a     the libraries of the certifier (not delcert_core)
#   include/delcert/{exact,io,certify}/...           their headers, included as "exact/x.hpp"
#   lib/cmake/delcert/                               the package config: find_package(delcert)
#   share/delcert/examples/                          the inputs of README's CMake snippet (delcert_EXAMPLES_DIR):
#                                                    the octahedron on S^2, its complex and true claims
#   DELCERT_PYTHON_INSTALL_DIR/delcert.*.so           the Python module, when built (python/CMakeLists.txt;
#                                                    lib/python3.11/dist-packages with Debian's python3)
#
# find_package(delcert) gives delcert::exact, delcert::io and delcert::certify (each bringing what
# it links), the programs as delcert::delcert and delcert::delcert-certify, the function
# delcert_add_certificate_test() (cmake/delcertCertificateTest.cmake) and delcert_EXAMPLES_DIR. The
# built-in manifold specs (builtin:NAME) are compiled into delcert_io, so they need no installed file.
# The programs are an export set of their own (delcertProgramTargets.cmake, no dependencies), so
# that a project without C or C++ (project(x LANGUAGES NONE)), which can run a certificate test but
# link nothing, gets them without the libraries' dependencies (cmake/delcertConfig.cmake.in).
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set(DELCERT_INSTALL_CMAKEDIR ${CMAKE_INSTALL_LIBDIR}/cmake/delcert)

set_target_properties(delcert_exact PROPERTIES EXPORT_NAME exact)
set_target_properties(delcert_io PROPERTIES EXPORT_NAME io)
set_target_properties(delcert_certify PROPERTIES EXPORT_NAME certify)
# delcert_topology (Regina's 3-sphere recognition) is linked by delcert_certify privately: installed
# for linking, its header not (no installed header includes it).
set_target_properties(delcert_topology PROPERTIES EXPORT_NAME topology)
install(TARGETS delcert delcert-certify EXPORT delcertProgramTargets RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(TARGETS delcert_exact delcert_io delcert_certify delcert_topology
        EXPORT delcertTargets
        RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR}
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
        # One include root for the three folders, under delcert/ so that "io/" and the others
        # do not land directly in the prefix's include/.
        INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/delcert)

# Every header of the three folders. detail/ headers are private (not an API), but some public
# headers include them (certify/restricted/rvd.hpp includes certify/detail/grid.hpp), so they are installed
# too. tests/install/consumer/ compiles every installed public header on its own.
foreach(folder exact io certify)
  install(DIRECTORY ${PROJECT_SOURCE_DIR}/${folder}/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/delcert/${folder}
          FILES_MATCHING PATTERN "*.hpp")
endforeach()

install(EXPORT delcertTargets NAMESPACE delcert:: DESTINATION ${DELCERT_INSTALL_CMAKEDIR})
install(EXPORT delcertProgramTargets NAMESPACE delcert:: DESTINATION ${DELCERT_INSTALL_CMAKEDIR})

# The inputs README's CMake snippet certifies (a copy of examples/downstream/data/, which is a
# copy of fixtures' octahedron): found through delcert_EXAMPLES_DIR, which the package config sets.
set(DELCERT_INSTALL_EXAMPLESDIR ${CMAKE_INSTALL_DATADIR}/delcert/examples)
install(DIRECTORY ${PROJECT_SOURCE_DIR}/examples/downstream/data/ DESTINATION ${DELCERT_INSTALL_EXAMPLESDIR})

configure_package_config_file(${CMAKE_CURRENT_LIST_DIR}/delcertConfig.cmake.in
                              ${PROJECT_BINARY_DIR}/cmake/delcertConfig.cmake
                              INSTALL_DESTINATION ${DELCERT_INSTALL_CMAKEDIR}
                              PATH_VARS DELCERT_INSTALL_EXAMPLESDIR)
# 0.x: a minor version may break the interface, so only the same minor version is compatible.
write_basic_package_version_file(${PROJECT_BINARY_DIR}/cmake/delcertConfigVersion.cmake
                                 COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/cmake/delcertConfig.cmake
              ${PROJECT_BINARY_DIR}/cmake/delcertConfigVersion.cmake
              ${CMAKE_CURRENT_LIST_DIR}/delcertCertificateTest.cmake
              ${CMAKE_CURRENT_LIST_DIR}/delcert-run-certificate-test.cmake
        DESTINATION ${DELCERT_INSTALL_CMAKEDIR})
