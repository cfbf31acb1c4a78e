# Builds the libFuzzer targets of tests/fuzz with clang, or runs one of them for a bounded time on
# its committed seed corpus. Invoked by ctest (tests/CMakeLists.txt):
#   cmake -DMODE=build -DSOURCE_DIR=. -DBINARY_DIR=build/fuzz [-DLAUNCHER=ccache] -P RunFuzz.cmake
#   cmake -DMODE=run -DBINARY_DIR=build/fuzz -DFUZZER=pss_fuzz_core -DCORPUS=tests/fuzz/corpus/core
#         -DSECONDS=60 [-DMAX_LEN=1024] -P RunFuzz.cmake
# A crash, a sanitizer report, a broken contract (abort), a leak or a slow input (-timeout) makes
# the fuzzer exit non-zero and the test fail; the input that did it is kept in
# BINARY_DIR/artifacts/ (replay it with `BINARY_DIR/FUZZER ARTIFACT`). New interesting inputs go
# to BINARY_DIR/work/FUZZER, never into the committed corpus.
foreach(var MODE BINARY_DIR)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "RunFuzz.cmake needs -D${var}=...")
  endif()
endforeach()

if(MODE STREQUAL "build")
  if(NOT DEFINED SOURCE_DIR)
    message(FATAL_ERROR "RunFuzz.cmake -DMODE=build needs -DSOURCE_DIR=... (the project's root)")
  endif()
  find_program(clangxx NAMES clang++ clang++-14 REQUIRED)
  find_program(clangc NAMES clang clang-14 REQUIRED)
  set(launcher "")
  if(LAUNCHER)
    set(launcher "-DCMAKE_C_COMPILER_LAUNCHER=${LAUNCHER}" "-DCMAKE_CXX_COMPILER_LAUNCHER=${LAUNCHER}")
  endif()
  # The fuzz preset of CMakePresets.json (PSS_FUZZ: only tests/fuzz), with the clang found here.
  execute_process(
    COMMAND "${CMAKE_COMMAND}" -S "${SOURCE_DIR}" --preset fuzz -B "${BINARY_DIR}"
      "-DCMAKE_C_COMPILER=${clangc}" "-DCMAKE_CXX_COMPILER=${clangxx}" ${launcher}
    RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "configuring the fuzz targets failed")
  endif()
  # ctest runs this step alone (RUN_SERIAL): every core, or CMAKE_BUILD_PARALLEL_LEVEL.
  if(DEFINED ENV{CMAKE_BUILD_PARALLEL_LEVEL} AND NOT "$ENV{CMAKE_BUILD_PARALLEL_LEVEL}" STREQUAL "")
    set(cores "$ENV{CMAKE_BUILD_PARALLEL_LEVEL}")
  else()
    cmake_host_system_information(RESULT cores QUERY NUMBER_OF_LOGICAL_CORES)
  endif()
  execute_process(COMMAND "${CMAKE_COMMAND}" --build "${BINARY_DIR}" --parallel ${cores} RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "building the fuzz targets failed")
  endif()
  return()
endif()

if(NOT MODE STREQUAL "run")
  message(FATAL_ERROR "RunFuzz.cmake: MODE must be build or run, not '${MODE}'")
endif()
foreach(var FUZZER CORPUS SECONDS)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "RunFuzz.cmake -DMODE=run needs -D${var}=...")
  endif()
endforeach()
set(executable "${BINARY_DIR}/${FUZZER}")
if(NOT EXISTS "${executable}")
  message(FATAL_ERROR "${executable} was not built (see the Fuzz.Build test)")
endif()
if(NOT DEFINED MAX_LEN)
  set(MAX_LEN 4096)
endif()
set(work "${BINARY_DIR}/work/${FUZZER}")
set(artifacts "${BINARY_DIR}/artifacts/")
file(REMOVE_RECURSE "${work}")
file(MAKE_DIRECTORY "${work}" "${artifacts}")

set(ENV{ASAN_OPTIONS} "halt_on_error=1:abort_on_error=1:detect_leaks=1")
set(ENV{LSAN_OPTIONS} "suppressions=${CMAKE_CURRENT_LIST_DIR}/lsan-vtk.supp:print_suppressions=0")
set(ENV{UBSAN_OPTIONS} "halt_on_error=1:print_stacktrace=1")
execute_process(
  COMMAND "${executable}" "-max_total_time=${SECONDS}" -timeout=60 -rss_limit_mb=3072 "-max_len=${MAX_LEN}"
    -print_final_stats=1 "-artifact_prefix=${artifacts}${FUZZER}-" "${work}" "${CORPUS}"
  RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  file(GLOB found "${artifacts}${FUZZER}-*")
  message(FATAL_ERROR "${FUZZER} found a failure (exit ${rc}); reproducer(s): ${found}\n"
    "replay: ${executable} <reproducer>")
endif()
