// SPDX-License-Identifier: BSD-3-Clause
#include "pss/Kernel.h"

#include "pss/Workspace.h"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>

// Run-time dispatch of the vector kernels below (x86-64 with GCC or clang): each is compiled
// twice, for the x86-64 baseline (SSE2) and for AVX2, and the first call picks the AVX2 copy when
// the CPU has it, unless the environment variable PSS_SIMD=baseline forces the baseline copy.
// Both copies compute with vectors of four doubles (two SSE2 registers on the baseline) and no
// fused multiply-add, so they give bitwise the same results; only the speed differs. A build
// for the compiling machine (PSS_NATIVE_ARCH, -march=native) compiles both for that machine.
#if (defined(__x86_64__) || defined(__i386__)) && (defined(__GNUC__) || defined(__clang__))
#define PSS_KERNEL_DISPATCH 1
#include <immintrin.h>
#define PSS_TARGET_AVX2 __attribute__((target("avx2")))
#else
#define PSS_KERNEL_DISPATCH 0
#endif
// The bodies the dispatched functions share: always inlined, so that each copy compiles them for
// its own instruction set (a call to an out-of-line copy would run baseline code).
#define PSS_KERNEL_INLINE inline __attribute__((always_inline))

namespace pss
{

namespace
{
// Doubles per vector on every path: the partial sums, and so every result, do not depend on the
// instruction set chosen.
constexpr int SimdLanes = 4;
} // namespace

void SurfaceParameters::validate() const
{
  if (!(h > 0.0) || !std::isfinite(h))
  {
    throw std::invalid_argument("the scale h must be a positive finite number, got " + std::to_string(h));
  }
  if (!(cutoff > 0.0) || !std::isfinite(cutoff))
  {
    throw std::invalid_argument("the kernel cutoff must be a positive finite number of h, got " + std::to_string(cutoff));
  }
  if (quadratureOrder < 1 || quadratureOrder > 32)
  {
    throw std::invalid_argument(
      "the quadrature order must be in [1, 32], got " + std::to_string(quadratureOrder));
  }
  if (integrandPower != 1 && integrandPower != 2)
  {
    throw std::invalid_argument("the integrand power must be 1 or 2, got " + std::to_string(integrandPower));
  }
  if (!(minStability >= 0.0 && minStability < 1.0))
  {
    throw std::invalid_argument("the minimum stability must be in [0, 1), got " + std::to_string(minStability));
  }
  if (!(deltaLattice == 0.0 || (deltaLattice >= 0.05 && deltaLattice <= 1.0)))
  {
    throw std::invalid_argument(
      "the delta lattice spacing must be 0 (exact) or in [0.05, 1] h, got " + std::to_string(deltaLattice));
  }
}

void Neighbourhood::resize(Eigen::Index n)
{
  // Room for a whole vector past the end: the loops below read and write in whole vectors.
  const Eigen::Index needed = n + SimdLanes;
  if (dx.size() < needed)
  {
    const Eigen::Index capacity = std::max<Eigen::Index>(needed, 2 * dx.size());
    for (Eigen::ArrayXd* a : { &dx, &dy, &dz, &sqDist, &weight })
    {
      a->resize(capacity);
    }
  }
  count = n;
}

namespace
{

// The weighted sums below run over whole vectors of SimdLanes doubles (GCC/Clang vector
// extensions: one AVX register on the AVX2 path, two SSE2 registers on the baseline). Each keeps
// one partial sum per lane and adds the lanes in a fixed order at the end, so a result depends
// only on the neighbours and their order, never on the thread, the call history or the CPU.
// GCC and clang note that returning a 32-byte vector without AVX changes the ABI: these helpers
// are internal and always inlined, so no such value ever crosses a call. (For the rest of this
// file: GCC reports the note at its end.)
#if defined(__clang__)
#if __has_warning("-Wpsabi")
#pragma clang diagnostic ignored "-Wpsabi"
#endif
#elif defined(__GNUC__)
#pragma GCC diagnostic ignored "-Wpsabi"
#endif
typedef double VecD __attribute__((vector_size(8 * SimdLanes)));
typedef std::uint64_t VecU __attribute__((vector_size(8 * SimdLanes)));

PSS_KERNEL_INLINE VecD load(const double* p)
{
  VecD v;
  std::memcpy(&v, p, sizeof v);
  return v;
}

PSS_KERNEL_INLINE void store(double* p, const VecD& v)
{
  std::memcpy(p, &v, sizeof v);
}

PSS_KERNEL_INLINE VecD splat(double x)
{
  return VecD{} + x;
}

PSS_KERNEL_INLINE double lanesSum(const VecD& v)
{
  double s = 0.0;
  for (int k = 0; k < SimdLanes; ++k)
  {
    s += v[k];
  }
  return s;
}

// exp(x) for x <= 0, SimdLanes at a time: x = k ln2 + r with |r| <= ln2 / 2 (ln2 in two parts,
// so k ln2 is exact to double precision), exp(r) by its Taylor series to degree 13 (remainder
// below 1e-17), and 2^k added to the exponent bits. Within one ulp of std::exp on [-708, 0];
// 0 below -708 (where the true value is subnormal: a neighbour weighing less than 1e-307 of the
// nearest one); NaN stays NaN.
PSS_KERNEL_INLINE VecD expNonPositive(const VecD& v)
{
  constexpr double log2e = 1.4426950408889634074;
  constexpr double ln2hi = 6.93147180369123816490e-01;
  constexpr double ln2lo = 1.90821492927058770002e-10;
  constexpr double shifter = 6755399441055744.0; // 1.5 * 2^52: adding it rounds to an integer
  const VecD x = v < -708.0 ? splat(-708.0) : v;
  const VecD t = x * log2e + shifter; // k in the low mantissa bits
  const VecD k = t - shifter;
  const VecD r = (x - k * ln2hi) - k * ln2lo;
  VecD p = r * (1.0 / 6227020800.0) + 1.0 / 479001600.0;
  p = p * r + 1.0 / 39916800.0;
  p = p * r + 1.0 / 3628800.0;
  p = p * r + 1.0 / 362880.0;
  p = p * r + 1.0 / 40320.0;
  p = p * r + 1.0 / 5040.0;
  p = p * r + 1.0 / 720.0;
  p = p * r + 1.0 / 120.0;
  p = p * r + 1.0 / 24.0;
  p = p * r + 1.0 / 6.0;
  p = p * r + 0.5;
  p = p * r + 1.0;
  p = p * r + 1.0;
  // Unsigned, so that a negative k wraps instead of shifting a negative number (undefined).
  VecU bits;
  std::memcpy(&bits, &p, sizeof bits);
  VecU kBits;
  std::memcpy(&kBits, &t, sizeof kBits);
  constexpr std::uint64_t shifterBits = 0x4338000000000000ULL; // the bits of shifter
  bits += (kBits - shifterBits) << 52;
  VecD e;
  std::memcpy(&e, &bits, sizeof e);
  e = v < -708.0 ? VecD{} : e;
  return v != v ? v : e;
}

// Keeps the candidates inside the band (squared distance below @p limit, or equal to the nearest
// one's), in order: writes their offsets and squared distances to @p nb from position 0 on and
// returns how many there are. May write up to four entries past that count (the arrays have
// that room). Candidates from @p i on, n kept so far; branch-free: every candidate is written,
// only the kept ones advance n.
PSS_KERNEL_INLINE Eigen::Index compactTail(const double* px, const double* py, const double* pz, const double* sq,
  Eigen::Index i, Eigen::Index m, Eigen::Index n, const Vec3& origin, double limit, double minSq, Neighbourhood& nb)
{
  for (; i < m; ++i)
  {
    nb.dx[n] = px[i] - origin.x();
    nb.dy[n] = py[i] - origin.y();
    nb.dz[n] = pz[i] - origin.z();
    nb.sqDist[n] = sq[i];
    n += static_cast<Eigen::Index>((sq[i] < limit) | (sq[i] == minSq));
  }
  return n;
}

Eigen::Index compactCandidatesBaseline(const double* px, const double* py, const double* pz, const double* sq,
  Eigen::Index m, const Vec3& origin, double limit, double minSq, Neighbourhood& nb)
{
  return compactTail(px, py, pz, sq, 0, m, 0, origin, limit, minSq, nb);
}

#if PSS_KERNEL_DISPATCH
// The lanes of v picked by perm (pairs of 32-bit indices), in order.
PSS_TARGET_AVX2 inline __m256d moveDownAvx2(__m256d v, __m256i perm)
{
  return _mm256_castps_pd(_mm256_permutevar8x32_ps(_mm256_castpd_ps(v), perm));
}

PSS_TARGET_AVX2 Eigen::Index compactCandidatesAvx2(const double* px, const double* py, const double* pz,
  const double* sq, Eigen::Index m, const Vec3& origin, double limit, double minSq, Neighbourhood& nb)
{
  Eigen::Index n = 0;
  Eigen::Index i = 0;
  // Four candidates at a time: the kept ones are moved to the front of the vector by a permutation
  // chosen from the 4-bit mask, and the whole vector is stored at n.
  static const auto permutations = [] {
    std::array<std::array<std::int32_t, 8>, 16> table{};
    for (int mask = 0; mask < 16; ++mask)
    {
      int slot = 0;
      for (int lane = 0; lane < 4; ++lane)
      {
        if (mask & (1 << lane))
        {
          table[mask][2 * slot] = 2 * lane;
          table[mask][2 * slot + 1] = 2 * lane + 1;
          ++slot;
        }
      }
    }
    return table;
  }();
  const __m256d ox = _mm256_set1_pd(origin.x());
  const __m256d oy = _mm256_set1_pd(origin.y());
  const __m256d oz = _mm256_set1_pd(origin.z());
  const __m256d lim = _mm256_set1_pd(limit);
  const __m256d nearest = _mm256_set1_pd(minSq);
  for (; i + 4 <= m; i += 4)
  {
    const __m256d d = _mm256_loadu_pd(sq + i);
    const __m256d keep =
      _mm256_or_pd(_mm256_cmp_pd(d, lim, _CMP_LT_OQ), _mm256_cmp_pd(d, nearest, _CMP_EQ_OQ));
    const int mask = _mm256_movemask_pd(keep);
    const __m256i perm =
      _mm256_loadu_si256(reinterpret_cast<const __m256i*>(permutations[static_cast<std::size_t>(mask)].data()));
    _mm256_storeu_pd(nb.dx.data() + n, moveDownAvx2(_mm256_sub_pd(_mm256_loadu_pd(px + i), ox), perm));
    _mm256_storeu_pd(nb.dy.data() + n, moveDownAvx2(_mm256_sub_pd(_mm256_loadu_pd(py + i), oy), perm));
    _mm256_storeu_pd(nb.dz.data() + n, moveDownAvx2(_mm256_sub_pd(_mm256_loadu_pd(pz + i), oz), perm));
    _mm256_storeu_pd(nb.sqDist.data() + n, moveDownAvx2(d, perm));
    n += __builtin_popcount(static_cast<unsigned>(mask));
  }
  return compactTail(px, py, pz, sq, i, m, n, origin, limit, minSq, nb);
}
#endif

// Weights w = exp(-(d^2 - minSq) / h^2) of the first @p padded neighbours into @p weight, and
// sums[] = {sum w, sum w dx, sum w dy, sum w dz}.
PSS_KERNEL_INLINE void weightsBody(const double* sqDist, const double* dx, const double* dy, const double* dz,
  double* weight, Eigen::Index padded, double minSq, double invH2, double* sums)
{
  const VecD nearestSq = splat(minSq);
  const VecD scale = splat(-invH2);
  VecD sw{}, sx{}, sy{}, sz{};
  for (Eigen::Index i = 0; i < padded; i += SimdLanes)
  {
    const VecD w = expNonPositive((load(sqDist + i) - nearestSq) * scale);
    store(weight + i, w);
    sw += w;
    sx += w * load(dx + i);
    sy += w * load(dy + i);
    sz += w * load(dz + i);
  }
  sums[0] = lanesSum(sw);
  sums[1] = lanesSum(sx);
  sums[2] = lanesSum(sy);
  sums[3] = lanesSum(sz);
}

PSS_KERNEL_INLINE void expBody(const double* x, double* out, Eigen::Index n)
{
  Eigen::Index i = 0;
  for (; i + SimdLanes <= n; i += SimdLanes)
  {
    store(out + i, expNonPositive(load(x + i)));
  }
  for (; i < n; ++i)
  {
    VecD v{};
    v[0] = x[i];
    out[i] = expNonPositive(v)[0];
  }
}

// sum_i w_i c_i c_i^T with c_i = (dx_i, dy_i, dz_i) - m: s[] = {xx, xy, xz, yy, yz, zz}.
PSS_KERNEL_INLINE void scatterBody(const double* weight, const double* dx, const double* dy, const double* dz,
  Eigen::Index count, double mx0, double my0, double mz0, double* s)
{
  const VecD mx = splat(mx0);
  const VecD my = splat(my0);
  const VecD mz = splat(mz0);
  VecD xx{}, xy{}, xz{}, yy{}, yz{}, zz{};
  for (Eigen::Index i = 0; i < count; i += SimdLanes)
  {
    const VecD w = load(weight + i);
    const VecD cx = load(dx + i) - mx;
    const VecD cy = load(dy + i) - my;
    const VecD cz = load(dz + i) - mz;
    const VecD wx = w * cx;
    const VecD wy = w * cy;
    xx += wx * cx;
    xy += wx * cy;
    xz += wx * cz;
    yy += wy * cy;
    yz += wy * cz;
    zz += w * cz * cz;
  }
  s[0] = lanesSum(xx);
  s[1] = lanesSum(xy);
  s[2] = lanesSum(xz);
  s[3] = lanesSum(yy);
  s[4] = lanesSum(yz);
  s[5] = lanesSum(zz);
}

// sum_i w_i s_i^k (k = 1..4) with s_i = a . (dx_i, dy_i, dz_i).
PSS_KERNEL_INLINE void momentsBody(const double* weight, const double* dx, const double* dy, const double* dz,
  Eigen::Index count, double ax0, double ay0, double az0, double* out)
{
  const VecD ax = splat(ax0);
  const VecD ay = splat(ay0);
  const VecD az = splat(az0);
  VecD m1{}, m2{}, m3{}, m4{};
  for (Eigen::Index i = 0; i < count; i += SimdLanes)
  {
    const VecD s = ax * load(dx + i) + ay * load(dy + i) + az * load(dz + i);
    const VecD ws = load(weight + i) * s;
    const VecD ws2 = ws * s;
    m1 += ws;
    m2 += ws2;
    m3 += ws2 * s;
    m4 += ws2 * (s * s);
  }
  out[0] = lanesSum(m1);
  out[1] = lanesSum(m2);
  out[2] = lanesSum(m3);
  out[3] = lanesSum(m4);
}

// One copy of every kernel per instruction set, and the table of the copy in use.
struct KernelTable
{
  const char* name;
  Eigen::Index (*compact)(const double*, const double*, const double*, const double*, Eigen::Index, const Vec3&,
    double, double, Neighbourhood&);
  void (*weights)(const double*, const double*, const double*, const double*, double*, Eigen::Index, double, double,
    double*);
  void (*exp)(const double*, double*, Eigen::Index);
  void (*scatter)(const double*, const double*, const double*, const double*, Eigen::Index, double, double, double,
    double*);
  void (*moments)(const double*, const double*, const double*, const double*, Eigen::Index, double, double, double,
    double*);
};

#define PSS_KERNEL_COPIES(SUFFIX, TARGET)                                                                        \
  TARGET void weights##SUFFIX(const double* sqDist, const double* dx, const double* dy, const double* dz,          \
    double* weight, Eigen::Index padded, double minSq, double invH2, double* sums)                                \
  {                                                                                                              \
    weightsBody(sqDist, dx, dy, dz, weight, padded, minSq, invH2, sums);                                         \
  }                                                                                                              \
  TARGET void exp##SUFFIX(const double* x, double* out, Eigen::Index n)                                         \
  {                                                                                                              \
    expBody(x, out, n);                                                                                          \
  }                                                                                                              \
  TARGET void scatter##SUFFIX(const double* w, const double* dx, const double* dy, const double* dz,             \
    Eigen::Index count, double mx, double my, double mz, double* s)                                              \
  {                                                                                                              \
    scatterBody(w, dx, dy, dz, count, mx, my, mz, s);                                                            \
  }                                                                                                              \
  TARGET void moments##SUFFIX(const double* w, const double* dx, const double* dy, const double* dz,             \
    Eigen::Index count, double ax, double ay, double az, double* s)                                              \
  {                                                                                                              \
    momentsBody(w, dx, dy, dz, count, ax, ay, az, s);                                                            \
  }

