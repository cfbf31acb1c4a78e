// SPDX-License-Identifier: BSD-3-Clause
#include "pss/DeltaLattice.h"
#include "pss/PointIndex.h"
#include "pss/Workspace.h"

#include <algorithm>
#include <cmath>
#include <deque>
#include <mutex>
#include <thread>

namespace pss
{

namespace
{

/// floor(i / BrickCells) for negative i too: the brick of cell i.
std::int64_t brickOf(std::int64_t i)
{
  static_assert(LatticeCache::BrickCells == 8, "brickOf shifts by 3");
  // An arithmetic shift: floor division for negative i too (GCC and Clang; C++20 guarantees it).
  return i >> 3;
}

/// The cubic Hermite basis on [0, 1] and its first two derivatives at t: value[corner][order]
/// multiplies a corner's value, slope[corner][order] its derivative.
struct HermiteBasis
{
  double value[2][3];
  double slope[2][3];

  explicit HermiteBasis(double t)
  {
    const double t2 = t * t;
    const double t3 = t2 * t;
    value[0][0] = 1.0 - 3.0 * t2 + 2.0 * t3;
    value[0][1] = -6.0 * t + 6.0 * t2;
    value[0][2] = -6.0 + 12.0 * t;
    value[1][0] = 3.0 * t2 - 2.0 * t3;
    value[1][1] = 6.0 * t - 6.0 * t2;
    value[1][2] = 6.0 - 12.0 * t;
    slope[0][0] = t - 2.0 * t2 + t3;
    slope[0][1] = 1.0 - 4.0 * t + 3.0 * t2;
    slope[0][2] = -4.0 + 6.0 * t;
    slope[1][0] = t3 - t2;
    slope[1][1] = 3.0 * t2 - 2.0 * t;
    slope[1][2] = 6.0 * t - 2.0;
  }
};

} // namespace

std::size_t LatticeCache::BrickHash::operator()(const BrickKey& key) const
{
  // Large odd multipliers spread neighbouring bricks over the buckets.
  const auto u = [](std::int64_t v) { return static_cast<std::uint64_t>(v); };
  std::uint64_t x = u(key.i) * 0x9E3779B97F4A7C15ull ^ u(key.j) * 0xC2B2AE3D27D4EB4Full ^ u(key.k) * 0x165667B19E3779F9ull;
  x ^= x >> 29;
  return static_cast<std::size_t>(x);
}

LatticeCache::Brick::Brick()
{
  // std::atomic's default constructor leaves the value unset (C++17).
  for (std::atomic<std::uint8_t>& node : state)
  {
    node.store(Empty, std::memory_order_relaxed);
  }
}

void LatticeCache::clear()
{
  table.reset();
  seen.clear();
  lastBrick = nullptr;
}

/**
 * The lattice nodes of one index, h, cutoff and spacing, shared by every workspace that reads
 * them (each holds the table through LatticeCache). The map is guarded by a mutex, a node's data
 * by its state (LatticeCache::Brick). Bricks are shared with the workspaces that looked them up,
 * so forgetting one here never frees it under a reader.
 */
class LatticeTable
{
public:
  LatticeTable(std::uint64_t serial, double h, double cutoff, double spacing)
    : Serial(serial)
    , H(h)
    , Cutoff(cutoff)
    , Spacing(spacing)
  {
  }

  /// The table of this lattice: the one some workspace already reads, else a new one.
  static std::shared_ptr<LatticeTable> of(std::uint64_t serial, double h, double cutoff, double spacing)
  {
    static std::mutex registryMutex;
    static std::vector<std::weak_ptr<LatticeTable>> registry;
    const std::lock_guard<std::mutex> lock(registryMutex);
    registry.erase(std::remove_if(registry.begin(), registry.end(),
                     [](const std::weak_ptr<LatticeTable>& t) { return t.expired(); }),
      registry.end());
    for (const std::weak_ptr<LatticeTable>& weak : registry)
    {
      std::shared_ptr<LatticeTable> table = weak.lock();
      if (table && table->serves(serial, h, cutoff, spacing))
      {
        return table;
      }
    }
    auto table = std::make_shared<LatticeTable>(serial, h, cutoff, spacing);
    registry.push_back(table);
    return table;
  }

