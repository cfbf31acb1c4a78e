// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Pcd.h
 * @brief PCD files (PCL's point clouds) through the module's vtkPCDReader and vtkPCDWriter, with
 *        their errors turned into exceptions for the tool.
 */
#ifndef pss_cli_io_Pcd_h
#define pss_cli_io_Pcd_h

#include "vtkSmartPointer.h"

#include <string>

class vtkPointSet;
class vtkPolyData;

namespace pss_cli
{
namespace io
{

/// The finite points of @p path and its fields as point arrays (vtkPCDReader); throws
/// std::runtime_error with the reader's message. Reports skipped NaN points on stderr.
vtkSmartPointer<vtkPolyData> ReadPcd(const std::string& path);

/// Writes @p data's points and numeric point arrays as PCD: binary_compressed, or binary when
/// @p compress is false (vtkPCDWriter).
void WritePcd(vtkPointSet* data, const std::string& path, bool compress);

}
}

#endif
