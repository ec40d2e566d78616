# install_readme_snippet (tests/install/CMakeLists.txt): README.md's CMake snippet, run as written.
# readme/CMakeLists.txt IS the snippet, character for character (keep the two equal; it has no
# comment of its own for that reason): a project declared LANGUAGES NONE that finds the installed
# package and certifies the installed example inputs through delcert_EXAMPLES_DIR. Then the same
# file with LANGUAGES C (FindThreads and CGAL's config need a language; C is enough), where the
# library targets must exist too. Each is configured against PREFIX alone, built, and its ctest
# run: the test must pass and its certificate say CERTIFIED.
cmake_minimum_required(VERSION 3.20)
include(${CMAKE_CURRENT_LIST_DIR}/common.cmake)

set(snippet ${CMAKE_CURRENT_LIST_DIR}/readme/CMakeLists.txt)
file(READ ${snippet} text)
string(FIND "${text}" "LANGUAGES NONE" none)
if(none EQUAL -1)
  message(FATAL_ERROR "${snippet} no longer declares LANGUAGES NONE; this test is about such a project")
endif()

function(delcert_run_snippet source build)
  delcert_configure_and_build(${source} ${build})
  delcert_run(${CTEST} --test-dir ${build} --output-on-failure)
  delcert_certificate_verdict(${build}/octahedron.certificate.json verdict)
  if(NOT verdict STREQUAL "CERTIFIED")
    message(FATAL_ERROR "${source}: the certificate says ${verdict}")
  endif()
endfunction()

delcert_run_snippet(${CMAKE_CURRENT_LIST_DIR}/readme ${WORK_DIR}/readme-none)
message("README's snippet (LANGUAGES NONE): configured against ${PREFIX}, its test passes, CERTIFIED")

set(c_project ${WORK_DIR}/readme-c-source)
file(REMOVE_RECURSE ${c_project})
string(REPLACE "LANGUAGES NONE" "LANGUAGES C" c_text "${text}")
string(APPEND c_text "foreach(target delcert::exact delcert::io delcert::certify Threads::Threads)\n"
                     "  if(NOT TARGET \${target})\n"
                     "    message(FATAL_ERROR \"\${target} is not defined in a C project\")\n"
                     "  endif()\n"
                     "endforeach()\n"
                     "if(NOT delcert_LIBRARIES_FOUND)\n"
                     "  message(FATAL_ERROR \"delcert_LIBRARIES_FOUND is false in a C project\")\n"
                     "endif()\n")
file(WRITE ${c_project}/CMakeLists.txt "${c_text}")
delcert_run_snippet(${c_project} ${WORK_DIR}/readme-c)
message("README's snippet with LANGUAGES C: the library targets are there too, CERTIFIED")
