// SPDX-License-Identifier: BSD-3-Clause
#include "PointSetSurfacesVertexCells.h"

#include "vtkNew.h"
#include "vtkSMPTools.h"
#include "vtkTypeInt32Array.h"
#include "vtkTypeInt64Array.h"

namespace pss_vtk
{

namespace
{

template <typename ArrayT>
vtkSmartPointer<vtkCellArray> VertexCellsOf(vtkIdType n)
{
  vtkNew<ArrayT> offsets;
  vtkNew<ArrayT> connectivity;
  offsets->SetNumberOfValues(n + 1);
  connectivity->SetNumberOfValues(n);
  auto* o = offsets->GetPointer(0);
  auto* c = connectivity->GetPointer(0);
  using Value = typename ArrayT::ValueType;
  vtkSMPTools::For(0, n, 1 << 16, [o, c](vtkIdType begin, vtkIdType end) {
    for (vtkIdType i = begin; i < end; ++i)
    {
      o[i] = static_cast<Value>(i);
      c[i] = static_cast<Value>(i);
    }
  });
  o[n] = static_cast<Value>(n);
  auto cells = vtkSmartPointer<vtkCellArray>::New();
  cells->SetData(offsets, connectivity);
  return cells;
}

} // namespace

vtkSmartPointer<vtkCellArray> VertexCells(vtkIdType n)
{
  return n < VTK_INT_MAX ? VertexCellsOf<vtkTypeInt32Array>(n) : VertexCellsOf<vtkTypeInt64Array>(n);
}

}
