// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Ply.h
 * @brief PLY files through VTK's reader and writer, with the whole file checked first: VTK's
 *        reader (the Stanford ply library) trusts the file, and no packaged library validates one.
 */
#ifndef pss_cli_io_Ply_h
#define pss_cli_io_Ply_h

#include "vtkSmartPointer.h"

#include <string>

class vtkDataSet;
class vtkPolyData;

namespace pss_cli
{
namespace io
{

/// The points (and faces) of @p path; throws std::runtime_error naming the line or element that
/// is wrong, before VTK's reader sees a file it cannot read safely.
vtkSmartPointer<vtkDataSet> ReadPly(const std::string& path);

/// Binary PLY of @p mesh's points, cells and normals (as float: VTK's writer keeps no others).
void WritePly(vtkPolyData* mesh, const std::string& path);

}
}

#endif
