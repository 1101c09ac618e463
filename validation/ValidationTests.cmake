# Included by the top-level CMakeLists.txt: `validation/run.py --quick` as the ctest test
# validation.quick (the README's test command runs it, so CI does), on the CPU backend unless
# DEME_BACKEND says otherwise, writing its plots and verdicts into <build>/validation-out. A failed
# verdict fails the test. One thread: ctest -j2 runs another test beside it, and two OpenMP teams
# of two on two cores wait on each other (226 s so, 31 s alone, 38 s on one thread).
# The interpreter the module was built for (python/CMakeLists.txt picks Debian's unless told).
set(deme_validation_python ${Python3_EXECUTABLE})
if(NOT deme_validation_python)
  set(deme_validation_python /usr/bin/python3)
endif()
add_test(NAME validation.quick
         COMMAND ${deme_validation_python} ${PROJECT_SOURCE_DIR}/validation/run.py --quick
                 --out ${PROJECT_BINARY_DIR}/validation-out)
set_tests_properties(validation.quick PROPERTIES TIMEOUT 900 LABELS validation
                     ENVIRONMENT "OMP_NUM_THREADS=1;PYTHONPATH=${PROJECT_BINARY_DIR}/python;DEME_BUILD_DIR=${PROJECT_BINARY_DIR};PYTHONDONTWRITEBYTECODE=1")