PSS_KERNEL_COPIES(Baseline, )
#if PSS_KERNEL_DISPATCH
PSS_KERNEL_COPIES(Avx2, PSS_TARGET_AVX2)
#endif

const KernelTable& kernels()
{
  static const KernelTable table = [] {
    const KernelTable baseline{ "baseline", compactCandidatesBaseline, weightsBaseline, expBaseline,
      scatterBaseline, momentsBaseline };
#if PSS_KERNEL_DISPATCH
    const KernelTable avx2{ "avx2", compactCandidatesAvx2, weightsAvx2, expAvx2, scatterAvx2, momentsAvx2 };
    const char* forced = std::getenv("PSS_SIMD");
    if (forced && std::strcmp(forced, "baseline") == 0)
    {
      return baseline;
    }
    __builtin_cpu_init();
    if (__builtin_cpu_supports("avx2"))
    {
      return avx2;
    }
#endif
    return baseline;
  }();
  return table;
}

} // namespace

namespace
{

// Sorts words (rank << 32 | index) by rank, ranks below @p bound: a least-significant-digit radix
// sort of 8-bit digits, as many as the bound needs. A few hundred candidates per fetch: a
// comparison sort of them mispredicted half its branches and made the fetch several times slower.
void sortByRank(std::vector<std::uint64_t>& items, std::vector<std::uint64_t>& scratch, std::size_t bound)
{
  int bits = 0;
  while (bits < 32 && (std::uint64_t(bound - 1) >> bits) != 0)
  {
    ++bits;
  }
  scratch.resize(items.size());
  for (int shift = 32; shift < 32 + std::max(bits, 1); shift += 8)
  {
    std::array<std::uint32_t, 257> start{};
    for (const std::uint64_t v : items)
    {
      ++start[((v >> shift) & 0xffu) + 1];
    }
    for (std::size_t d = 1; d < start.size(); ++d)
    {
      start[d] += start[d - 1];
    }
    for (const std::uint64_t v : items)
    {
      scratch[start[(v >> shift) & 0xffu]++] = v;
    }
    items.swap(scratch);
  }
}

} // namespace

