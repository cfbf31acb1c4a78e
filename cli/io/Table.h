// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Table.h
 * @brief Text tables of points: .csv (a header names the columns x, y[, z] and arrays) and
 *        .xyz/.txt (whitespace-separated x y [z] per line, # comments).
 */
#ifndef pss_cli_io_Table_h
#define pss_cli_io_Table_h

#include "vtkSmartPointer.h"

#include <string>

class vtkDataSet;

namespace pss_cli
{
namespace io
{

/// Points as vertices, and for a CSV with a header every other numeric column as a point array.
vtkSmartPointer<vtkDataSet> ReadTable(const std::string& path, bool csv);

/// Every point, and for CSV every named point array, one column per component (%.17g).
void WriteTable(vtkDataSet* data, const std::string& path, bool csv);

}
}

#endif
