# The pss tool's readers and writers, one file per format: cli/CMakeLists.txt builds them into pss
# and tests/fuzz/CMakeLists.txt into pss_fuzz_cli_input (instrumented), from this one list, with
# the VTK modules they need.
set(PSS_IO_SOURCES
  "${CMAKE_CURRENT_LIST_DIR}/../PssIO.cxx"
  "${CMAKE_CURRENT_LIST_DIR}/Mesh.cxx"
  "${CMAKE_CURRENT_LIST_DIR}/Pcd.cxx"
  "${CMAKE_CURRENT_LIST_DIR}/Ply.cxx"
  "${CMAKE_CURRENT_LIST_DIR}/Table.cxx"
  "${CMAKE_CURRENT_LIST_DIR}/Text.cxx"
  "${CMAKE_CURRENT_LIST_DIR}/VtkXml.cxx"
  "${CMAKE_CURRENT_LIST_DIR}/VtkXmlFile.cxx"
  "${CMAKE_CURRENT_LIST_DIR}/VtkXmlArrayData.cxx")
# VTK::expat: VtkXmlFile.cxx asks expat, through vtkXMLDataParser's parser, what went wrong.
set(PSS_IO_VTK_LIBRARIES VTK::CommonCore VTK::CommonDataModel VTK::CommonExecutionModel VTK::FiltersCore
  VTK::IOCore VTK::IOGeometry VTK::IOPLY VTK::IOXML VTK::IOXMLParser VTK::expat)
# The module's PCD reader and writer (io/Pcd.cxx calls them): pss links the module, the fuzz
# targets compile these sources themselves, instrumented.
set(PSS_PCD_SOURCES
  "${CMAKE_CURRENT_LIST_DIR}/../../filters/vtkPCDReader.cxx"
  "${CMAKE_CURRENT_LIST_DIR}/../../filters/vtkPCDWriter.cxx"
  "${CMAKE_CURRENT_LIST_DIR}/../../filters/PointSetSurfacesPCD.cxx"
  "${CMAKE_CURRENT_LIST_DIR}/../../filters/PointSetSurfacesPCDBody.cxx"
  "${CMAKE_CURRENT_LIST_DIR}/../../filters/PointSetSurfacesVertexCells.cxx")