// True when every point within sqrt(dmin(y)^2 + band) of y is among the candidates:
// dmin(y) <= centerMinDist + |y - center|, and that ball around y lies in the fetched one.
bool CandidateCache::covers(const PointIndex& index, const SurfaceParameters& params, const Vec3& y, double extra) const
{
  if (!reusable || indexSerial != index.serial() || h != params.h || band != params.cutoff * params.cutoff * h * h)
  {
    return false;
  }
  const double shift = (y - center).norm() + extra;
  const double reach = centerMinDist + shift;
  return std::sqrt(reach * reach + band) + shift <= radius;
}

void CandidateCache::fetch(const PointIndex& index, const SurfaceParameters& params, const Vec3& y,
  PointIndex::LeafRanges& leaves, double minMargin)
{
  indexSerial = index.serial();
  h = params.h;
  band = params.cutoff * params.cutoff * h * h;
  center = y;
  const auto nearest = index.nearest(y);
  centerMinDist = std::sqrt(nearest.second);
  const double margin = std::max({ 0.5 * h, std::min(0.05 * centerMinDist, 2.0 * h), minMargin });
  const double reach = centerMinDist + margin;
  radius = std::sqrt(reach * reach + band) + margin;
  const double sqRadius = radius * radius;
  // The leaves come in index order, so the candidates do too: every later neighbourhood is
  // then independent of where this fetch was made. (The count and the arrays are locals in
  // the loop, which keeps them in registers.)
  Eigen::Index n = 0;
  if (index.coordinateOrder())
  {
    // The same candidates, in the order of their coordinates instead of their indices. Each
    // is sorted as (rank, index) in one word, so that no lookup of the rank's point is needed.
    std::size_t kept = 0;
    index.forEachLeafInBall(y, sqRadius, leaves, [&](std::uint32_t begin, std::uint32_t end) {
      if (ranks.size() < kept + (end - begin))
      {
        ranks.resize(std::max<std::size_t>(kept + (end - begin), 2 * ranks.size()));
      }
      std::uint64_t* out = ranks.data();
      for (std::uint32_t i = begin; i < end; ++i)
      {
        out[kept] = std::uint64_t(index.coordinateRank(i)) << 32 | i;
        kept += (index.point(i) - y).squaredNorm() < sqRadius ? 1 : 0;
      }
    });
    ranks.resize(kept);
    sortByRank(ranks, rankScratch, index.size());
    n = static_cast<Eigen::Index>(ranks.size());
    reserve(n);
    for (Eigen::Index k = 0; k < n; ++k)
    {
      const Vec3& p = index.point(static_cast<std::uint32_t>(ranks[static_cast<std::size_t>(k)]));
      px[k] = p.x();
      py[k] = p.y();
      pz[k] = p.z();
    }
  }
  else
  {
    index.forEachLeafInBall(y, sqRadius, leaves, [&](std::uint32_t begin, std::uint32_t end) {
      reserve(n + (end - begin));
      double* x = px.data();
      double* yy = py.data();
      double* z = pz.data();
      for (std::uint32_t i = begin; i < end; ++i)
      {
        const Vec3& p = index.point(i);
        x[n] = p.x();
        yy[n] = p.y();
        z[n] = p.z();
        n += (p - y).squaredNorm() < sqRadius ? 1 : 0;
      }
    });
  }
  count = n;
  // The ball holds every point within radius only while the squared distances are finite.
  reusable = count > 0 && std::isfinite(sqRadius);
  if (count == 0)
  {
    // Only when the radius rounds below the nearest distance (absurd scale ratios, or squared
    // distances beyond double's range). Such candidates are good for this query alone: reusing
    // them for the next one made results depend on which query came first (found by
    // tests/fuzz/FuzzCore.cxx: 1 vs 2 threads differed for a start 1e300 from the cloud).
    reserve(1);
    const Vec3& p = index.point(nearest.first);
    px[0] = p.x();
    py[0] = p.y();
    pz[0] = p.z();
    count = 1;
  }
}

