# Included by the top-level CMakeLists.txt: `validation/run.py --quick <case>` as one ctest test per
# case, validation.quick.<case> (the README's test command runs them, so CI does), on the CPU backend
# unless DEME_BACKEND says otherwise, writing plots and verdicts into <build>/validation-out/<case>.
# A failed verdict fails the test. One test per case so that ctest -j2 spreads them over the cores
# beside the other tests. One thread each: two OpenMP teams of two on two cores wait on each other
# (the first three cases took 226 s so, 31 s alone, 38 s on one thread).
# The interpreter the module was built for (python/CMakeLists.txt picks Debian's unless told).
set(deme_validation_python ${Python3_EXECUTABLE})
if(NOT deme_validation_python)
  set(deme_validation_python /usr/bin/python3)
endif()
file(GLOB deme_validation_cases CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/validation/cases/*.py)
foreach(script ${deme_validation_cases})
  get_filename_component(case ${script} NAME_WE)
  add_test(NAME validation.quick.${case}
           COMMAND ${deme_validation_python} ${PROJECT_SOURCE_DIR}/validation/run.py --quick ${case}
                   --out ${PROJECT_BINARY_DIR}/validation-out/${case})
  set_tests_properties(validation.quick.${case} PROPERTIES TIMEOUT 900 LABELS validation
                       ENVIRONMENT "OMP_NUM_THREADS=1;PYTHONPATH=${PROJECT_BINARY_DIR}/python;DEME_BUILD_DIR=${PROJECT_BINARY_DIR};PYTHONDONTWRITEBYTECODE=1")
endforeach()
# The suite's own tooling (validation/tests: e.g. the drum's replay of earlier runs from their data),
# with pytest, as the Python module's tests.
add_test(NAME validation.tools
         COMMAND ${deme_validation_python} -m pytest -q -p no:cacheprovider ${PROJECT_SOURCE_DIR}/validation/tests)
set_tests_properties(validation.tools PROPERTIES TIMEOUT 300 LABELS validation
                     ENVIRONMENT "OMP_NUM_THREADS=1;PYTHONPATH=${PROJECT_BINARY_DIR}/python;DEME_BUILD_DIR=${PROJECT_BINARY_DIR};PYTHONDONTWRITEBYTECODE=1")
