// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file VtkXml.h
 * @brief VTK XML files (.vtp .vtu .vti) through VTK's readers and writers, every file checked in
 *        full before a reader sees it.
 */
#ifndef pss_cli_io_VtkXml_h
#define pss_cli_io_VtkXml_h

#include "PssIO.h"

#include "vtkSmartPointer.h"

#include <string>

class vtkDataObject;
class vtkDataSet;

namespace pss_cli
{
namespace io
{

/// The dataset of @p path, by its extension (.vtp .vtu .vti); throws std::runtime_error naming
/// the element, array or attribute that is wrong when VTK's reader could not read it safely.
vtkSmartPointer<vtkDataSet> ReadVtkXml(const std::string& path);

/// Writes @p data (a vtkPolyData, vtkUnstructuredGrid or vtkImageData, by the extension of
/// @p path) as appended raw binary data with @p compression.
void WriteVtkXml(vtkDataObject* data, const std::string& path, Compression compression);

}
}

#endif
