# cmake -DPSS=build/bin/pss -DWORK=dir -P CompareKernels.cmake: the pss tool projects the same
# cloud with the AVX2 kernels and with PSS_SIMD=baseline; the outputs must be the same bytes (both
# copies compute with four-double vectors and no fused multiply-add, see pss/KernelDispatch.cxx).
file(MAKE_DIRECTORY "${WORK}")
execute_process(COMMAND "${PSS}" generate --scene sphere --dimension 3 --count 1500 --noise 0.3 --size 40
    -o "${WORK}/cloud.csv" RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "pss generate failed (exit ${rc})")
endif()
foreach(variant com integral levin)
  foreach(isa baseline avx2)
    set(ENV{PSS_SIMD} "${isa}")
    execute_process(COMMAND "${PSS}" project "${WORK}/cloud.csv" --variant ${variant} --h 2 --threads 2
        -o "${WORK}/${variant}-${isa}.csv" RESULT_VARIABLE rc)
    if(NOT rc EQUAL 0)
      message(FATAL_ERROR "pss project --variant ${variant} with PSS_SIMD=${isa} failed (exit ${rc})")
    endif()
  endforeach()
  execute_process(COMMAND "${CMAKE_COMMAND}" -E compare_files "${WORK}/${variant}-baseline.csv" "${WORK}/${variant}-avx2.csv"
    RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "--variant ${variant}: the baseline and AVX2 kernels gave different outputs")
  endif()
  message(STATUS "--variant ${variant}: baseline and AVX2 kernels agree bitwise")
endforeach()
