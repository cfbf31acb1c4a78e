# Python wrapping of the VTK module (vtk_module_wrap_python), as the Python package
# `pointsetsurfaces`:
#
#   PYTHONPATH=build/lib/python3.11/site-packages python3 -c "from pointsetsurfaces import vtkPointSetSurfaceProjection"
#
# It imports next to `vtkmodules` (Debian's python3-paraview, also what pvpython and pvbatch use):
# the wrapped classes derive from vtkmodules' and compose with any vtkmodules filter. Installed
# under <prefix>/lib/python3.X/site-packages/pointsetsurfaces, finding libPointSetSurfacesFilters
# in <prefix>/lib through its RUNPATH. Needs the wrapping tools of the VTK found (ParaView's ship
# vtkWrapPython-pv5.11) and the Python 3 it was built with; PSS_WRAP_PYTHON=OFF skips it.
option(PSS_WRAP_PYTHON "Wrap the VTK module for Python (package pointsetsurfaces)" ON)
set(PSS_PYTHON_WRAPPED OFF)
if(NOT PSS_WRAP_PYTHON)
  return()
endif()

find_package(VTK QUIET COMPONENTS Python WrappingPythonCore)
if(NOT TARGET VTK::WrapPython OR NOT TARGET VTK::WrapPythonInit OR NOT TARGET VTK::WrappingPythonCore)
  message(STATUS "PointSetSurfaces: this VTK has no Python wrapping tools; the pointsetsurfaces package is not built")
  return()
endif()

if(NOT DEFINED VTK_PYTHON_VERSION)
  set(VTK_PYTHON_VERSION 3)
endif()
vtk_module_python_default_destination(PSS_PYTHON_DESTINATION)
vtk_module_wrap_python(
  MODULES ${pss_vtk_modules}
  TARGET PointSetSurfaces::PythonModules
  WRAPPED_MODULES pss_python_wrapped_modules
  PYTHON_PACKAGE "pointsetsurfaces"
  MODULE_DESTINATION "${PSS_PYTHON_DESTINATION}"
  LIBRARY_DESTINATION "${CMAKE_INSTALL_LIBDIR}"
  CMAKE_DESTINATION "${PSS_INSTALL_CMAKEDIR}"
  INSTALL_HEADERS OFF
  BUILD_STATIC OFF)

# The package's own Python files: __init__.py re-exports the wrapped classes and the numpy
# functions of _numpy_api.py. Copied next to the wrapped module in the build tree (configure_file
# copies again when a file changes) and installed beside it.
set(pss_python_package_dir "${PROJECT_BINARY_DIR}/${PSS_PYTHON_DESTINATION}/pointsetsurfaces")
foreach(pss_python_file __init__.py _numpy_api.py _numpy_support.py)
  configure_file("${PROJECT_SOURCE_DIR}/filters/python/${pss_python_file}" "${pss_python_package_dir}/${pss_python_file}"
    COPYONLY)
  install(FILES "${pss_python_package_dir}/${pss_python_file}"
    DESTINATION "${PSS_PYTHON_DESTINATION}/pointsetsurfaces" COMPONENT python)
endforeach()

set(PSS_PYTHON_WRAPPED ON)
set(PSS_PYTHONPATH "${PROJECT_BINARY_DIR}/${PSS_PYTHON_DESTINATION}")
message(STATUS "PointSetSurfaces: Python package pointsetsurfaces in ${PSS_PYTHONPATH}")
