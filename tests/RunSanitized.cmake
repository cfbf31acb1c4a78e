# A sanitized copy of the project, in two steps that ctest runs as separate tests
# (tests/CMakeLists.txt), so the suites of one copy run side by side once it is built:
#   cmake -DMODE=build -DSANITIZER=address|thread -DSOURCE_DIR=... -DBINARY_DIR=... -DTARGETS=a,b [-DLAUNCHER=ccache] -P RunSanitized.cmake
#   cmake -DMODE=run   -DSANITIZER=address|thread -DBINARY_DIR=... -DTARGETS=a -DFILTER=... [-DSHARD=i/n] -P RunSanitized.cmake
# SHARD runs the i-th of n shards of the suite (googletest's own sharding, 0-based), so that ctest
# can run a long suite's shards side by side.
# address: AddressSanitizer + UndefinedBehaviorSanitizer (the asan preset: PSS_SANITIZE);
# thread: ThreadSanitizer (the tsan preset: compiler and linker flags of the whole copy);
# none with -DPRESET=clang: the plain suites built with clang (the clang stage).
# Any report or failing test fails the run.
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

# The copy's flags are the asan / tsan presets of CMakePresets.json (RelWithDebInfo, the plugin,
# examples, benchmarks and nested stages left out); the run's options match those presets' tests.
if(SANITIZER STREQUAL "address")
  set(preset asan)
  # halt_on_error makes any ASan/UBSan report fail the run; VTK's own singletons are not leaks of ours.
  set(ENV{ASAN_OPTIONS} "halt_on_error=1:detect_leaks=0")
  set(ENV{UBSAN_OPTIONS} "halt_on_error=1:print_stacktrace=1")
elseif(SANITIZER STREQUAL "thread")
  set(preset tsan)
  set(ENV{TSAN_OPTIONS} "halt_on_error=1:second_deadlock_stack=1:suppressions=${CMAKE_CURRENT_LIST_DIR}/tsan-vtk.supp")
elseif(SANITIZER STREQUAL "none")
  # A plain copy with another preset's compiler, e.g. -DPRESET=clang (the clang stage).
  if(NOT DEFINED PRESET)
    message(FATAL_ERROR "RunSanitized.cmake: SANITIZER=none needs -DPRESET=...")
  endif()
  set(preset ${PRESET})
else()
  message(FATAL_ERROR "RunSanitized.cmake: SANITIZER must be address, thread or none, not '${SANITIZER}'")
endif()

if(MODE STREQUAL "build")
  set(launcher "")
  if(LAUNCHER)
    set(launcher "-DCMAKE_C_COMPILER_LAUNCHER=${LAUNCHER}" "-DCMAKE_CXX_COMPILER_LAUNCHER=${LAUNCHER}")
  endif()
  execute_process(
    COMMAND "${CMAKE_COMMAND}" -S "${SOURCE_DIR}" --preset ${preset} -B "${BINARY_DIR}" ${launcher}
    RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "configuring the ${SANITIZER}-sanitized build failed")
  endif()
  # ctest runs this step alone (RUN_SERIAL): every core, or CMAKE_BUILD_PARALLEL_LEVEL.
  if(DEFINED ENV{CMAKE_BUILD_PARALLEL_LEVEL} AND NOT "$ENV{CMAKE_BUILD_PARALLEL_LEVEL}" STREQUAL "")
    set(cores "$ENV{CMAKE_BUILD_PARALLEL_LEVEL}")
  else()
    cmake_host_system_information(RESULT cores QUERY NUMBER_OF_LOGICAL_CORES)
  endif()
  execute_process(
    COMMAND "${CMAKE_COMMAND}" --build "${BINARY_DIR}" --parallel ${cores} --target ${TARGETS}
    RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "building the ${SANITIZER}-sanitized tests failed")
  endif()
  return()
endif()

if(DEFINED SHARD)
  string(REPLACE "/" ";" shard "${SHARD}")
  list(GET shard 0 index)
  list(GET shard 1 count)
  set(ENV{GTEST_SHARD_INDEX} "${index}")
  set(ENV{GTEST_TOTAL_SHARDS} "${count}")
endif()
foreach(target IN LISTS TARGETS)
  execute_process(
    COMMAND "${BINARY_DIR}/bin/${target}" "--gtest_filter=${FILTER}"
    RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${target} failed under the ${SANITIZER} sanitizer (exit ${rc})")
  endif()
endforeach()
