# Helpers of the install tests (tests/install/CMakeLists.txt passes the variables they read).

foreach(variable DELCERT_BINARY_DIR DELCERT_SOURCE_DIR PREFIX BINDIR LIBDIR INCLUDEDIR WORK_DIR CTEST GENERATOR
                 CXX_COMPILER)
  if(NOT DEFINED ${variable} OR "${${variable}}" STREQUAL "")
    message(FATAL_ERROR "-D${variable}=... is missing: run this script through ctest (tests/install/CMakeLists.txt)")
  endif()
endforeach()

# Runs a command; fails showing its output unless its exit status is 0.
function(delcert_run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE status OUTPUT_VARIABLE output ERROR_VARIABLE output)
  if(NOT status STREQUAL "0")
    list(JOIN ARGN " " shown)
    message(FATAL_ERROR "failed (${status}): ${shown}\n${output}")
  endif()
endfunction()

# Configures the project in `source` against PREFIX alone in a fresh `build` folder, with this
# build's toolchain, and builds it. Extra arguments go to the configure step.
function(delcert_configure_and_build source build)
  file(REMOVE_RECURSE ${build})
  set(configure ${CMAKE_COMMAND} -S ${source} -B ${build} -G ${GENERATOR} -DCMAKE_PREFIX_PATH=${PREFIX}
      -DCMAKE_CXX_COMPILER=${CXX_COMPILER} -DCMAKE_BUILD_TYPE=${BUILD_TYPE}
      "-DCMAKE_CXX_FLAGS=${CXX_FLAGS}" "-DCMAKE_EXE_LINKER_FLAGS=${LINKER_FLAGS}" ${ARGN})
  if(LAUNCHER)
    list(APPEND configure "-DCMAKE_CXX_COMPILER_LAUNCHER=${LAUNCHER}")
  endif()
  if(WERROR)
    list(APPEND configure -DCMAKE_COMPILE_WARNING_AS_ERROR=ON)
  endif()
  delcert_run(${configure})
  delcert_run(${CMAKE_COMMAND} --build ${build} --parallel 2)
endfunction()

# The top-level "verdict" of a certificate file.
function(delcert_certificate_verdict file out)
  if(NOT EXISTS ${file})
    message(FATAL_ERROR "no certificate at ${file}")
  endif()
  file(READ ${file} json)
  string(JSON verdict GET "${json}" verdict)
  set(${out} ${verdict} PARENT_SCOPE)
endfunction()