Eigen::VectorBlock<Eigen::ArrayXd> CandidateCache::squaredDistances(const Vec3& y, Eigen::ArrayXd& out) const
{
  if (out.size() < count)
  {
    out.resize(count);
  }
  auto sq = out.head(count);
  sq = (px.head(count) - y.x()).square() + (py.head(count) - y.y()).square() + (pz.head(count) - y.z()).square();
  return sq;
}

// The same guarantee as a fetch at c with margin reach, from a scan of wider's candidates
// instead of a k-d tree query.
void CandidateCache::focus(const CandidateCache& wider, const Vec3& c, double reach, Eigen::ArrayXd& sq)
{
  indexSerial = wider.indexSerial;
  h = wider.h;
  band = wider.band;
  center = c;
  const Eigen::Index m = wider.count;
  centerMinDist = std::sqrt(wider.squaredDistances(c, sq).minCoeff());
  const double outer = centerMinDist + reach;
  radius = std::sqrt(outer * outer + band) + reach;
  const double sqRadius = radius * radius;
  reserve(m);
  const double* wx = wider.px.data();
  const double* wy = wider.py.data();
  const double* wz = wider.pz.data();
  const double* ds = sq.data();
  double* x = px.data();
  double* y = py.data();
  double* z = pz.data();
  Eigen::Index n = 0;
  for (Eigen::Index i = 0; i < m; ++i)
  {
    x[n] = wx[i];
    y[n] = wy[i];
    z[n] = wz[i];
    n += ds[i] < sqRadius ? 1 : 0;
  }
  count = n;
  reusable = wider.reusable && n > 0 && std::isfinite(sqRadius);
}

