// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Mesh.h
 * @brief STL and OBJ, written only: they hold geometry (OBJ also the normals), for meshes.
 */
#ifndef pss_cli_io_Mesh_h
#define pss_cli_io_Mesh_h

#include <string>

class vtkPolyData;

namespace pss_cli
{
namespace io
{

/// Writes @p mesh through VTK's STL (binary) or OBJ writer, by @p ext (".stl" or ".obj").
void WriteMesh(vtkPolyData* mesh, const std::string& path, const std::string& ext);

}
}

#endif
