# ThreadSanitizer run of the threading tests (ctest `tsan_threading`): builds a runner of the files
# that hold them (deme_thread_tests, tests/CMakeLists.txt) with -fsanitize=thread in its own
# directory and runs the kinematics/dynamics thread tests and one of the output writer thread.
# OpenMP loops run on one thread there (OMP_NUM_THREADS=1): libgomp is not instrumented, and the
# threads under test are the kinematics worker and the dynamics thread.
# Inputs: -DDEME_SOURCE_DIR, -DWORK_DIR, -DGENERATOR, -DMAKE_PROGRAM, -DCXX_COMPILER
file(MAKE_DIRECTORY ${WORK_DIR})
set(build ${WORK_DIR}/build-tsan)
execute_process(
  COMMAND ${CMAKE_COMMAND} -S ${DEME_SOURCE_DIR} -B ${build} -G ${GENERATOR} -DCMAKE_MAKE_PROGRAM=${MAKE_PROGRAM}
          -DCMAKE_CXX_COMPILER=${CXX_COMPILER} -DCMAKE_BUILD_TYPE=RelWithDebInfo -DDEME_TSAN=ON
          -DDEME_BUILD_DEMOS=OFF -DDEME_BUILD_BENCH=OFF -DDEME_NATIVE_ARCH=OFF -DDEME_ENABLE_CUDA=OFF
  RESULT_VARIABLE rc OUTPUT_FILE ${WORK_DIR}/tsan-configure.log ERROR_FILE ${WORK_DIR}/tsan-configure.log)
if(NOT rc EQUAL 0)
  file(READ ${WORK_DIR}/tsan-configure.log log)
  message(FATAL_ERROR "configuring the TSAN build failed:\n${log}")
endif()
set(ENV{MAKEFLAGS} "")
execute_process(COMMAND ${CMAKE_COMMAND} --build ${build} -j 2 --target deme_thread_tests
  RESULT_VARIABLE rc OUTPUT_FILE ${WORK_DIR}/tsan-build.log ERROR_FILE ${WORK_DIR}/tsan-build.log)
if(NOT rc EQUAL 0)
  file(READ ${WORK_DIR}/tsan-build.log log)
  message(FATAL_ERROR "building the TSAN test runner failed:\n${log}")
endif()
set(ENV{OMP_NUM_THREADS} 1)
set(ENV{TSAN_OPTIONS} "halt_on_error=1 second_deadlock_stack=1")
execute_process(COMMAND ${build}/tests/deme_thread_tests --gtest_filter=Async.Small*:Async.Incline*:Async.Worker*:Async.Update*:Api.*:OutputFailure.FailedWrite*
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
message("${out}")
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "ThreadSanitizer run failed (exit ${rc})")
endif()
