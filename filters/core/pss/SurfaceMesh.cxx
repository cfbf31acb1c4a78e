// SPDX-License-Identifier: BSD-3-Clause
#include "pss/SurfaceMesh.h"

#include "pss/Parallel.h"
#include "pss/SurfaceMeshGrid.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <queue>
#include <sstream>
#include <stdexcept>
#include <tuple>

namespace pss
{

void MeshOptions::validate() const
{
  auto positive = [](double v) { return v > 0.0 && std::isfinite(v); };
  if (viewpoint && !isFinite(*viewpoint))
    throw std::invalid_argument("the viewpoint must have finite coordinates");
  if (!positive(cellSize))
  {
    throw std::invalid_argument("the mesh cell size must be a positive finite multiple of h");
  }
  if (!positive(band))
  {
    throw std::invalid_argument("the mesh band must be a positive finite multiple of h");
  }
  if (!positive(maxVertexTravel))
  {
    throw std::invalid_argument("the mesh's largest vertex travel must be a positive finite number of cells");
  }
  if (!(maxSeamAngle >= 0.0 && maxSeamAngle <= 180.0) || !(maxFoldAngle >= 0.0 && maxFoldAngle <= 180.0))
  {
    throw std::invalid_argument("the mesh's seam and fold angles must be in [0, 180] degrees");
  }
  if (!(minPieceArea >= 0.0 && std::isfinite(minPieceArea)))
  {
    throw std::invalid_argument("the mesh's smallest piece area must be a finite number of h^2, at least 0");
  }
  if (!(trimDistance >= 0.0 && std::isfinite(trimDistance)))
  {
    throw std::invalid_argument("the mesh's trim distance must be a finite number of local spacings, at least 0");
  }
  if (!(coveredPieceArea >= 0.0 && std::isfinite(coveredPieceArea)))
  {
    throw std::invalid_argument("the mesh's covered piece area must be a finite number of h^2, at least 0");
  }
  if (maxBandCells == 0)
  {
    throw std::invalid_argument("the mesh's largest band must be at least one cell");
  }
  projection.validate();
  domain.validate();
}

using grid::Coords;
using grid::KeyOrder;

MeshFrame MeshFrame::of(const SurfaceDefinition& surface)
{
  const PointIndex& index = surface.index();
  return MeshFrame{ surface.dimension(), surface.h(), index.boundsMin(), index.boundsMax(), index.centroid() };
}

SurfaceMesher::SurfaceMesher(const SurfaceDefinition& surface, const MeshOptions& options)
  : SurfaceMesher(MeshFrame::of(surface), options)
{
  const PointIndex& index = surface.index();
  if (!(Options.adaptiveCells && index.hasScales() && buildAdaptiveBand(index)))
  {
    buildBand(cellKeysOf(index.points()));
  }
  useSurface(surface);
}

SurfaceMesher::SurfaceMesher(const MeshFrame& frame, const MeshOptions& options)
  : Options(options)
  , Frame(frame)
{
  Options.validate();
  Dimension = frame.dimension;
  Cell = Options.cellSize * frame.h;
  const double ratio = Options.band / Options.cellSize;
  if (ratio > 1e5)
  {
    throw std::invalid_argument("the mesh band is more than 1e5 cells wide: use a larger cell size");
  }
  Reach = static_cast<long long>(std::ceil(ratio));
  sizeGrid(Reach + 1);
}

void SurfaceMesher::useSurface(const SurfaceDefinition& surface)
{
  const PointIndex& index = surface.index();
  if (!Options.cloudNormals.empty() && Options.cloudNormals.size() != index.size() + index.skippedCount())
  {
    throw std::invalid_argument("the mesher was given " + std::to_string(Options.cloudNormals.size()) +
      " cloud normals for " + std::to_string(index.size() + index.skippedCount()) + " points");
  }
  Surface = &surface;
  Normals = std::make_unique<CloudNormals>(surface);
}

SurfaceMesher::Key SurfaceMesher::keyOf(const std::array<long long, 3>& c) const
{
  return KeyOrder{ { 0, 1, 2 }, Size }.encode(c);
}

std::array<long long, 3> SurfaceMesher::coordsOf(Key k) const
{
  return KeyOrder{ { 0, 1, 2 }, Size }.decode(k);
}

Vec3 SurfaceMesher::positionOf(Key k) const
{
  const Coords c = coordsOf(k);
  Vec3 x = Origin;
  for (int a = 0; a < Dimension; ++a)
  {
    x[a] += static_cast<double>(c[a]) * Cell;
  }
  return x;
}

void SurfaceMesher::linkNeighbours()
{
  // Keys + stride is sorted like Keys, so one merge finds every neighbour along an axis.
  const std::size_t n = Keys.size();
  Key stride = 1;
  for (int a = 0; a < Dimension; ++a)
  {
    std::vector<std::uint32_t>& up = Step[2 * a];
    std::vector<std::uint32_t>& down = Step[2 * a + 1];
    up.assign(n, NoIndex);
    down.assign(n, NoIndex);
    std::size_t j = 0;
    for (std::size_t i = 0; i < n; ++i)
    {
      const Key target = Keys[i] + stride;
      while (j < n && Keys[j] < target)
      {
        ++j;
      }
      if (j < n && Keys[j] == target)
      {
        up[i] = static_cast<std::uint32_t>(j);
        down[j] = static_cast<std::uint32_t>(i);
      }
    }
    stride *= static_cast<Key>(Size[a]);
  }
  CellCorner.resize(Cells.size());
  std::size_t j = 0;
  for (std::size_t c = 0; c < Cells.size(); ++c)
  {
    while (Keys[j] < Cells[c])
    {
      ++j;
    }
    CellCorner[c] = static_cast<std::uint32_t>(j);
  }
}

void SurfaceMesher::sizeGrid(long long margin)
{
  // Axis lengths leave room for the band and the cells' far corners on either side.
  std::ostringstream dims;
  for (int a = 0; a < 3; ++a)
  {
    if (a >= Dimension)
    {
      Size[a] = 1;
      continue;
    }
    const double cells = std::floor((Frame.boundsMax[a] - Frame.boundsMin[a]) / Cell) + 2.0 * static_cast<double>(margin) + 1.0;
    dims << (a > 0 ? " x " : "") << cells;
    if (!(cells <= static_cast<double>(1LL << 20)))
    {
      throw std::invalid_argument("the mesh grid over the cloud's bounds would be " + dims.str() +
        " cells, more than 2^20 along an axis: use a larger cell size");
    }
    Size[a] = static_cast<long long>(cells);
    Origin[a] = Frame.boundsMin[a] - static_cast<double>(margin) * Cell;
  }
}

std::vector<std::uint64_t> SurfaceMesher::cellKeysOf(const std::vector<Vec3>& points) const
{
  std::vector<Key> occupied;
  occupied.reserve(points.size());
  for (const Vec3& p : points)
  {
    if (!isFinite(p))
    {
      continue;
    }
    Coords c{ { 0, 0, 0 } };
    for (int a = 0; a < Dimension; ++a)
    {
      // Clamped to the cells the axis lengths were sized for: rounding in p - Origin may add one.
      c[a] = std::clamp(static_cast<long long>(std::floor((p[a] - Origin[a]) / Cell)), Reach + 1, Size[a] - Reach - 2);
    }
    occupied.push_back(keyOf(c));
  }
  std::sort(occupied.begin(), occupied.end());
  occupied.erase(std::unique(occupied.begin(), occupied.end()), occupied.end());
  return occupied;
}

void SurfaceMesher::buildBand(std::vector<std::uint64_t> occupied)
{
  std::sort(occupied.begin(), occupied.end());
  occupied.erase(std::unique(occupied.begin(), occupied.end()), occupied.end());
  Cells = grid::widen(std::move(occupied), Size, Dimension, Reach, Reach, Options.maxBandCells, "band");
  Keys = grid::widen(Cells, Size, Dimension, 0, 1, 2 * Options.maxBandCells, "band's corners");
  Values.assign(Keys.size(), CornerValue{});
  linkNeighbours();
  Statistics.bandCells = Cells.size();
  Statistics.gridVertices = Keys.size();
}

void SurfaceMesher::evaluateVertex(std::size_t i, Workspace& ws)
{
  if (!Hanging.empty() && Hanging[i])
  {
    return; // interpolated after orient()
  }
  const Vec3 x = positionOf(Keys[i]);
  const Direction d = Surface->direction(x, ws);
  CornerValue& v = Values[i];
  v.defined = d.defined;
  if (d.defined)
  {
    v.n = d.n;
    v.g = Surface->lineSample(x, d.n, ws).trueSlope();
    v.defined = std::isfinite(v.g);
  }
}

std::uint32_t SurfaceMesher::crossingOn(std::uint32_t a, std::uint32_t b, int direction)
{
  std::uint32_t& slot = CrossingOfEdge[7 * static_cast<std::size_t>(a) + static_cast<std::size_t>(direction - 1)];
  if (slot == NoIndex)
  {
    slot = newCrossing(a, b);
  }
  return slot;
}

std::uint32_t SurfaceMesher::newCrossing(std::uint32_t a, std::uint32_t b)
{
  const double fa = Values[a].g * Sign[a];
  const double fb = Values[b].g * Sign[b];
  // Clamped away from the corners so that the crossings of edges sharing a corner stay apart.
  const double t = std::clamp(fa / (fa - fb), 1e-3, 1.0 - 1e-3);
  Crossing c;
  c.point = positionOf(Keys[a]) + t * (positionOf(Keys[b]) - positionOf(Keys[a]));
  c.reference = (t < 0.5 ? Values[a].n * Sign[a] : Values[b].n * Sign[b]);
  // Minimum or maximum of e along n (Eq. 2's g rises through a minimum): read off the edge when it
  // runs clearly along n, not across it.
  const Vec3 edge = (positionOf(Keys[b]) - positionOf(Keys[a])).normalized();
  const double along = edge.dot(Values[a].n * Sign[a] + Values[b].n * Sign[b]) / 2.0;
  if (std::abs(along) > 0.2)
  {
    c.type = (fb - fa) * along > 0.0 ? ExtremumType::Minimum : ExtremumType::Maximum;
  }
  // The side of the cells this edge belongs to: its longest extent along an axis, in grid steps.
  const Coords ca = coordsOf(Keys[a]);
  const Coords cb = coordsOf(Keys[b]);
  long long steps = 0;
  for (int k = 0; k < Dimension; ++k)
  {
    steps = std::max(steps, std::abs(cb[k] - ca[k]));
  }
  c.cell = Cell * static_cast<double>(steps);
  Crossings.push_back(std::move(c));
  return static_cast<std::uint32_t>(Crossings.size() - 1);
}

void SurfaceMesher::contourSimplex(const std::array<std::uint32_t, 4>& corners, const std::array<int, 4>& bits, int count)
{
  std::array<double, 4> f{};
  int positives = 0;
  for (int k = 0; k < count; ++k)
  {
    if (!Values[corners[k]].defined)
    {
      return;
    }
    f[k] = Values[corners[k]].g * Sign[corners[k]];
    positives += f[k] > 0.0 ? 1 : 0;
  }
  if (positives == 0 || positives == count)
  {
    return;
  }
  const double seamCos = std::cos(Options.maxSeamAngle * M_PI / 180.0);
  for (int a = 0; a < count; ++a)
  {
    for (int b = a + 1; b < count; ++b)
    {
      const CornerValue& va = Values[corners[a]];
      const CornerValue& vb = Values[corners[b]];
      if (va.n.dot(vb.n) * Sign[corners[a]] * Sign[corners[b]] < seamCos)
      {
        ++Statistics.seamSimplices;
        return;
      }
    }
  }
  // From the negative corners' centroid to the positive ones': the surface's cells are wound
  // counter-clockwise about it.
  Vec3 positiveSum = Vec3::Zero();
  Vec3 negativeSum = Vec3::Zero();
  for (int k = 0; k < count; ++k)
  {
    (f[k] > 0.0 ? positiveSum : negativeSum) += positionOf(Keys[corners[k]]);
  }
  const Vec3 towardPositive = positiveSum / positives - negativeSum / (count - positives);
  std::array<int, 4> pos{};
  std::array<int, 4> neg{};
  int np = 0;
  int nn = 0;
  for (int k = 0; k < count; ++k)
  {
    (f[k] > 0.0 ? pos[np++] : neg[nn++]) = k;
  }
  // The simplex's corners go up one axis at a time, so the lower end of an edge is the earlier one.
  const bool adaptive = !CellLevel.empty();
  auto cross = [&](int p, int q) {
    const int lo = std::min(p, q);
    const int hi = std::max(p, q);
    return adaptive ? crossingBetween(corners[lo], corners[hi]) : crossingOn(corners[lo], corners[hi], bits[hi] & ~bits[lo]);
  };
  if (count == 3)
  {
    // 2D: one segment between the two edges that leave the lone corner.
    const int lone = np == 1 ? pos[0] : neg[0];
    const int o1 = np == 1 ? neg[0] : pos[0];
    const int o2 = np == 1 ? neg[1] : pos[1];
    std::array<std::uint32_t, 2> s{ { cross(lone, o1), cross(lone, o2) } };
    const Vec3 d = Crossings[s[1]].point - Crossings[s[0]].point;
    if (Vec3(-d.y(), d.x(), 0.0).dot(towardPositive) < 0.0)
    {
      std::swap(s[0], s[1]);
    }
    Segments.push_back(s);
    return;
  }
  // The contour polygon: its crossings in cyclic order, each on the simplex edge of two corners.
  std::array<std::array<int, 2>, 4> ends{};
  int size = 0;
  if (np == 1 || nn == 1)
  {
    const int lone = np == 1 ? pos[0] : neg[0];
    for (int k = 0; k < 4; ++k)
    {
      if (k != lone)
      {
        ends[size++] = { { lone, k } };
      }
    }
  }
  else
  {
    // Two corners on each side: a quadrilateral around the cycle p0-n0, p0-n1, p1-n1, p1-n0.
    ends = { { { { pos[0], neg[0] } }, { { pos[0], neg[1] } }, { { pos[1], neg[1] } }, { { pos[1], neg[0] } } } };
    size = 4;
  }
  std::array<std::uint32_t, 4> q{};
  for (int k = 0; k < size; ++k)
  {
    q[k] = cross(ends[k][0], ends[k][1]);
  }
  if (adaptive)
  {
    // A side of the polygon on a face that finer cells share passes through their crossings.
    std::vector<std::uint32_t>& loop = Polygon.loop;
    std::vector<unsigned>& sides = Polygon.sides;
    std::vector<std::uint32_t>& inside = Polygon.inside;
    loop.clear();
    sides.clear();
    for (int k = 0; k < size; ++k)
    {
      const int next = (k + 1) % size;
      loop.push_back(q[k]);
      sides.push_back((1u << k) | (1u << ((k + size - 1) % size)));
      std::array<int, 4> face{ { ends[k][0], ends[k][1], ends[next][0], ends[next][1] } };
      std::sort(face.begin(), face.end());
      const auto last = std::unique(face.begin(), face.end());
      if (last - face.begin() == 3)
      {
        crossingsInside({ { corners[face[0]], corners[face[1]], corners[face[2]] } }, q[k], q[next], inside);
        for (const std::uint32_t c : inside)
        {
          loop.push_back(c);
          sides.push_back(1u << k);
        }
      }
    }
    if (loop.size() > static_cast<std::size_t>(size))
    {
      triangulatePolygon(loop, sides, towardPositive);
      return;
    }
  }
  addTriangle(q[0], q[1], q[2], towardPositive);
  if (size == 4)
  {
    addTriangle(q[0], q[2], q[3], towardPositive);
  }
}

void SurfaceMesher::addTriangle(std::uint32_t a, std::uint32_t b, std::uint32_t c, const Vec3& towardPositive)
{
  const Vec3 normal = (Crossings[b].point - Crossings[a].point).cross(Crossings[c].point - Crossings[a].point);
  if (normal.dot(towardPositive) < 0.0)
  {
    std::swap(b, c);
  }
  Triangles.push_back({ { a, b, c } });
}

void SurfaceMesher::contour()
{
  if (Sign.size() != Keys.size())
  {
    throw std::logic_error("SurfaceMesher::contour() before orient()");
  }
  const int cornersPerCell = 1 << Dimension;
  // Kuhn's subdivision: one simplex per ordering of the axes, walking from corner 0 to the far
  // corner one axis at a time.
  std::vector<std::array<int, 3>> orders;
  std::array<int, 3> axes{ { 0, 1, 2 } };
  do
  {
    orders.push_back(axes);
  } while (std::next_permutation(axes.begin(), axes.begin() + Dimension));
  if (CellLevel.empty())
  {
    CrossingOfEdge.assign(7 * Keys.size(), NoIndex);
  }
  // About one crossing per band cell and two triangles per crossing on a surface (measured: the
  // bunny 1.08 and 1.97): reserved so that they do not grow by copying.
  Crossings.reserve(Cells.size() + Cells.size() / 4);
  if (Dimension == 3)
  {
    Triangles.reserve(2 * Crossings.capacity());
  }
  std::array<std::uint32_t, 8> corner{};
  for (std::size_t cell = 0; cell < Cells.size(); ++cell)
  {
    for (int bits = 0; bits < cornersPerCell; ++bits)
    {
      std::uint32_t v = CellCorner.empty() ? CellCorners[cell][bits] : CellCorner[cell];
      // Regular grid: every corner of a band cell is a grid vertex, so these steps never fall off
      // the band (adaptive cells have their corners listed).
      for (int a = 0; a < Dimension && v != NoIndex && CellCorners.empty(); ++a)
      {
        v = (bits >> a) & 1 ? Step[2 * a][v] : v;
      }
      if (v == NoIndex)
      {
        throw std::logic_error("SurfaceMesher: a band cell lacks a corner (a bug: please report it)");
      }
      corner[bits] = v;
    }
    for (const auto& order : orders)
    {
      std::array<std::uint32_t, 4> simplex{};
      std::array<int, 4> bits{};
      simplex[0] = corner[0];
      for (int k = 0; k < Dimension; ++k)
      {
        bits[k + 1] = bits[k] | (1 << order[k]);
        simplex[k + 1] = corner[bits[k + 1]];
      }
      contourSimplex(simplex, bits, Dimension + 1);
    }
  }
  Statistics.crossings = Crossings.size();
  Statistics.undefinedVertices = static_cast<std::size_t>(
    std::count_if(Values.begin(), Values.end(), [](const CornerValue& v) { return !v.defined; }));
  // What only the grid stages need goes before the projections, the stage with the largest state.
  Evidence.assign(Crossings.size(), DomainEvidence{});
  CrossingOfEdge = {};
  CrossingOfPair = {};
  Step = {};
  CellCorner = {};
  CellCorners = {};
  Values = {};
}

void SurfaceMesher::classifyCrossing(std::size_t i, Workspace& ws)
{
  Evidence[i] = classifyStart(*Surface, Crossings[i].point, Options.projection, Options.domain, ws, Normals.get());
}

namespace
{
void putDirection(double*& out, const Direction& d)
{
  *out++ = d.n.x();
  *out++ = d.n.y();
  *out++ = d.n.z();
  *out++ = d.stability;
  *out++ = d.defined ? 1.0 : 0.0;
}

Direction takeDirection(const double*& in)
{
  Direction d;
  d.n = Vec3(in[0], in[1], in[2]);
  d.stability = in[3];
  d.defined = in[4] != 0.0;
  in += 5;
  return d;
}
} // namespace

std::vector<double> SurfaceMesher::cornerValues() const
{
  std::vector<double> out(Values.size() * CornerWidth);
  double* o = out.data();
  for (const CornerValue& v : Values)
  {
    *o++ = v.n.x();
    *o++ = v.n.y();
    *o++ = v.n.z();
    *o++ = v.g;
    *o++ = v.defined ? 1.0 : 0.0;
  }
  return out;
}

void SurfaceMesher::setCornerValues(const std::vector<double>& values)
{
  const double* in = values.data();
  for (CornerValue& v : Values)
  {
    v.n = Vec3(in[0], in[1], in[2]);
    v.g = in[3];
    v.defined = in[4] != 0.0;
    in += CornerWidth;
  }
}

namespace
{

// A DomainEvidence as EvidenceWidth doubles, and back.
void putEvidence(double*& o, const DomainEvidence& e)
{
  const ProjectionResult& p = e.projection;
  *o++ = static_cast<double>(e.label);
  *o++ = p.point.x();
  *o++ = p.point.y();
  *o++ = p.point.z();
  putDirection(o, p.direction);
  putDirection(o, p.startDirection);
  *o++ = p.energy;
  *o++ = p.iterations;
  *o++ = p.converged ? 1.0 : 0.0;
  *o++ = p.lastStep;
  *o++ = static_cast<double>(p.reason);
  *o++ = static_cast<double>(p.type);
  *o++ = e.distanceToCloud;
  *o++ = e.normalAngle;
  *o++ = e.startAngle;
  *o++ = e.startStability;
}

void takeEvidence(const double*& in, DomainEvidence& e)
{
  ProjectionResult& p = e.projection;
  e.label = static_cast<DomainLabel>(static_cast<int>(*in++));
  p.point = Vec3(in[0], in[1], in[2]);
  in += 3;
  p.direction = takeDirection(in);
  p.startDirection = takeDirection(in);
  p.energy = *in++;
  p.iterations = static_cast<int>(*in++);
  p.converged = *in++ != 0.0;
  p.lastStep = *in++;
  p.reason = static_cast<StopReason>(static_cast<int>(*in++));
  p.type = static_cast<ExtremumType>(static_cast<int>(*in++));
  e.distanceToCloud = *in++;
  e.normalAngle = *in++;
  e.startAngle = *in++;
  e.startStability = *in++;
}

} // namespace

std::vector<double> SurfaceMesher::crossingEvidence() const
{
  std::vector<double> out(Evidence.size() * EvidenceWidth);
  double* o = out.data();
  for (const DomainEvidence& e : Evidence)
  {
    putEvidence(o, e);
  }
  return out;
}

void SurfaceMesher::setCrossingEvidence(const std::vector<double>& values)
{
  const double* in = values.data();
  for (DomainEvidence& e : Evidence)
  {
    takeEvidence(in, e);
  }
}

std::vector<double> SurfaceMesher::holeValues() const
{
  std::vector<double> out(HoleEvidence.size() * HoleWidth);
  double* o = out.data();
  for (std::size_t j = 0; j < HoleEvidence.size(); ++j)
  {
    putEvidence(o, HoleEvidence[j]);
    *o++ = HoleCloudGapSq[j];
  }
  return out;
}

void SurfaceMesher::setHoleValues(const std::vector<double>& values)
{
  const double* in = values.data();
  for (std::size_t j = 0; j < HoleEvidence.size(); ++j)
  {
    takeEvidence(in, HoleEvidence[j]);
    HoleCloudGapSq[j] = *in++;
  }
}

namespace
{

// Measures the time since the last lap into @p seconds.
class Laps
{
public:
  void lap(double& seconds)
  {
    const auto now = std::chrono::steady_clock::now();
    seconds = std::chrono::duration<double>(now - Last).count();
    Last = now;
  }

private:
  std::chrono::steady_clock::time_point Last = std::chrono::steady_clock::now();
};

} // namespace

std::optional<SurfaceMesh> runMeshStages(
  SurfaceMesher& mesher, const std::function<bool(const MeshStage&)>& run, MeshTimings& t)
{
  Laps laps;
  if (!run(MeshStage{ mesher.gridVertexCount(), [&](std::size_t i) { return mesher.gridVertex(i); },
        &SurfaceMesher::evaluateVertex, &SurfaceMesher::cornerValues, &SurfaceMesher::setCornerValues,
        SurfaceMesher::CornerWidth, LoopShare(0.0, 0.45) }))
  {
    return std::nullopt;
  }
  laps.lap(t.corners);
  mesher.orient();
  laps.lap(t.orient);
  mesher.contour();
  laps.lap(t.contour);
  if (!run(MeshStage{ mesher.crossingCount(), [&](std::size_t i) { return mesher.crossing(i); },
        &SurfaceMesher::classifyCrossing, &SurfaceMesher::crossingEvidence, &SurfaceMesher::setCrossingEvidence,
        SurfaceMesher::EvidenceWidth, LoopShare(0.5, 0.98) }))
  {
    return std::nullopt;
  }
  laps.lap(t.projection);
  SurfaceMesh mesh = mesher.assemble();
  mesher.findHoles(mesh);
  if (!run(MeshStage{ mesher.holeCount(), [&](std::size_t j) { return mesher.holeCentre(j); },
        &SurfaceMesher::evaluateHole, &SurfaceMesher::holeValues, &SurfaceMesher::setHoleValues,
        SurfaceMesher::HoleWidth, LoopShare(0.98, 0.99) }))
  {
    return std::nullopt;
  }
  mesher.closeHoles(mesh);
  for (mesher.beginSpacings(); mesher.spacingCount() > 0;)
  {
    if (!run(MeshStage{ mesher.spacingCount(), [&](std::size_t i) { return mesher.spacingPoint(i); },
          &SurfaceMesher::evaluateSpacing, &SurfaceMesher::spacingValues, &SurfaceMesher::setSpacingValues, 1,
          LoopShare(0.99, 1.0) }))
    {
      return std::nullopt;
    }
    if (!mesher.nextSpacingPass())
    {
      break;
    }
  }
  for (mesher.beginTrim(mesh); mesher.trimSampleCount() > 0; mesher.refineTrim(mesh))
  {
    if (!run(MeshStage{ mesher.trimSampleCount(), [&](std::size_t i) { return mesher.trimSample(i); },
          &SurfaceMesher::evaluateTrimSample, &SurfaceMesher::trimValues, &SurfaceMesher::setTrimValues,
          SurfaceMesher::TrimWidth, LoopShare(0.99, 1.0) }))
    {
      return std::nullopt;
    }
  }
  mesher.cutFar(mesh);
  laps.lap(t.finish);
  return mesh;
}

std::optional<SurfaceMesh> extractSurfaceMesh(const SurfaceDefinition& surface, const MeshOptions& options,
  const ParallelLoop& loop, MeshTimings* timings, const StageSplit* split)
{
  MeshTimings local;
  MeshTimings& t = timings ? *timings : local;
  Laps laps;
  SurfaceMesher mesher(surface, options);
  laps.lap(t.band);
  // Each parallel stage: one call of a mesher method per index (of this part's block, with a
  // split) through the caller's loop; with a split every part then takes part in the exchange,
  // aborted or not, so none waits in vain.
  return runMeshStages(
    mesher,
    [&](const MeshStage& stage) {
      const std::size_t first = split ? split->begin(stage.count) : 0;
      const std::size_t last = split ? split->end(stage.count) : stage.count;
      const bool completed = loop(last - first, stage.share, [&](std::size_t begin, std::size_t end, Workspace& ws) {
        for (std::size_t i = first + begin; i < first + end; ++i)
        {
          (mesher.*stage.evaluate)(i, ws);
        }
      });
      if (!split)
      {
        return completed;
      }
      std::vector<double> items = (mesher.*stage.get)();
      if (!split->share(items, stage.width, stage.count, completed))
      {
        return false;
      }
      (mesher.*stage.set)(items);
      return true;
    },
    t);
}

SurfaceMesh extractSurfaceMesh(const SurfaceDefinition& surface, const MeshOptions& options, int threads, MeshTimings* timings)
{
  return *extractSurfaceMesh(surface, options, threadLoop(threads), timings); // threadLoop never stops early
}

} // namespace pss
