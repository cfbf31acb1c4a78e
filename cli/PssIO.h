// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file PssIO.h
 * @brief Reading and writing datasets by file extension for the `pss` command-line tool.
 *
 * | extension | read as | written from |
 * | --- | --- | --- |
 * | .vtp | vtkPolyData (XML) | any vtkPointSet (non-polydata: its points as vertices) |
 * | .vtu | vtkUnstructuredGrid (XML) | any vtkDataSet |
 * | .vti | vtkImageData (XML) | vtkImageData |
 * | .ply | vtkPolyData (points, faces ignored by the filters) | vtkPolyData (points + point arrays dropped) |
 * | .pcd | vtkPolyData of the finite points and every field (vtkPCDReader) | points and numeric point arrays, binary_compressed (binary with --compression none) |
 * | .csv | points from columns x,y[,z] after a header; other numeric columns become arrays | points and every point array, one column per component |
 * | .xyz | whitespace-separated x y [z] per line (# comments) | x y z per line |
 */
#ifndef PssIO_h
#define PssIO_h

#include "vtkSmartPointer.h"

#include <string>

class vtkDataObject;
class vtkDataSet;

namespace pss_cli
{

/// Lower-case extension of @p path including the dot ("" when none).
std::string Extension(const std::string& path);

/// Reads @p path; throws std::runtime_error with a readable message on any failure.
vtkSmartPointer<vtkDataSet> ReadDataSet(const std::string& path);

/// Compression of the XML formats (.vtp .vtu .vti): LZ4 is several times faster than zlib for
/// files about a third larger; every VTK >= 8.1 and ParaView >= 5.5 reads all three.
enum class Compression
{
  LZ4,
  ZLib,
  None
};

/// Writes @p data to @p path by extension; throws std::runtime_error on failure.
void WriteDataSet(vtkDataSet* data, const std::string& path, Compression compression = Compression::LZ4);

}

#endif