  bool serves(std::uint64_t serial, double h, double cutoff, double spacing) const
  {
    return Serial == serial && H == h && Cutoff == cutoff && Spacing == spacing;
  }

  /// The brick of @p key, added (empty) when absent; a full table first forgets the oldest
  /// quarter of its bricks (their nodes are computed again if asked for after that).
  std::shared_ptr<LatticeCache::Brick> add(const LatticeCache::BrickKey& key)
  {
    const std::lock_guard<std::mutex> lock(Mutex);
    auto found = Bricks.find(key);
    if (found == Bricks.end())
    {
      if (Bricks.size() >= LatticeCache::MaxBricks)
      {
        for (std::size_t n = 0; n < LatticeCache::MaxBricks / 4; ++n)
        {
          Bricks.erase(Order.front());
          Order.pop_front();
        }
      }
      found = Bricks.emplace(key, std::make_shared<LatticeCache::Brick>()).first;
      Order.push_back(key);
    }
    return found->second;
  }

  /// The brick of @p key, or nullptr.
  std::shared_ptr<LatticeCache::Brick> find(const LatticeCache::BrickKey& key)
  {
    const std::lock_guard<std::mutex> lock(Mutex);
    const auto found = Bricks.find(key);
    return found == Bricks.end() ? nullptr : found->second;
  }

private:
  const std::uint64_t Serial;
  const double H;
  const double Cutoff;
  const double Spacing;
  std::mutex Mutex;
  std::unordered_map<LatticeCache::BrickKey, std::shared_ptr<LatticeCache::Brick>, LatticeCache::BrickHash> Bricks;
  std::deque<LatticeCache::BrickKey> Order; ///< Bricks' keys, oldest first
};

double DeltaLattice::spacingFor(const PointIndex& index, const SurfaceParameters& params)
{
  return params.deltaLattice * (index.hasScales() ? index.minScale() : params.h);
}

DeltaLattice::DeltaLattice(const DistanceField& field)
  : Field(field)
  , Spacing(spacingFor(field.index(), field.parameters()))
  , Planar(field.index().dimension() == 2)
{
}

LatticeCache::Brick& DeltaLattice::brickAt(const LatticeCache::BrickKey& key, Workspace& ws) const
{
  LatticeCache& cache = ws.lattice;
  if (cache.lastBrick && cache.lastKey == key)
  {
    return *cache.lastBrick;
  }
  auto found = cache.seen.find(key);
  if (found == cache.seen.end())
  {
    if (cache.seen.size() >= LatticeCache::MaxSeen)
    {
      cache.seen.clear();
      cache.lastBrick = nullptr;
    }
    found = cache.seen.emplace(key, cache.table->add(key)).first;
  }
  LatticeCache::Brick* brick = found->second.get();
  cache.lastKey = key;
  cache.lastBrick = brick;
  return *brick;
}

std::uint8_t DeltaLattice::readyNode(
  LatticeCache::Brick& brick, const LatticeCache::BrickKey& key, int local, Workspace& ws) const
{
  std::atomic<std::uint8_t>& state = brick.state[local];
  for (;;)
  {
    std::uint8_t seen = state.load(std::memory_order_acquire);
    if (LatticeCache::isReady(seen))
    {
      return seen;
    }
    if (seen == LatticeCache::Empty && state.compare_exchange_strong(seen, LatticeCache::Busy, std::memory_order_acquire))
    {
      std::uint8_t ready = LatticeCache::Empty;
      try
      {
        ready = computeNode(brick, key, local, ws);
      }
      catch (...)
      {
        // Whoever reads the node next computes it: nobody waits for a node that will not come.
        state.store(LatticeCache::Empty, std::memory_order_release);
        throw;
      }
      state.store(ready, std::memory_order_release);
      return ready;
    }
    if (seen == LatticeCache::Busy)
    {
      // Another thread is computing it (microseconds: one neighbourhood's exact Hessian).
      std::this_thread::yield();
    }
  }
}

std::uint8_t DeltaLattice::computeNode(
  LatticeCache::Brick& brick, const LatticeCache::BrickKey& key, int local, Workspace& ws) const
{
  constexpr int side = LatticeCache::BrickSide;
  constexpr int cells = LatticeCache::BrickCells;
  constexpr int nodeData = LatticeCache::NodeData;
  const int l[3] = { local / (side * side), local / side % side, local % side };
  double* data = brick.data.data() + local * nodeData;
  // A node on a face, edge or corner of the brick belongs to the neighbours across it too.
  LatticeCache& cache = ws.lattice;
  for (int across = 1; across < 8; ++across)
  {
    LatticeCache::BrickKey other = key;
    std::int64_t* keyOf[3] = { &other.i, &other.j, &other.k };
    int otherLocal = 0;
    bool shared = true;
    for (int axis = 0; axis < 3 && shared; ++axis)
    {
      int m = l[axis];
      if (across & (1 << axis))
      {
        shared = m == 0 || m == cells;
        *keyOf[axis] += m == 0 ? -1 : 1;
        m = m == 0 ? cells : 0;
      }
      otherLocal = otherLocal * side + m;
    }
    if (!shared)
    {
      continue;
    }
    const auto seen = cache.seen.find(other);
    const std::shared_ptr<LatticeCache::Brick> from = seen != cache.seen.end() ? seen->second : cache.table->find(other);
    if (!from)
    {
      continue;
    }
    const std::uint8_t state = from->state[otherLocal].load(std::memory_order_acquire);
    if (LatticeCache::isReady(state))
    {
      std::copy_n(from->data.data() + otherLocal * nodeData, nodeData, data);
      return state;
    }
  }
  // The node's own reach decides its flag, whatever the caller's evaluation had noted so far.
  const bool before = ws.leftCompleteRegion;
  ws.leftCompleteRegion = false;
  const std::int64_t i = key.i * cells + l[0];
  const std::int64_t j = key.j * cells + l[1];
  const std::int64_t k = key.k * cells + l[2];
  // One candidate set for each block of 4 x 4 x 4 nodes, as e_I's quarters have for their nodes.
  constexpr int block = 4;
  const double blockSpan = block * Spacing;
  const auto blockStart = [](std::int64_t n) { return static_cast<double>(n - (n % block + block) % block); };
  const Vec3 blockCentre = (Vec3(blockStart(i), blockStart(j), blockStart(k)) + Vec3::Constant(0.5 * block)) * Spacing;
  focusNeighbourhoods(Field.index(), Field.parameters(), Planar ? Vec3(blockCentre.x(), blockCentre.y(), 0.0) : blockCentre,
    (Planar ? std::sqrt(0.5) : std::sqrt(0.75)) * blockSpan, ws);
  const DeltaHessian d = Field.hessian(Vec3(i * Spacing, j * Spacing, k * Spacing), ws);
  const std::uint8_t state = ws.leftCompleteRegion ? LatticeCache::ReadyFromBeyond : LatticeCache::Ready;
  ws.leftCompleteRegion = before;
  const double s2 = Spacing * Spacing;
  data[0] = d.value;
  data[1] = d.gradient.z() * Spacing;
  data[2] = d.gradient.y() * Spacing;
  data[3] = d.hessian(1, 2) * s2;
  data[4] = d.gradient.x() * Spacing;
  data[5] = d.hessian(0, 2) * s2;
  data[6] = d.hessian(0, 1) * s2;
  data[7] = 0.0;
  return state;
}

template <bool WithDerivatives>
bool DeltaLattice::interpolate(const Vec3& y, Workspace& ws, double& value, Vec3* gradient, Mat3* hessian) const
{
  // Cell indices must fit an int64 with room for the cell's fraction: beyond 2^50 cells from the
  // origin (or at a NaN) the lattice has nothing to offer.
  constexpr double limit = 1125899906842624.0; // 2^50
  const Vec3 u = y / Spacing;
  if (!(std::abs(u.x()) < limit && std::abs(u.y()) < limit && std::abs(u.z()) < limit))
  {
    return false;
  }
  LatticeCache& cache = ws.lattice;
  const SurfaceParameters& params = Field.parameters();
  const std::uint64_t serial = Field.index().serial();
  if (!cache.table || !cache.table->serves(serial, params.h, params.cutoff, Spacing))
  {
    cache.clear();
    cache.table = LatticeTable::of(serial, params.h, params.cutoff, Spacing);
  }
  const std::int64_t ci = static_cast<std::int64_t>(std::floor(u.x()));
  const std::int64_t cj = static_cast<std::int64_t>(std::floor(u.y()));
  const std::int64_t ck = Planar ? 0 : static_cast<std::int64_t>(std::floor(u.z()));
  const HermiteBasis bx(u.x() - static_cast<double>(ci));
  const HermiteBasis by(u.y() - static_cast<double>(cj));
  const HermiteBasis bz(Planar ? 0.0 : u.z() - static_cast<double>(ck));
  constexpr int orders = WithDerivatives ? 3 : 1;
  const int zCorners = Planar ? 1 : 2;
  const LatticeCache::BrickKey key{ brickOf(ci), brickOf(cj), brickOf(ck) };
  LatticeCache::Brick& brick = brickAt(key, ws);
  constexpr int side = LatticeCache::BrickSide;
  constexpr int cells = LatticeCache::BrickCells;
  const int origin = static_cast<int>(((ci - key.i * cells) * side + (cj - key.j * cells)) * side + (ck - key.k * cells));
  for (int cz = 0; cz < zCorners; ++cz)
  {
    for (int corner = 0; corner < 4; ++corner)
    {
      const int local = origin + ((corner >> 1) * side + (corner & 1)) * side + cz;
      std::uint8_t state = brick.state[local].load(std::memory_order_acquire);
      if (!LatticeCache::isReady(state))
      {
        state = readyNode(brick, key, local, ws);
      }
      ws.leftCompleteRegion = ws.leftCompleteRegion || state == LatticeCache::ReadyFromBeyond;
    }
  }
  // The tensor-product sum contracted one axis at a time. A node's data each take the value (V)
  // or slope (D) basis along x, y and z: delta VVV, d/dz VVD, d/dy VDV, d2/dydz VDD take x's
  // value basis, d/dx DVV, d2/dxdz DVD, d2/dxdy DDV its slope basis; the node's two groups of
  // four (LatticeCache::NodeData) line up so that one vector sum along x gives, for x's
  // derivative order a, the parts that take (V, V), (V, D), (D, V), (D, D) along (y, z):
  // X = (A, C, B, E).
  using Array2 = Eigen::Array2d;
  using Array4 = Eigen::Array4d;
  Array4 X[2][2][orders];
  constexpr int nextX = side * side * LatticeCache::NodeData;
  for (int cz = 0; cz < zCorners; ++cz)
  {
    for (int cy = 0; cy < 2; ++cy)
    {
      const double* q = brick.data.data() + (origin + cy * side + cz) * LatticeCache::NodeData;
      const Eigen::Map<const Array4> qV(q), qD(q + 4), rV(q + nextX), rD(q + nextX + 4);
      for (int a = 0; a < orders; ++a)
      {
        X[cz][cy][a] = qV * bx.value[0][a] + qD * bx.slope[0][a] + rV * bx.value[1][a] + rD * bx.slope[1][a];
      }
    }
  }
  // Along y, for orders (a along x, b along y) and each z layer: (P, Q), the parts that take z's
  // value basis and its slope basis ((A, C) take y's value basis, (B, E) its slope basis).
  struct Layers
  {
    Array2 pq[2];
  };
  auto layers = [&](int a, int b) {
    Layers l;
    l.pq[1] = Array2::Zero();
    for (int cz = 0; cz < zCorners; ++cz)
    {
      const Array4& y0 = X[cz][0][a];
      const Array4& y1 = X[cz][1][a];
      l.pq[cz] = y0.template head<2>() * by.value[0][b] + y0.template tail<2>() * by.slope[0][b] +
        y1.template head<2>() * by.value[1][b] + y1.template tail<2>() * by.slope[1][b];
    }
    return l;
  };
  // Along z, for order c of the z basis (in the plane only the z = 0 layer, with its value basis).
  auto term = [&](const Layers& l, int c) {
    if (Planar)
    {
      return c == 0 ? l.pq[0](0) : 0.0;
    }
    return (l.pq[0] * Array2(bz.value[0][c], bz.slope[0][c]) + l.pq[1] * Array2(bz.value[1][c], bz.slope[1][c])).sum();
  };
  const Layers l00 = layers(0, 0);
  value = term(l00, 0);
  if constexpr (WithDerivatives)
  {
    const Layers l10 = layers(1, 0), l01 = layers(0, 1), l20 = layers(2, 0), l02 = layers(0, 2), l11 = layers(1, 1);
    // Cell coordinates to the cloud's: one factor 1 / Spacing per derivative.
    const double inv = 1.0 / Spacing;
    const double inv2 = inv * inv;
    *gradient = Vec3(term(l10, 0), term(l01, 0), term(l00, 1)) * inv;
    const double hxy = term(l11, 0), hxz = term(l10, 1), hyz = term(l01, 1);
    Mat3& H = *hessian;
    H << term(l20, 0), hxy, hxz, hxy, term(l02, 0), hyz, hxz, hyz, term(l00, 2);
    H *= inv2;
  }
  return true;
}

double DeltaLattice::value(const Vec3& y, Workspace& ws) const
{
  double f = 0.0;
  return interpolate<false>(y, ws, f, nullptr, nullptr) ? f : Field.delta(y, ws);
}

DeltaJet DeltaLattice::jet(const Vec3& y, const Vec3& a, Workspace& ws) const
{
  DeltaJet out;
  Mat3 H;
  if (!interpolate<true>(y, ws, out.value, &out.gradient, &H))
  {
    return Field.jet(y, a, ws);
  }
  out.curvature = a.dot(H * a);
  return out;
}

std::vector<std::uint64_t> latticeBrickKeys(
  const std::vector<Vec3>& points, const PointIndex& index, const SurfaceParameters& params)
{
  std::vector<std::uint64_t> keys;
  const double side = LatticeCache::BrickCells * DeltaLattice::spacingFor(index, params);
  if (!(side > 0.0))
  {
    return keys;
  }
  keys.reserve(points.size());
  const bool planar = index.dimension() == 2;
  constexpr std::uint64_t mask = (std::uint64_t{ 1 } << 21) - 1;
  auto coordinate = [&](double x) {
    // Clamped far beyond any cloud (1e15 bricks), so the conversion is defined; then wrapped.
    const double b = std::clamp(std::floor(x / side), -1e15, 1e15);
    return static_cast<std::uint64_t>(static_cast<std::int64_t>(b)) & mask;
  };
  for (const Vec3& p : points)
  {
    if (isFinite(p))
    {
      keys.push_back(coordinate(p.x()) | coordinate(p.y()) << 21 | (planar ? 0 : coordinate(p.z())) << 42);
    }
  }
  std::sort(keys.begin(), keys.end());
  keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
  return keys;
}

bool latticeServes(std::size_t starts, std::size_t bricks)
{
  return static_cast<double>(starts) >= LatticeStartsPerBrick * static_cast<double>(bricks);
}

} // namespace pss
