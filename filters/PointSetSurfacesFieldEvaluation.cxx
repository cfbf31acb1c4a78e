// SPDX-License-Identifier: BSD-3-Clause
#include "PointSetSurfacesFieldEvaluation.h"


#include "vtkCellType.h"
#include "vtkDataSet.h"
#include "vtkIdList.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkRectilinearGrid.h"
#include "vtkStructuredGrid.h"

#include "pss/NormalOrientation.h"
#include "pss/PointIndex.h"
#include "pss/SurfaceDefinition.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <vector>

namespace pss_vtk
{

bool MakeOrientation(int rule, const double referencePoint[3], const double referenceDirection[3],
  const pss::Vec3& centroid, pss::Orientation& out, std::string& error)
{
  switch (rule)
  {
    case ORIENT_AWAY_FROM_CENTROID:
      out = pss::Orientation::awayFrom(centroid);
      return true;
    case ORIENT_AWAY_FROM_POINT:
    {
      const pss::Vec3 p(referencePoint[0], referencePoint[1], referencePoint[2]);
      if (!pss::isFinite(p))
      {
        error = "the ReferencePoint has a NaN or infinite coordinate";
        return false;
      }
      out.rule = pss::Orientation::Rule::AwayFromPoint;
      out.reference = p;
      return true;
    }
    case ORIENT_ALONG_DIRECTION:
    {
      const pss::Vec3 d(referenceDirection[0], referenceDirection[1], referenceDirection[2]);
      const double norm = d.norm();
      if (!std::isfinite(norm) || !(norm > 0.0))
      {
        error = "the ReferenceDirection must be a finite, non-zero vector";
        return false;
      }
      out.rule = pss::Orientation::Rule::AlongDirection;
      out.reference = d / norm;
      return true;
    }
    default:
      error = "unknown orientation mode " + std::to_string(rule);
      return false;
  }
}

FieldEvaluator::FieldEvaluator(const pss::SurfaceDefinition& surface, const pss::Orientation& orientation)
  : Definition(surface)
  , Orient(orientation)
  , Distance(surface.index(), surface.parameters())
{
}

namespace
{
// Replaces a non-finite value by 0 and reports whether it was finite.
bool Sanitize(double& v)
{
  if (std::isfinite(v))
  {
    return true;
  }
  v = 0.0;
  return false;
}
}

FieldValues FieldEvaluator::Evaluate(const double xIn[3], pss::Workspace& ws, unsigned parts) const
{
  FieldValues out;
  const pss::Vec3 x(xIn[0], xIn[1], xIn[2]);
  if (!pss::isFinite(x))
  {
    return out; // valid = false, everything 0
  }
  bool finite = true;
  if (parts & FIELD_DIRECTIONAL)
  {
    const pss::ImplicitSample s = pss::evaluateImplicit(this->Definition, x, this->Orient, ws);
    if (s.direction.n.allFinite())
    {
      // Zero where n is undefined (FieldValues::normal): the eigenvector of a degenerate
      // covariance is an arbitrary direction, not a normal.
      out.normal = s.direction.defined ? s.direction.n : pss::Vec3::Zero();
    }
    else
    {
      finite = false;
    }
    out.energy = s.energy;
    out.g = s.g;
    out.stability = s.direction.stability;
    out.extremumType = static_cast<int>(s.type);
    finite = Sanitize(out.energy) && finite;
    finite = Sanitize(out.g) && finite;
    finite = Sanitize(out.stability) && finite;
  }
  if (parts & FIELD_DELTA)
  {
    out.delta = this->Distance.delta(x, ws);
    finite = Sanitize(out.delta) && finite;
  }
  out.valid = finite;
  if (!finite)
  {
    out.normal.setZero();
    out.stability = 0.0;
    out.extremumType = 0;
  }
  return out;
}

namespace
{

// Structured datasets: the 2 * dim axis neighbours (i +- 1, j +- 1, k +- 1).
bool StructuredDimensions(vtkDataSet* mesh, int dims[3])
{
  if (auto* image = vtkImageData::SafeDownCast(mesh))
  {
    image->GetDimensions(dims);
    return true;
  }
  if (auto* rect = vtkRectilinearGrid::SafeDownCast(mesh))
  {
    rect->GetDimensions(dims);
    return true;
  }
  if (auto* grid = vtkStructuredGrid::SafeDownCast(mesh))
  {
    grid->GetDimensions(dims);
    return true;
  }
  return false;
}

// Neighbours of every point (a grid's axis neighbours, or points consecutive in a cell).
pss::NeighbourGraph BuildGraph(vtkDataSet* mesh)
{
  const vtkIdType n = mesh->GetNumberOfPoints();
  std::vector<std::pair<vtkIdType, vtkIdType>> edges;
  int dims[3];
  if (StructuredDimensions(mesh, dims) && vtkIdType(dims[0]) * dims[1] * dims[2] == n)
  {
    const vtkIdType sx = 1, sy = dims[0], sz = vtkIdType(dims[0]) * dims[1];
    for (int k = 0; k < dims[2]; ++k)
    {
      for (int j = 0; j < dims[1]; ++j)
      {
        for (int i = 0; i < dims[0]; ++i)
        {
          const vtkIdType id = i * sx + j * sy + k * sz;
          if (i + 1 < dims[0])
          {
            edges.emplace_back(id, id + sx);
          }
          if (j + 1 < dims[1])
          {
            edges.emplace_back(id, id + sy);
          }
          if (k + 1 < dims[2])
          {
            edges.emplace_back(id, id + sz);
          }
        }
      }
    }
  }
  else
  {
    // Points consecutive in a cell are neighbours; polygons and 3D cells close the ring, lines
    // and poly-lines do not (their ends are not adjacent), vertices connect nothing.
    vtkNew<vtkIdList> ids;
    const vtkIdType cells = mesh->GetNumberOfCells();
    for (vtkIdType c = 0; c < cells; ++c)
    {
      const int type = mesh->GetCellType(c);
      if (type == VTK_EMPTY_CELL || type == VTK_VERTEX || type == VTK_POLY_VERTEX)
      {
        continue;
      }
      mesh->GetCellPoints(c, ids);
      const vtkIdType m = ids->GetNumberOfIds();
      const bool open = type == VTK_LINE || type == VTK_POLY_LINE || m < 3;
      for (vtkIdType a = 0; a + (open ? 1 : 0) < m; ++a)
      {
        const vtkIdType p = ids->GetId(a);
        const vtkIdType q = ids->GetId((a + 1) % m);
        if (p != q && p >= 0 && q >= 0 && p < n && q < n)
        {
          edges.emplace_back(p, q);
        }
      }
    }
  }

  pss::NeighbourGraph g;
  g.start.assign(static_cast<std::size_t>(n) + 1, 0);
  for (const auto& e : edges)
  {
    ++g.start[static_cast<std::size_t>(e.first) + 1];
    ++g.start[static_cast<std::size_t>(e.second) + 1];
  }
  std::partial_sum(g.start.begin(), g.start.end(), g.start.begin());
  g.adjacent.resize(g.start.back());
  std::vector<std::size_t> fill(g.start.begin(), g.start.end() - 1);
  for (const auto& e : edges)
  {
    g.adjacent[fill[static_cast<std::size_t>(e.first)]++] = static_cast<std::uint32_t>(e.second);
    g.adjacent[fill[static_cast<std::size_t>(e.second)]++] = static_cast<std::uint32_t>(e.first);
  }
  return g;
}

} // namespace

vtkIdType PropagateOrientation(vtkDataSet* mesh, double* normals, double* g, const double* stability)
{
  const vtkIdType n = mesh ? mesh->GetNumberOfPoints() : 0;
  if (n == 0)
  {
    return 0;
  }
  // Seeds: the most stable point of each component first, kept as it is; n and g change sign
  // together (see the header).
  std::vector<std::uint32_t> order(static_cast<std::size_t>(n));
  std::iota(order.begin(), order.end(), 0u);
  std::stable_sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) { return stability[a] > stability[b]; });
  return static_cast<vtkIdType>(pss::propagateOrientation(
    BuildGraph(mesh), normals, order, [](std::uint32_t) { return false; }, [&](std::uint32_t i) { g[i] = -g[i]; }));
}

}