void CandidateCache::reserve(Eigen::Index n)
{
  if (px.size() < n)
  {
    const Eigen::Index capacity = std::max<Eigen::Index>(n, 2 * px.size());
    px.conservativeResize(capacity);
    py.conservativeResize(capacity);
    pz.conservativeResize(capacity);
  }
}

void prefetchNeighbourhoods(
  const PointIndex& index, const SurfaceParameters& params, const Vec3& center, double reach, Workspace& ws)
{
  const Vec3 c = index.restrict(center);
  if (!ws.wide.covers(index, params, c, reach))
  {
    // Half an h of slack beyond the reach asked for, so that nearby centres (the steps of a
    // projection, the samples of a line search) reuse the same fetch.
    ws.wide.fetch(index, params, c, ws.leaves, reach + 0.5 * params.h);
  }
}

void focusNeighbourhoods(
  const PointIndex& index, const SurfaceParameters& params, const Vec3& center, double reach, Workspace& ws)
{
  const Vec3 c = index.restrict(center);
  if (ws.focused.covers(index, params, c, reach))
  {
    return;
  }
  prefetchNeighbourhoods(index, params, c, reach, ws);
  ws.focused.focus(ws.wide, c, reach, ws.focusSq);
}

void noteReach(const PointIndex& index, const Vec3& y, double sqRadius, Workspace& ws)
{
  if (!index.holdsBall(y, std::sqrt(sqRadius)))
  {
    ws.leftCompleteRegion = true;
  }
}

