// SPDX-License-Identifier: BSD-3-Clause
#include "Table.h"

#include "Text.h"

#include "vtkCellArray.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <fstream>
#include <stdexcept>
#include <vector>

namespace pss_cli
{
namespace io
{

// Points (and, for CSV with a header, extra numeric columns as arrays) from a text table.
vtkSmartPointer<vtkDataSet> ReadTable(const std::string& path, bool csv)
{
  std::ifstream in(path);
  if (!in)
  {
    throw std::runtime_error("cannot open " + path);
  }
  std::vector<std::string> names;
  std::vector<std::vector<double>> columns;
  std::string line;
  std::size_t lineNumber = 0;
  std::size_t width = 0;
  while (std::getline(in, line))
  {
    ++lineNumber;
    const std::string t = Trim(line);
    if (t.empty() || t[0] == '#')
    {
      continue;
    }
    const std::vector<std::string> tokens = Split(t, csv);
    std::vector<double> values(tokens.size());
    bool numeric = true;
    for (std::size_t i = 0; i < tokens.size() && numeric; ++i)
    {
      numeric = ParseDouble(tokens[i], values[i]);
    }
    if (!numeric)
    {
      if (csv && names.empty() && columns.empty())
      {
        for (const std::string& tok : tokens)
        {
          names.push_back(Lower(tok));
        }
        continue;
      }
      throw std::runtime_error(path + ":" + std::to_string(lineNumber) + ": not a row of numbers: " + t);
    }
    if (width == 0)
    {
      width = values.size();
      if (width < 2)
      {
        throw std::runtime_error(path + ":" + std::to_string(lineNumber) + ": need at least two columns (x y)");
      }
      // Every column of the header must have its numbers (a header wider than the rows once
      // sent the x or y lookup past the last column).
      if (!names.empty() && names.size() != width)
      {
        throw std::runtime_error(path + ":" + std::to_string(lineNumber) + ": the header names " +
          std::to_string(names.size()) + " columns, this row has " + std::to_string(width));
      }
      columns.resize(width);
    }
    if (values.size() != width)
    {
      throw std::runtime_error(path + ":" + std::to_string(lineNumber) + ": expected " + std::to_string(width) +
        " columns, found " + std::to_string(values.size()));
    }
    for (std::size_t i = 0; i < width; ++i)
    {
      columns[i].push_back(values[i]);
    }
  }
  // Coordinates: the columns named x, y, z when there is a header, else the first two or three.
  auto column = [&](const char* name, std::size_t fallback) -> int {
    if (!names.empty())
    {
      const auto it = std::find(names.begin(), names.end(), name);
      return it == names.end() ? -1 : static_cast<int>(it - names.begin());
    }
    return fallback < width ? static_cast<int>(fallback) : -1;
  };
  const int cx = column("x", 0);
  const int cy = column("y", 1);
  const int cz = column("z", 2);
  if (width > 0 && (cx < 0 || cy < 0))
  {
    throw std::runtime_error(path + ": the header has no x and y columns");
  }
  const vtkIdType n = width == 0 ? 0 : static_cast<vtkIdType>(columns[0].size());
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(n);
  for (vtkIdType i = 0; i < n; ++i)
  {
    points->SetPoint(i, columns[cx][i], columns[cy][i], cz >= 0 ? columns[cz][i] : 0.0);
  }
  auto poly = vtkSmartPointer<vtkPolyData>::New();
  poly->SetPoints(points);
  vtkNew<vtkCellArray> verts;
  for (vtkIdType i = 0; i < n; ++i)
  {
    verts->InsertNextCell(1, &i);
  }
  poly->SetVerts(verts);
  for (std::size_t c = 0; c < names.size() && c < width; ++c)
  {
    if (static_cast<int>(c) == cx || static_cast<int>(c) == cy || static_cast<int>(c) == cz)
    {
      continue;
    }
    vtkNew<vtkDoubleArray> a;
    a->SetName(names[c].c_str());
    a->SetNumberOfValues(n);
    for (vtkIdType i = 0; i < n; ++i)
    {
      a->SetValue(i, columns[c][i]);
    }
    poly->GetPointData()->AddArray(a);
  }
  return poly;
}

void WriteTable(vtkDataSet* data, const std::string& path, bool csv)
{
  std::ofstream out(path);
  if (!out)
  {
    throw std::runtime_error("cannot write " + path);
  }
  vtkPointData* pd = data->GetPointData();
  std::vector<vtkDataArray*> arrays;
  if (csv)
  {
    out << "x,y,z";
    for (int a = 0; a < pd->GetNumberOfArrays(); ++a)
    {
      vtkDataArray* array = pd->GetArray(a);
      if (!array || !array->GetName())
      {
        continue;
      }
      arrays.push_back(array);
      // A column name must survive being read back: no separators, line breaks or control
      // characters, and not empty (an unnamed column would shift every later one).
      std::string name = array->GetName();
      for (char& ch : name)
      {
        ch = ch == ',' || std::iscntrl(static_cast<unsigned char>(ch)) ? '_' : ch;
      }
      name = Trim(name).empty() ? "array" + std::to_string(arrays.size()) : name;
      const int nc = array->GetNumberOfComponents();
      for (int c = 0; c < nc; ++c)
      {
        out << ',' << name;
        if (nc > 1)
        {
          out << '_' << c;
        }
      }
    }
    out << '\n';
  }
  char buffer[64];
  const char sep = csv ? ',' : ' ';
  for (vtkIdType i = 0; i < data->GetNumberOfPoints(); ++i)
  {
    double p[3];
    data->GetPoint(i, p);
    for (int k = 0; k < 3; ++k)
    {
      std::snprintf(buffer, sizeof(buffer), "%.17g", p[k]);
      out << (k ? std::string(1, sep) : std::string()) << buffer;
    }
    for (vtkDataArray* array : arrays)
    {
      for (int c = 0; c < array->GetNumberOfComponents(); ++c)
      {
        std::snprintf(buffer, sizeof(buffer), "%.17g", array->GetComponent(i, c));
        out << sep << buffer;
      }
    }
    out << '\n';
  }
  if (!out)
  {
    throw std::runtime_error("error while writing " + path);
  }
}

}
}
