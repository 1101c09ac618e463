# Included by python/CMakeLists.txt: the pytest suite as ctest tests, one per test file, run with
# the interpreter the module was built for (Debian's /usr/bin/python3 and its python3-pytest),
# importing the build tree's package.
execute_process(COMMAND ${Python3_EXECUTABLE} -c "import pytest" RESULT_VARIABLE deme_pytest_rc
                OUTPUT_QUIET ERROR_QUIET)
if(NOT deme_pytest_rc EQUAL 0)
  message(STATUS "DEME: Python tests skipped: pytest not found for ${Python3_EXECUTABLE} (apt-get install python3-pytest)")
  return()
endif()

set(deme_py_test_env
  PYTHONPATH=${CMAKE_CURRENT_BINARY_DIR}
  # Custom force models compiled by the tests share the C++ tests' cache (tests/CMakeLists.txt).
  DEME_CACHE_DIR=${PROJECT_BINARY_DIR}/tests/deme_cache
  DEME_TEST_BUILD_DIR=${PROJECT_BINARY_DIR}
  DEME_TEST_SOURCE_DIR=${PROJECT_SOURCE_DIR}
  DEME_TEST_PYTHON_INSTALL_DIR=${DEME_PYTHON_INSTALL_DIR}
  DEME_TEST_CMAKE=${CMAKE_COMMAND}
  PYTHONDONTWRITEBYTECODE=1)

file(GLOB deme_py_tests CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/tests/test_*.py)
file(MAKE_DIRECTORY ${CMAKE_CURRENT_BINARY_DIR}/test-runs)
foreach(test_file ${deme_py_tests})
  get_filename_component(name ${test_file} NAME_WE)
  string(REGEX REPLACE "^test_" "" name ${name})
  add_test(NAME python.${name}
           COMMAND ${Python3_EXECUTABLE} -m pytest -q -p no:cacheprovider ${test_file}
           WORKING_DIRECTORY ${CMAKE_CURRENT_BINARY_DIR}/test-runs)
  set_tests_properties(python.${name} PROPERTIES TIMEOUT 300 LABELS python ENVIRONMENT "${deme_py_test_env}")
endforeach()

# The pip route into a fresh virtual environment (pip_install_test.sh): it builds the library and
# the module again (CPU-only, without tests, demos and benchmarks), a minute or two on 2 cores.
find_program(DEME_BASH bash)
if(DEME_BASH)
  add_test(NAME python.pip_install
           COMMAND ${DEME_BASH} ${CMAKE_CURRENT_SOURCE_DIR}/tests/pip_install_test.sh ${PROJECT_SOURCE_DIR}
                   ${CMAKE_CURRENT_BINARY_DIR}/pip_install_test ${Python3_EXECUTABLE})
  set_tests_properties(python.pip_install PROPERTIES TIMEOUT 900 LABELS "python;package")
endif()