void gatherNeighbourhood(
  const PointIndex& index, const SurfaceParameters& params, const Vec3& y, Neighbourhood& nb, Workspace& ws)
{
  const Vec3 origin = index.restrict(y);
  if (nb.indexSerial == index.serial() && nb.h == params.h && nb.cutoff == params.cutoff && nb.origin == origin)
  {
    noteReach(index, origin, nb.minSqDist + params.cutoff * params.cutoff * params.h * params.h, ws);
    return;
  }
  nb.indexSerial = 0; // until the new contents are complete
  nb.origin = origin;
  nb.invH2 = 1.0 / (params.h * params.h);
  // Either cache holds, in index order, every point the neighbourhood can need, so which one
  // serves the query does not change a bit of the result.
  const bool focused = ws.focused.covers(index, params, nb.origin);
  CandidateCache& cache = focused ? ws.focused : ws.wide;
  if (!focused && !cache.covers(index, params, nb.origin))
  {
    cache.fetch(index, params, nb.origin, ws.leaves);
  }
  const Eigen::Index m = cache.count;
  // Offsets are p - y from absolute coordinates: for large coordinates this subtraction is the
  // only place digits can go, and it is exact to one rounding whatever the cache centre was.
  const auto sq = cache.squaredDistances(nb.origin, ws.candidateSq);
  const double minSq = sq.minCoeff();
  nb.resize(m);
  const Eigen::Index n = kernels().compact(cache.px.data(), cache.py.data(), cache.pz.data(), sq.data(), m,
    nb.origin, minSq + cache.band, minSq, nb);
  nb.count = n;
  nb.minSqDist = minSq;
  noteReach(index, origin, minSq + cache.band, ws);
  // The last vector is padded with neighbours of weight 0 at offset 0, which add nothing.
  const Eigen::Index padded = (n + SimdLanes - 1) / SimdLanes * SimdLanes;
  for (Eigen::Index i = n; i < padded; ++i)
  {
    nb.dx[i] = nb.dy[i] = nb.dz[i] = 0.0;
    nb.sqDist[i] = std::numeric_limits<double>::infinity();
  }
  // Weights, their sum and the first moments in one pass.
  double sums[4];
  kernels().weights(nb.sqDist.data(), nb.dx.data(), nb.dy.data(), nb.dz.data(), nb.weight.data(), padded, minSq,
    nb.invH2, sums);
  nb.weightSum = sums[0];
  nb.moment = Vec3(sums[1], sums[2], sums[3]);
  nb.indexSerial = index.serial();
  nb.h = params.h;
  nb.cutoff = params.cutoff;
}

void expNonPositive(const double* x, double* out, Eigen::Index n)
{
  kernels().exp(x, out, n);
}

const char* kernelInstructionSet()
{
  return kernels().name;
}

Vec3 centroidOffset(const Neighbourhood& nb)
{
  return nb.moment / nb.weightSum;
}

// sum_i w_i (p_i - y - m)(p_i - y - m)^T: the six distinct entries in one pass over the
// neighbours (the padding after the last one weighs 0).
Mat3 weightedScatter(const Neighbourhood& nb, const Vec3& m)
{
  double s[6];
  kernels().scatter(nb.weight.data(), nb.dx.data(), nb.dy.data(), nb.dz.data(), nb.count, m.x(), m.y(), m.z(), s);
  Mat3 c;
  c(0, 0) = s[0];
  c(1, 1) = s[3];
  c(2, 2) = s[5];
  c(0, 1) = c(1, 0) = s[1];
  c(0, 2) = c(2, 0) = s[2];
  c(1, 2) = c(2, 1) = s[4];
  return c;
}

LineMoments lineMoments(const Neighbourhood& nb, const Vec3& a)
{
  double s[4];
  kernels().moments(nb.weight.data(), nb.dx.data(), nb.dy.data(), nb.dz.data(), nb.count, a.x(), a.y(), a.z(), s);
  LineMoments out;
  out.s1 = s[0];
  out.s2 = s[1];
  out.s3 = s[2];
  out.s4 = s[3];
  return out;
}

Mat3 covarianceAboutQuery(const Neighbourhood& nb)
{
  return weightedScatter(nb, Vec3::Zero());
}

Mat3 covarianceAboutCentroid(const Neighbourhood& nb)
{
  // Two passes: far from the cloud the offsets are large and nearly equal, and the one-pass
  // form E[r r^T] - m m^T would cancel away the digits that matter.
  return weightedScatter(nb, centroidOffset(nb)) / nb.weightSum;
}

