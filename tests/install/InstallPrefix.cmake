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
message(STATUS "installed into ${PREFIX}")
