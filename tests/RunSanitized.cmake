# Builds an AddressSanitizer + UndefinedBehaviorSanitizer copy of the project and runs the given
# test executables in it with a gtest filter (the bad-input tests). Invoked by ctest:
#   cmake -DSOURCE_DIR=... -DBINARY_DIR=... -DTARGETS=a,b -DFILTER=... -P RunSanitized.cmake
foreach(var SOURCE_DIR BINARY_DIR TARGETS FILTER)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "RunSanitized.cmake needs -D${var}=...")
  endif()
endforeach()
string(REPLACE "," ";" TARGETS "${TARGETS}")

execute_process(
  COMMAND "${CMAKE_COMMAND}" -S "${SOURCE_DIR}" -B "${BINARY_DIR}" -DCMAKE_BUILD_TYPE=RelWithDebInfo
    -DPSS_SANITIZE=ON -DPSS_TEST_SANITIZERS=OFF -DPSS_BUILD_PARAVIEW_PLUGIN=OFF
    -DPSS_BUILD_EXAMPLES=OFF -DPSS_BUILD_BENCHMARKS=OFF
  RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "configuring the sanitized build failed")
endif()
cmake_host_system_information(RESULT cores QUERY NUMBER_OF_LOGICAL_CORES)
execute_process(
  COMMAND "${CMAKE_COMMAND}" --build "${BINARY_DIR}" --parallel ${cores} --target ${TARGETS}
  RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "building the sanitized tests failed")
endif()

# halt_on_error makes any ASan/UBSan report fail the run; VTK's own singletons are not leaks of ours.
set(ENV{ASAN_OPTIONS} "halt_on_error=1:detect_leaks=0")
set(ENV{UBSAN_OPTIONS} "halt_on_error=1:print_stacktrace=1")
foreach(target IN LISTS TARGETS)
  execute_process(
    COMMAND "${BINARY_DIR}/bin/${target}" "--gtest_filter=${FILTER}"
    RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${target} failed under the sanitizers (exit ${rc})")
  endif()
endforeach()
