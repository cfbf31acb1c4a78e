# A sanitized copy of the project, in two steps that ctest runs as separate tests
# (tests/CMakeLists.txt), so the suites of one copy run side by side once it is built:
#   cmake -DMODE=build -DSANITIZER=address|thread -DSOURCE_DIR=... -DBINARY_DIR=... -DTARGETS=a,b -P RunSanitized.cmake
#   cmake -DMODE=run   -DSANITIZER=address|thread -DBINARY_DIR=... -DTARGETS=a -DFILTER=... -P RunSanitized.cmake
# address: AddressSanitizer + UndefinedBehaviorSanitizer (the project's PSS_SANITIZE option);
# thread: ThreadSanitizer (compiler and linker flags of the whole copy). Any report fails the run.
if(NOT DEFINED MODE)
  set(MODE build)
endif()
if(MODE STREQUAL "build")
  set(required SOURCE_DIR BINARY_DIR TARGETS)
else()
  set(required BINARY_DIR TARGETS FILTER)
endif()
foreach(var IN LISTS required)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "RunSanitized.cmake needs -D${var}=...")
  endif()
endforeach()
if(NOT DEFINED SANITIZER)
  set(SANITIZER address)
endif()
string(REPLACE "," ";" TARGETS "${TARGETS}")

set(common -DPSS_TEST_SANITIZERS=OFF -DPSS_TEST_FUZZ=OFF -DPSS_BUILD_PARAVIEW_PLUGIN=OFF
  -DPSS_BUILD_EXAMPLES=OFF -DPSS_BUILD_BENCHMARKS=OFF)
if(SANITIZER STREQUAL "address")
  set(flags -DPSS_SANITIZE=ON)
  # halt_on_error makes any ASan/UBSan report fail the run; VTK's own singletons are not leaks of ours.
  set(ENV{ASAN_OPTIONS} "halt_on_error=1:detect_leaks=0")
  set(ENV{UBSAN_OPTIONS} "halt_on_error=1:print_stacktrace=1")
elseif(SANITIZER STREQUAL "thread")
  set(tsan "-fsanitize=thread -fno-omit-frame-pointer")
  set(flags -DPSS_SANITIZE=OFF "-DCMAKE_C_FLAGS=${tsan}" "-DCMAKE_CXX_FLAGS=${tsan}"
    "-DCMAKE_EXE_LINKER_FLAGS=-fsanitize=thread" "-DCMAKE_SHARED_LINKER_FLAGS=-fsanitize=thread"
    "-DCMAKE_MODULE_LINKER_FLAGS=-fsanitize=thread")
  set(ENV{TSAN_OPTIONS} "halt_on_error=1:second_deadlock_stack=1:suppressions=${CMAKE_CURRENT_LIST_DIR}/tsan-vtk.supp")
else()
  message(FATAL_ERROR "RunSanitized.cmake: SANITIZER must be address or thread, not '${SANITIZER}'")
endif()

if(MODE STREQUAL "build")
  execute_process(
    COMMAND "${CMAKE_COMMAND}" -S "${SOURCE_DIR}" -B "${BINARY_DIR}" -DCMAKE_BUILD_TYPE=RelWithDebInfo ${flags} ${common}
    RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "configuring the ${SANITIZER}-sanitized build failed")
  endif()
  cmake_host_system_information(RESULT cores QUERY NUMBER_OF_LOGICAL_CORES)
  execute_process(
    COMMAND "${CMAKE_COMMAND}" --build "${BINARY_DIR}" --parallel ${cores} --target ${TARGETS}
    RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "building the ${SANITIZER}-sanitized tests failed")
  endif()
  return()
endif()

foreach(target IN LISTS TARGETS)
  execute_process(
    COMMAND "${BINARY_DIR}/bin/${target}" "--gtest_filter=${FILTER}"
    RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${target} failed under the ${SANITIZER} sanitizer (exit ${rc})")
  endif()
endforeach()
