# install_python_module (tests/install/CMakeLists.txt): the Python module that `cmake --install`
# put under PREFIX/PYTHON_DIR imports with PYTHONPATH pointing there (not the build tree's copy)
# and samples an eps-net.
cmake_minimum_required(VERSION 3.20)
include(${CMAKE_CURRENT_LIST_DIR}/common.cmake)

foreach(variable PYTHON PYTHON_DIR)
  if(NOT DEFINED ${variable} OR "${${variable}}" STREQUAL "")
    message(FATAL_ERROR "-D${variable}=... is missing: run this script through ctest (tests/install/CMakeLists.txt)")
  endif()
endforeach()
file(GLOB modules ${PREFIX}/${PYTHON_DIR}/delcert*.so)
if(NOT modules)
  message(FATAL_ERROR "cmake --install did not install the Python module into ${PREFIX}/${PYTHON_DIR}")
endif()
set(script [=[
import os, sys
import delcert
prefix = os.path.realpath(sys.argv[1])
where = os.path.realpath(delcert.__file__)
assert where.startswith(prefix + os.sep), f"imported {where}, not the installed module under {prefix}"
points = delcert.sample("builtin:sphere-2", eps=0.5, seed=1)
assert points.ndim == 2 and points.shape[1] == 3 and points.shape[0] > 10, points.shape
print(f"delcert {delcert.__version__} from {where}: {points.shape[0]} points")
]=])
file(MAKE_DIRECTORY ${WORK_DIR}/python-module)
execute_process(COMMAND ${CMAKE_COMMAND} -E env PYTHONPATH=${PREFIX}/${PYTHON_DIR} PYTHONNOUSERSITE=1
                        ${PYTHON} -c "${script}" ${PREFIX}
                WORKING_DIRECTORY ${WORK_DIR}/python-module
                RESULT_VARIABLE status OUTPUT_VARIABLE output ERROR_VARIABLE output)
if(NOT status STREQUAL "0")
  message(FATAL_ERROR "importing the installed module failed (${status}):\n${output}")
endif()
message("${output}")
