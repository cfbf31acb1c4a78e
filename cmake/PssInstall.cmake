# cmake --install: the core (its two shared copies, or one static library; its headers and
# PointSetSurfacesCoreTargets.cmake), the pss tool, and the package files that make
# find_package(PointSetSurfaces) work downstream:
#
#   find_package(PointSetSurfaces REQUIRED)                   # Core, and Filters when it was built
#   find_package(PointSetSurfaces REQUIRED COMPONENTS Core)   # Eigen and nanoflann only, no VTK
#   target_link_libraries(app PRIVATE PointSetSurfaces::Core PointSetSurfaces::Filters)
#
# The VTK module's own files (PointSetSurfaces-targets.cmake and the vtk-module files) are
# installed by vtk_module_build() in the top-level CMakeLists.txt, the plugin by paraview_plugin_build().
include(CMakePackageConfigHelpers)

set_target_properties(PointSetSurfacesCore PROPERTIES EXPORT_NAME Core)
target_include_directories(PointSetSurfacesCore PUBLIC $<INSTALL_INTERFACE:${PSS_INSTALL_INCLUDEDIR}>)
install(TARGETS PointSetSurfacesCore EXPORT PointSetSurfacesCore
  ARCHIVE DESTINATION "${CMAKE_INSTALL_LIBDIR}" COMPONENT development
  LIBRARY DESTINATION "${CMAKE_INSTALL_LIBDIR}" COMPONENT runtime)
if(PSS_CORE_X86_64_V3)
  # Where glibc's loader looks for the x86-64-v3 copy of a library it finds in LIBDIR.
  install(TARGETS PointSetSurfacesCoreX86_64_v3
    LIBRARY DESTINATION "${CMAKE_INSTALL_LIBDIR}/glibc-hwcaps/x86-64-v3" COMPONENT runtime)
endif()
file(GLOB pss_core_headers "${PROJECT_SOURCE_DIR}/filters/core/pss/*.h")
list(FILTER pss_core_headers EXCLUDE REGEX "/NanoflannInternals\\.h$")  # private to PointIndex.cxx
list(FILTER pss_core_headers EXCLUDE REGEX "/ChunkedLoops\\.h$")  # private to PointIndex.cxx and SpatialOrder.cxx
list(FILTER pss_core_headers EXCLUDE REGEX "/KernelDispatch\\.h$")  # private to the kernels' files
install(FILES ${pss_core_headers} DESTINATION "${PSS_INSTALL_INCLUDEDIR}/pss" COMPONENT development)
install(EXPORT PointSetSurfacesCore NAMESPACE PointSetSurfaces:: FILE PointSetSurfacesCoreTargets.cmake
  DESTINATION "${PSS_INSTALL_CMAKEDIR}" COMPONENT development)
# The build tree's export of the VTK module names the (shared) core too.
export(EXPORT PointSetSurfacesCore NAMESPACE PointSetSurfaces::
  FILE "${PROJECT_BINARY_DIR}/install-package/PointSetSurfacesCoreTargets.cmake")

if(PSS_ENABLE_VTK)
  # The pss tool finds libPointSetSurfacesFilters.so next to it, in ../LIBDIR.
  file(RELATIVE_PATH pss_bin_to_lib "/prefix/${CMAKE_INSTALL_BINDIR}" "/prefix/${CMAKE_INSTALL_LIBDIR}")
  set_target_properties(pss PROPERTIES INSTALL_RPATH "$ORIGIN/${pss_bin_to_lib}")
  install(TARGETS pss RUNTIME DESTINATION "${CMAKE_INSTALL_BINDIR}" COMPONENT runtime)
endif()

# What the package config needs to know about this build.
set(PSS_CONFIG_WITH_FILTERS ${PSS_ENABLE_VTK})
set(PSS_CONFIG_VTK_DIR "${VTK_DIR}")
set(PSS_CONFIG_VTK_COMPONENTS CommonCore CommonDataModel CommonExecutionModel CommonMath)
set(PSS_CONFIG_PLUGIN_SUBDIR "${PSS_INSTALL_PLUGINDIR}")
configure_package_config_file("${CMAKE_CURRENT_LIST_DIR}/PointSetSurfacesConfig.cmake.in"
  "${PROJECT_BINARY_DIR}/install-package/PointSetSurfacesConfig.cmake"
  INSTALL_DESTINATION "${PSS_INSTALL_CMAKEDIR}"
  PATH_VARS PSS_INSTALL_INCLUDEDIR)
write_basic_package_version_file("${PROJECT_BINARY_DIR}/install-package/PointSetSurfacesConfigVersion.cmake"
  COMPATIBILITY SameMinorVersion)
install(FILES
  "${PROJECT_BINARY_DIR}/install-package/PointSetSurfacesConfig.cmake"
  "${PROJECT_BINARY_DIR}/install-package/PointSetSurfacesConfigVersion.cmake"
  DESTINATION "${PSS_INSTALL_CMAKEDIR}" COMPONENT development)