namespace
{

// Eigenvalues and eigenvectors (columns, eigenvalues ascending) of a symmetric matrix, or of its
// leading 2x2 block in 2D, by Eigen's QR iteration.
void eigenFromScratch(const Mat3& C, int dimension, Vec3& values, Mat3& vectors)
{
  vectors.setIdentity();
  values.setZero();
  if (dimension == 2)
  {
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> solver(C.topLeftCorner<2, 2>());
    vectors.topLeftCorner<2, 2>() = solver.eigenvectors();
    values.head<2>() = solver.eigenvalues();
  }
  else
  {
    Eigen::SelfAdjointEigenSolver<Mat3> solver(C);
    vectors = solver.eigenvectors();
    values = solver.eigenvalues();
  }
}

// The same from the eigenvectors of a nearby matrix (the previous iterate's), by cyclic Jacobi
// rotations of vectors^T C vectors: that matrix is nearly diagonal, and Jacobi's convergence is
// quadratic, so a few sweeps finish it. Returns false (and leaves the outputs to be
// recomputed) if it has not converged after a few sweeps.
bool eigenFromNearby(const Mat3& C, int dimension, Vec3& values, Mat3& vectors)
{
  const double scale = C.cwiseAbs().maxCoeff();
  if (!(scale > 0.0))
  {
    return false;
  }
  // Scaled to a largest entry of 1, so that no intermediate over- or underflows.
  Mat3 a = vectors.transpose() * (C / scale) * vectors;
  if (dimension == 2)
  {
    a.row(2).setZero();
    a.col(2).setZero();
  }
  double d[3] = { a(0, 0), a(1, 1), a(2, 2) };
  double off[3] = { a(0, 1), a(0, 2), a(1, 2) }; // (p, q) = (0, 1), (0, 2), (1, 2)
  constexpr int pairs[3][2] = { { 0, 1 }, { 0, 2 }, { 1, 2 } }; // (p, q)
  // off[] index of the entries (r, p) and (r, q), r the third index, for each pair.
  constexpr int others[3][2] = { { 1, 2 }, { 0, 2 }, { 0, 1 } };
  const int rotations = dimension == 2 ? 1 : 3;
  for (int sweep = 0; sweep < 8; ++sweep)
  {
    bool rotated = false;
    for (int k = 0; k < rotations; ++k)
    {
      const int p = pairs[k][0];
      const int q = pairs[k][1];
      const double apq = off[k];
      // An entry below the rounding of its diagonal neighbours changes nothing (the criterion
      // that keeps the small eigenvalues' relative accuracy).
      constexpr double eps = std::numeric_limits<double>::epsilon();
      if (!(apq * apq > eps * eps * std::abs(d[p] * d[q])))
      {
        continue;
      }
      rotated = true;
      // The rotation that zeroes a(p, q): theta = (a_qq - a_pp) / (2 a_pq), t = tan of the angle
      // (the smaller root), then the updates of Rutishauser's formulation. The last sweeps turn
      // by tiny angles, where t = 1 / (2 theta) and c = 1 - t^2 / 2 are exact to rounding.
      const double theta = (d[q] - d[p]) / (2.0 * apq);
      double t = 0.0;
      double c = 0.0;
      if (std::abs(theta) > 1e8)
      {
        t = 0.5 / theta;
        c = 1.0 - 0.5 * t * t;
      }
      else
      {
        t = std::copysign(1.0, theta) / (std::abs(theta) + std::sqrt(theta * theta + 1.0));
        c = 1.0 / std::sqrt(t * t + 1.0);
      }
      const double sn = t * c;
      d[p] -= t * apq;
      d[q] += t * apq;
      off[k] = 0.0;
      double& arp = off[others[k][0]];
      double& arq = off[others[k][1]];
      const double rp = arp;
      const double rq = arq;
      arp = c * rp - sn * rq;
      arq = sn * rp + c * rq;
      const Vec3 vp = vectors.col(p);
      const Vec3 vq = vectors.col(q);
      vectors.col(p) = c * vp - sn * vq;
      vectors.col(q) = sn * vp + c * vq;
    }
    if (!rotated)
    {
      // Ascending order of the eigenvalues (in 2D the third stays last).
      int order[3] = { 0, 1, 2 };
      auto ascending = [&](int i, int j) {
        if (d[order[j]] < d[order[i]])
        {
          std::swap(order[i], order[j]);
        }
      };
      ascending(0, 1);
      if (dimension != 2)
      {
        ascending(1, 2);
        ascending(0, 1);
      }
      const Mat3 unsorted = vectors;
      for (int k = 0; k < 3; ++k)
      {
        values[k] = scale * d[order[k]];
        vectors.col(k) = unsorted.col(order[k]);
      }
      if (dimension == 2)
      {
        values[2] = 0.0;
      }
      return true;
    }
  }
  return false;
}

} // namespace

Direction smallestEigenDirection(const Mat3& C, int dimension, double minStability, EigenFrame* frame)
{
  Direction out;
  if (!C.allFinite())
  {
    return out;
  }
  Vec3 values;
  Mat3 vectors;
  if (frame && frame->valid)
  {
    vectors = frame->vectors;
    if (!eigenFromNearby(C, dimension, values, vectors))
    {
      eigenFromScratch(C, dimension, values, vectors);
    }
  }
  else
  {
    eigenFromScratch(C, dimension, values, vectors);
  }
  if (frame)
  {
    frame->vectors = vectors;
    frame->valid = vectors.allFinite();
  }
  out.n = vectors.col(0);
  double l0 = values[0];
  double l1 = values[1];
  const double lmax = dimension == 2 ? values[1] : values[2];
  // Eigenvalues within rounding of zero are zero: a rank-deficient matrix (all weight on one
  // point, or a collinear neighbourhood in 3D) has no unique smallest direction.
  const double floor = 64.0 * std::numeric_limits<double>::epsilon() * std::abs(lmax);
  l0 = l0 > floor ? l0 : 0.0;
  l1 = l1 > floor ? l1 : 0.0;
  out.stability = (l1 + l0) > 0.0 ? (l1 - l0) / (l1 + l0) : 0.0;
  out.n.normalize();
  out.defined = out.stability > minStability && out.n.allFinite();
  return out;
}

