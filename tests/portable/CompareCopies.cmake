# cmake -DPSS=build/bin/pss -DWORK=dir -DPYTHON=python3 -DCOPIES=ON|OFF -DBASELINE_ENV=VAR=VALUE
#   -P CompareCopies.cmake:
# the pss tool projects the same cloud (five definitions: APSS and RIMLS with the normals it estimates)
# with each build of the core it has.
# - The baseline copy (the loader takes it with BASELINE_ENV: GLIBC_TUNABLES=glibc.cpu.hwcaps=-AVX2)
#   with its SSE2 kernels (PSS_SIMD=baseline) and with its AVX2 kernels: the same bytes (both
#   compute with four-double vectors and no fused multiply-add, see pss/KernelDispatch.cxx).
# - With COPIES (PSS_CORE_X86_64_V3): the loader takes the x86-64-v3 copy where the CPU runs it
#   (`pss --version` says which), and its outputs agree with the baseline copy's to rounding:
#   the same iterations, stop reasons and extremum types, values within 1e-10 (h for lengths;
#   compare_outputs.py). Fused multiply-adds round differently, so the bytes differ.
file(MAKE_DIRECTORY "${WORK}")
execute_process(COMMAND "${PSS}" generate --scene sphere --dimension 3 --count 1500 --noise 0.3 --size 40
    -o "${WORK}/cloud.csv" RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "pss generate failed (exit ${rc})")
endif()

function(pss_run out)  # pss_run(OUT [ENV VAR=VALUE...] ARGS ARG...): runs pss, its output in OUT
  cmake_parse_arguments(PARSE_ARGV 1 run "" "" "ENV;ARGS")
  execute_process(COMMAND "${CMAKE_COMMAND}" -E env ${run_ENV} "${PSS}" ${run_ARGS}
    RESULT_VARIABLE rc OUTPUT_VARIABLE text ERROR_VARIABLE text)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "pss ${run_ARGS} (${run_ENV}) failed (exit ${rc}): ${text}")
  endif()
  set(${out} "${text}" PARENT_SCOPE)
endfunction()

pss_run(version ENV ${BASELINE_ENV} PSS_SIMD=baseline ARGS --version)
if(NOT version MATCHES "SIMD baseline")
  message(FATAL_ERROR "the baseline copy with PSS_SIMD=baseline should run SSE2 kernels: ${version}")
endif()
set(check_v3 OFF)
if(COPIES)
  pss_run(version ARGS --version)
  execute_process(COMMAND /lib64/ld-linux-x86-64.so.2 --help OUTPUT_VARIABLE loader ERROR_QUIET)
  if(loader MATCHES "x86-64-v3 \\(supported")
    if(NOT version MATCHES "SIMD x86-64-v3")
      message(FATAL_ERROR "this CPU runs x86-64-v3, but the loader did not take the core's copy for it: ${version}")
    endif()
    set(check_v3 ON)
  else()
    message(STATUS "this CPU does not run x86-64-v3: only the baseline copy is compared")
  endif()
endif()

foreach(variant com integral levin apss rimls)
  set(args project "${WORK}/cloud.csv" --variant ${variant} --h 2 --threads 2)
  foreach(isa baseline avx2)
    pss_run(ignored ENV ${BASELINE_ENV} PSS_SIMD=${isa} ARGS ${args} -o "${WORK}/${variant}-${isa}.csv")
  endforeach()
  execute_process(COMMAND "${CMAKE_COMMAND}" -E compare_files "${WORK}/${variant}-baseline.csv" "${WORK}/${variant}-avx2.csv"
    RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "--variant ${variant}: the baseline copy's SSE2 and AVX2 kernels gave different outputs")
  endif()
  message(STATUS "--variant ${variant}: the baseline copy's SSE2 and AVX2 kernels agree bitwise")
  if(check_v3)
    pss_run(ignored ARGS ${args} -o "${WORK}/${variant}-v3.csv")
    set(energy_unit)
    if(variant MATCHES "apss|rimls")
      set(energy_unit --energy-in-h2) # f^2: rounding noise at every converged end point
    endif()
    execute_process(COMMAND "${PYTHON}" "${CMAKE_CURRENT_LIST_DIR}/compare_outputs.py" --h 2 ${energy_unit}
        "${WORK}/${variant}-baseline.csv" "${WORK}/${variant}-v3.csv" RESULT_VARIABLE rc OUTPUT_VARIABLE report)
    message(STATUS "--variant ${variant}, baseline against x86-64-v3:\n${report}")
    if(NOT rc EQUAL 0)
      message(FATAL_ERROR "--variant ${variant}: the x86-64-v3 copy disagrees with the baseline copy")
    endif()
  endif()
endforeach()
