# cmake -DBINARY_DIR=build -DPREFIX=dir -P InstallPrefix.cmake: a fresh `cmake --install` of the
# build into PREFIX, then a check that the package's files are where find_package looks.
file(REMOVE_RECURSE "${PREFIX}")
execute_process(COMMAND "${CMAKE_COMMAND}" --install "${BINARY_DIR}" --prefix "${PREFIX}"
  OUTPUT_QUIET RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "cmake --install ${BINARY_DIR} --prefix ${PREFIX} failed (exit ${rc})")
endif()
file(GLOB config "${PREFIX}/lib*/cmake/PointSetSurfaces/PointSetSurfacesConfig.cmake")
file(GLOB header "${PREFIX}/include/PointSetSurfaces/pss/Core.h")
if(NOT config OR NOT header)
  message(FATAL_ERROR "the install in ${PREFIX} has no PointSetSurfacesConfig.cmake or pss/Core.h")
endif()
# The core's copy for x86-64-v3 goes where glibc's loader looks for it, beside the baseline one.
if(EXISTS "${BINARY_DIR}/lib/glibc-hwcaps/x86-64-v3/libPointSetSurfacesCore.so")
  file(GLOB v3 "${PREFIX}/lib*/glibc-hwcaps/x86-64-v3/libPointSetSurfacesCore.so")
  if(NOT v3)
    message(FATAL_ERROR "the install in ${PREFIX} has no glibc-hwcaps/x86-64-v3/libPointSetSurfacesCore.so")
  endif()
endif()
message(STATUS "installed into ${PREFIX}")