double approximateSqDistance(const Neighbourhood& nb)
{
  return (nb.w() * nb.d2()).sum() / nb.weightSum;
}

namespace
{

// What delta's jet and Hessian share (approximateSqDistanceJet's formulas): delta, the weighted
// mean offset m, T = sum theta_N (d_i^2 - delta) r_i, and grad delta.
struct DeltaFirstOrder
{
  double value = 0.0;
  Vec3 m = Vec3::Zero();
  Vec3 t = Vec3::Zero();
  Vec3 gradient = Vec3::Zero();
};

DeltaFirstOrder deltaFirstOrder(const Neighbourhood& nb)
{
  const auto w = nb.w();
  const double weightSum = nb.weightSum;
  DeltaFirstOrder out;
  out.value = (w * nb.d2()).sum() / weightSum;
  const auto spread = w * (nb.d2() - out.value);
  out.m = Vec3((w * nb.x()).sum(), (w * nb.y()).sum(), (w * nb.z()).sum()) / weightSum;
  out.t = Vec3((spread * nb.x()).sum(), (spread * nb.y()).sum(), (spread * nb.z()).sum()) / weightSum;
  out.gradient = -2.0 * out.m + 2.0 * nb.invH2 * out.t;
  return out;
}

} // namespace

DeltaJet approximateSqDistanceJet(const Neighbourhood& nb, const Vec3& a)
{
  const auto w = nb.w();
  const double weightSum = nb.weightSum;
  const DeltaFirstOrder first = deltaFirstOrder(nb);
  DeltaJet out;
  out.value = first.value;
  out.gradient = first.gradient;
  const Vec3& m = first.m;
  const Vec3& t = first.t;
  const auto spread = w * (nb.d2() - out.value);
  const auto along = a.x() * nb.x() + a.y() * nb.y() + a.z() * nb.z(); // <a, r_i>
  const double k = nb.invH2;
  const double am = a.dot(m);
  const double alongCovariance = (w * along.square()).sum() / weightSum - am * am;
  const double alongSpread = (spread * along.square()).sum() / weightSum;
  out.curvature = 2.0 - 8.0 * k * alongCovariance + 4.0 * k * k * (alongSpread - 2.0 * a.dot(t) * am);
  return out;
}

DeltaHessian approximateSqDistanceHessian(const Neighbourhood& nb)
{
  const auto w = nb.w();
  const double weightSum = nb.weightSum;
  const DeltaFirstOrder first = deltaFirstOrder(nb);
  DeltaHessian out;
  out.value = first.value;
  out.gradient = first.gradient;
  const Vec3& m = first.m;
  const Vec3& t = first.t;
  const auto spread = w * (nb.d2() - out.value);
  const double k = nb.invH2;
  // Second moments about y, weighted by w and by the spread, one entry of the upper triangle at a time.
  Mat3 second, spreadSecond;
  const std::array<decltype(nb.x()), 3> r{ nb.x(), nb.y(), nb.z() };
  for (int i = 0; i < 3; ++i)
  {
    for (int j = i; j < 3; ++j)
    {
      const auto rr = r[i] * r[j];
      second(i, j) = second(j, i) = (w * rr).sum() / weightSum;
      spreadSecond(i, j) = spreadSecond(j, i) = (spread * rr).sum() / weightSum;
    }
  }
  const Mat3 covariance = second - m * m.transpose();
  out.hessian = 2.0 * Mat3::Identity() - 8.0 * k * covariance +
    4.0 * k * k * (spreadSecond - t * m.transpose() - m * t.transpose());
  return out;
}

DistanceField::DistanceField(const PointIndex& index, const SurfaceParameters& params)
  : Index(index)
  , Params(params)
{
  Params.validate();
  if (Index.empty())
  {
    throw std::invalid_argument("the point cloud is empty (no finite points)");
  }
}

double DistanceField::delta(const Vec3& y, Workspace& ws) const
{
  Neighbourhood& nb = ws.field;
  gatherNeighbourhood(Index, Params, y, nb, ws);
  return approximateSqDistance(nb);
}

DeltaJet DistanceField::jet(const Vec3& y, const Vec3& a, Workspace& ws, double* nearestSqDist) const
{
  Neighbourhood& nb = ws.field;
  gatherNeighbourhood(Index, Params, y, nb, ws);
  if (nearestSqDist)
  {
    *nearestSqDist = nb.minSqDist;
  }
  return approximateSqDistanceJet(nb, a);
}

DeltaHessian DistanceField::hessian(const Vec3& y, Workspace& ws) const
{
  Neighbourhood& nb = ws.field;
  gatherNeighbourhood(Index, Params, y, nb, ws);
  return approximateSqDistanceHessian(nb);
}

} // namespace pss
