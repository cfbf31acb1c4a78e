// SPDX-License-Identifier: BSD-3-Clause
#include "pss/KernelDispatch.h"

#include <array>
#include <cstdint>
#include <cstdlib>
#include <cstring>

// Run-time dispatch of the vector kernels below (x86-64 with GCC or clang): each is compiled
// twice, for the x86-64 baseline (SSE2) and for AVX2, and the first call picks the AVX2 copy when
// the CPU has it, unless the environment variable PSS_SIMD=baseline forces the baseline copy.
// Both copies compute with vectors of four doubles (two SSE2 registers on the baseline) and no
// fused multiply-add, so they give bitwise the same results; only the speed differs. A build
// for the compiling machine (PSS_NATIVE_ARCH, -march=native) compiles both for that machine. The
// core's copy for x86-64-v3 (PSS_CORE_COPY_X86_64_V3) has no dispatch: one copy, with FMA.
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
namespace dispatch
{

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

// Each vector's lanes summed into out[0], out[1], ... in order: a kernel's totals.
template <class... Vectors>
PSS_KERNEL_INLINE void storeLaneSums(double* out, const Vectors&... v)
{
  int j = 0;
  ((out[j++] = lanesSum(v)), ...);
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

// The normals of candidate i, when the candidates carry them (Normals), to nb's slot n.
template <bool Normals>
PSS_KERNEL_INLINE void copyNormal(const Candidates& c, Eigen::Index i, Eigen::Index n, Neighbourhood& nb)
{
  if constexpr (Normals)
  {
    nb.nx[n] = c.nx[i];
    nb.ny[n] = c.ny[i];
    nb.nz[n] = c.nz[i];
  }
}

// Keeps the candidates inside the band (squared distance below @p limit, or equal to the nearest
// one's), in order: writes their offsets, squared distances and (Normals) normals to @p nb from
// position 0 on and returns how many there are. May write up to four entries past that count (the
// arrays have that room). Candidates from @p i on, n kept so far; branch-free: every candidate is
// written, only the kept ones advance n.
template <bool Normals>
PSS_KERNEL_INLINE Eigen::Index compactTail(const Candidates& c, Eigen::Index i, Eigen::Index n, const Vec3& origin,
  double limit, double minSq, Neighbourhood& nb)
{
  for (; i < c.count; ++i)
  {
    nb.dx[n] = c.px[i] - origin.x();
    nb.dy[n] = c.py[i] - origin.y();
    nb.dz[n] = c.pz[i] - origin.z();
    nb.sqDist[n] = c.sq[i];
    copyNormal<Normals>(c, i, n, nb);
    n += static_cast<Eigen::Index>((c.sq[i] < limit) | (c.sq[i] == minSq));
  }
  return n;
}

#if !defined(PSS_CORE_COPY_X86_64_V3)
Eigen::Index compactCandidatesBaseline(
  const Candidates& c, const Vec3& origin, double limit, double minSq, Neighbourhood& nb)
{
  return c.nx ? compactTail<true>(c, 0, 0, origin, limit, minSq, nb)
              : compactTail<false>(c, 0, 0, origin, limit, minSq, nb);
}
#endif

// The scaled candidates below @p bound (scaled squared distances), in order: their offsets,
// squared distances, 1/h_i^2, h_i, (Normals) normals, and in weight the exponent minScaled -
// scaled (<= 0) that expNonPositive turns into the weight. Candidates from @p i on, n kept so
// far; branch-free as compactTail.
template <bool Normals>
PSS_KERNEL_INLINE Eigen::Index compactScaledTail(const ScaledCandidates& c, Eigen::Index i, Eigen::Index n,
  const Vec3& origin, double bound, double minScaled, Neighbourhood& nb)
{
  for (; i < c.count; ++i)
  {
    nb.dx[n] = c.px[i] - origin.x();
    nb.dy[n] = c.py[i] - origin.y();
    nb.dz[n] = c.pz[i] - origin.z();
    nb.sqDist[n] = c.sq[i];
    nb.inverseSqScale[n] = c.pk[i];
    nb.pointScale[n] = c.ph[i];
    nb.weight[n] = minScaled - c.scaledSq[i];
    copyNormal<Normals>(c, i, n, nb);
    n += static_cast<Eigen::Index>(c.scaledSq[i] < bound);
  }
  return n;
}

#if !defined(PSS_CORE_COPY_X86_64_V3)
Eigen::Index compactScaledBaseline(
  const ScaledCandidates& c, const Vec3& origin, double bound, double minScaled, Neighbourhood& nb)
{
  return c.nx ? compactScaledTail<true>(c, 0, 0, origin, bound, minScaled, nb)
              : compactScaledTail<false>(c, 0, 0, origin, bound, minScaled, nb);
}
#endif

#if PSS_KERNEL_DISPATCH
// For each 4-bit mask of kept lanes, the permutation (pairs of 32-bit indices) that moves them to
// the front in order.
const std::array<std::array<std::int32_t, 8>, 16>& compactPermutations()
{
  static const auto table = [] {
    std::array<std::array<std::int32_t, 8>, 16> t{};
    for (int mask = 0; mask < 16; ++mask)
    {
      int slot = 0;
      for (int lane = 0; lane < 4; ++lane)
      {
        if (mask & (1 << lane))
        {
          t[mask][2 * slot] = 2 * lane;
          t[mask][2 * slot + 1] = 2 * lane + 1;
          ++slot;
        }
      }
    }
    return t;
  }();
  return table;
}

// The lanes of v picked by perm (pairs of 32-bit indices), in order.
PSS_TARGET_AVX2 inline __m256d moveDownAvx2(__m256d v, __m256i perm)
{
  return _mm256_castps_pd(_mm256_permutevar8x32_ps(_mm256_castpd_ps(v), perm));
}

// The arrays a compaction reads and writes, as local pointers: stores through double* may alias
// the Candidates and Neighbourhood members that hold them, so reading them from there in the loop
// reloaded every pointer after every store (a fifth of the loop's time, by perf annotate).
template <int Count>
struct CompactionArrays
{
  const double* source[Count];
  double* target[Count];
};

// Stores the lanes of each source from @p i on that perm picks, at each target + n; the first
// three minus the origin's coordinates (the offsets).
template <int Count>
PSS_TARGET_AVX2 inline void storeKeptAvx2(
  const CompactionArrays<Count>& a, const __m256d* origin, Eigen::Index i, Eigen::Index n, __m256i perm)
{
#pragma GCC unroll 16
  for (int k = 0; k < Count; ++k)
  {
    __m256d v = _mm256_loadu_pd(a.source[k] + i);
    if (k < 3)
    {
      v = _mm256_sub_pd(v, origin[k]);
    }
    _mm256_storeu_pd(a.target[k] + n, moveDownAvx2(v, perm));
  }
}

// How many arrays a compaction moves: offsets and squared distances, (Normals) the normals and
// (Scaled) 1 / h_i^2 and h_i.
template <bool Normals, bool Scaled>
constexpr int CompactedArrays = 4 + (Normals ? 3 : 0) + (Scaled ? 2 : 0);

template <bool Normals, bool Scaled>
CompactionArrays<CompactedArrays<Normals, Scaled>> compactionArrays(
  const Candidates& c, const double* pk, const double* ph, Neighbourhood& nb)
{
  CompactionArrays<CompactedArrays<Normals, Scaled>> a{};
  int k = 0;
  auto add = [&](const double* source, double* target) {
    a.source[k] = source;
    a.target[k++] = target;
  };
  add(c.px, nb.dx.data());
  add(c.py, nb.dy.data());
  add(c.pz, nb.dz.data());
  add(c.sq, nb.sqDist.data());
  if constexpr (Normals)
  {
    add(c.nx, nb.nx.data());
    add(c.ny, nb.ny.data());
    add(c.nz, nb.nz.data());
  }
  if constexpr (Scaled)
  {
    add(pk, nb.inverseSqScale.data());
    add(ph, nb.pointScale.data());
  }
  return a;
}

// Four candidates at a time: the kept ones are moved to the front of the vector by a permutation
// chosen from the 4-bit mask, and the whole vector is stored at n.
template <bool Normals>
PSS_TARGET_AVX2 Eigen::Index compactAvx2(
  const Candidates& c, const Vec3& origin, double limit, double minSq, Neighbourhood& nb)
{
  Eigen::Index n = 0;
  Eigen::Index i = 0;
  const auto& permutations = compactPermutations();
  const __m256d o[3] = { _mm256_set1_pd(origin.x()), _mm256_set1_pd(origin.y()), _mm256_set1_pd(origin.z()) };
  const __m256d lim = _mm256_set1_pd(limit);
  const __m256d nearest = _mm256_set1_pd(minSq);
  const auto arrays = compactionArrays<Normals, false>(c, nullptr, nullptr, nb);
  const double* const sq = c.sq;
  const Eigen::Index count = c.count;
  for (; i + 4 <= count; i += 4)
  {
    const __m256d d = _mm256_loadu_pd(sq + i);
    const __m256d keep =
      _mm256_or_pd(_mm256_cmp_pd(d, lim, _CMP_LT_OQ), _mm256_cmp_pd(d, nearest, _CMP_EQ_OQ));
    const int mask = _mm256_movemask_pd(keep);
    const __m256i perm =
      _mm256_loadu_si256(reinterpret_cast<const __m256i*>(permutations[static_cast<std::size_t>(mask)].data()));
    storeKeptAvx2(arrays, o, i, n, perm);
    n += __builtin_popcount(static_cast<unsigned>(mask));
  }
  return compactTail<Normals>(c, i, n, origin, limit, minSq, nb);
}

PSS_TARGET_AVX2 Eigen::Index compactCandidatesAvx2(
  const Candidates& c, const Vec3& origin, double limit, double minSq, Neighbourhood& nb)
{
  return c.nx ? compactAvx2<true>(c, origin, limit, minSq, nb) : compactAvx2<false>(c, origin, limit, minSq, nb);
}

template <bool Normals>
PSS_TARGET_AVX2 Eigen::Index compactScaledAvx2(
  const ScaledCandidates& c, const Vec3& origin, double bound, double minScaled, Neighbourhood& nb)
{
  const auto& permutations = compactPermutations();
  const __m256d o[3] = { _mm256_set1_pd(origin.x()), _mm256_set1_pd(origin.y()), _mm256_set1_pd(origin.z()) };
  const __m256d lim = _mm256_set1_pd(bound);
  const __m256d least = _mm256_set1_pd(minScaled);
  const auto arrays = compactionArrays<Normals, true>(c, c.pk, c.ph, nb);
  const double* const scaledSq = c.scaledSq;
  double* const exponent = nb.weight.data();
  const Eigen::Index count = c.count;
  Eigen::Index n = 0;
  Eigen::Index i = 0;
  for (; i + 4 <= count; i += 4)
  {
    const __m256d s = _mm256_loadu_pd(scaledSq + i);
    const int mask = _mm256_movemask_pd(_mm256_cmp_pd(s, lim, _CMP_LT_OQ));
    const __m256i perm =
      _mm256_loadu_si256(reinterpret_cast<const __m256i*>(permutations[static_cast<std::size_t>(mask)].data()));
    storeKeptAvx2(arrays, o, i, n, perm);
    _mm256_storeu_pd(exponent + n, moveDownAvx2(_mm256_sub_pd(least, s), perm));
    n += __builtin_popcount(static_cast<unsigned>(mask));
  }
  return compactScaledTail<Normals>(c, i, n, origin, bound, minScaled, nb);
}

PSS_TARGET_AVX2 Eigen::Index compactScaledCandidatesAvx2(
  const ScaledCandidates& c, const Vec3& origin, double bound, double minScaled, Neighbourhood& nb)
{
  return c.nx ? compactScaledAvx2<true>(c, origin, bound, minScaled, nb)
              : compactScaledAvx2<false>(c, origin, bound, minScaled, nb);
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
  storeLaneSums(sums, sw, sx, sy, sz);
}

// The same with a scale per point: @p weight holds the exponents on entry (compactScaled's
// minScaled - |p - y|^2 / h_i^2, -inf in the padding) and the weights on return;
// sums[] = {sum w, sum w dx, sum w dy, sum w dz, sum w h_i}.
PSS_KERNEL_INLINE void scaledWeightsBody(const double* dx, const double* dy, const double* dz, const double* pointScale,
  double* weight, Eigen::Index padded, double* sums)
{
  VecD sw{}, sx{}, sy{}, sz{}, sh{};
  for (Eigen::Index i = 0; i < padded; i += SimdLanes)
  {
    const VecD w = expNonPositive(load(weight + i));
    store(weight + i, w);
    sw += w;
    sx += w * load(dx + i);
    sy += w * load(dy + i);
    sz += w * load(dz + i);
    sh += w * load(pointScale + i);
  }
  storeLaneSums(sums, sw, sx, sy, sz, sh);
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
  storeLaneSums(s, xx, xy, xz, yy, yz, zz);
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
  storeLaneSums(out, m1, m2, m3, m4);
}

// The sums of the algebraic sphere's fit: out[] = {sum w n_x, sum w n_y, sum w n_z, sum w r . n,
// sum w |r|^2} with r = (dx, dy, dz) (the padding's zero offsets and normals add nothing).
PSS_KERNEL_INLINE void orientedMomentsBody(const double* weight, const double* dx, const double* dy, const double* dz,
  const double* nx, const double* ny, const double* nz, Eigen::Index count, double* out)
{
  VecD sx{}, sy{}, sz{}, rn{}, rr{};
  for (Eigen::Index i = 0; i < count; i += SimdLanes)
  {
    const VecD w = load(weight + i);
    const VecD x = load(dx + i);
    const VecD y = load(dy + i);
    const VecD z = load(dz + i);
    const VecD wx = w * load(nx + i);
    const VecD wy = w * load(ny + i);
    const VecD wz = w * load(nz + i);
    sx += wx;
    sy += wy;
    sz += wz;
    rn += wx * x + wy * y + wz * z;
    rr += w * (x * x + y * y + z * z);
  }
  storeLaneSums(out, sx, sy, sz, rn, rr);
}

// RIMLS's robust factors (its refits): robust[i] = exp(min(0, -(f_i - f)^2 rf - |n_i - g|^2 nf)) with
// f_i = -(r_i . n_i), over whole vectors (the padding's values are finite and weigh 0).
PSS_KERNEL_INLINE void robustFactorsBody(const double* dx, const double* dy, const double* dz, const double* nx,
  const double* ny, const double* nz, Eigen::Index count, const double* fit, double* robust)
{
  const VecD f = splat(fit[0]);
  const VecD gx = splat(fit[1]);
  const VecD gy = splat(fit[2]);
  const VecD gz = splat(fit[3]);
  const VecD gg = splat(fit[4]);
  const VecD rf = splat(fit[5]);
  const VecD nf = splat(fit[6]);
  for (Eigen::Index i = 0; i < count; i += SimdLanes)
  {
    const VecD x = load(nx + i);
    const VecD y = load(ny + i);
    const VecD z = load(nz + i);
    const VecD residual = -(load(dx + i) * x + load(dy + i) * y + load(dz + i) * z) - f;
    const VecD normalGap = 1.0 - 2.0 * (x * gx + y * gy + z * gz) + gg;
    const VecD e = -residual * residual * rf - normalGap * nf;
    store(robust + i, expNonPositive(e < 0.0 ? e : VecD{}));
  }
}

// RIMLS's sums for one fit, with w_i = weight_i (times robust_i when given) and wk_i = 2 w_i k_i
// (k_i from @p k when given, else @p k0): out[] = {sum w, sum w f_i, sum wk r (3), sum wk f_i r (3),
// sum w n (3)}, f_i = -(r_i . n_i).
PSS_KERNEL_INLINE void robustSumsBody(const double* weight, const double* robust, const double* k, double k0,
  const double* dx, const double* dy, const double* dz, const double* nx, const double* ny, const double* nz,
  Eigen::Index count, double* out)
{
  VecD sw{}, sf{}, gx{}, gy{}, gz{}, fx{}, fy{}, fz{}, sx{}, sy{}, sz{};
  const VecD constantK = splat(2.0 * k0);
  for (Eigen::Index i = 0; i < count; i += SimdLanes)
  {
    const VecD w = robust ? load(weight + i) * load(robust + i) : load(weight + i);
    const VecD wk = k ? 2.0 * w * load(k + i) : w * constantK;
    const VecD x = load(dx + i);
    const VecD y = load(dy + i);
    const VecD z = load(dz + i);
    const VecD nxi = load(nx + i);
    const VecD nyi = load(ny + i);
    const VecD nzi = load(nz + i);
    const VecD fi = -(x * nxi + y * nyi + z * nzi);
    sw += w;
    sf += w * fi;
    gx += wk * x;
    gy += wk * y;
    gz += wk * z;
    const VecD wkf = wk * fi;
    fx += wkf * x;
    fy += wkf * y;
    fz += wkf * z;
    sx += w * nxi;
    sy += w * nyi;
    sz += w * nzi;
  }
  storeLaneSums(out, sw, sf, gx, gy, gz, fx, fy, fz, sx, sy, sz);
}

#define PSS_KERNEL_COPIES(SUFFIX, TARGET)                                                                        \
  TARGET void weights##SUFFIX(const double* sqDist, const double* dx, const double* dy, const double* dz,          \
    double* weight, Eigen::Index padded, double minSq, double invH2, double* sums)                                \
  {                                                                                                              \
    weightsBody(sqDist, dx, dy, dz, weight, padded, minSq, invH2, sums);                                         \
  }                                                                                                              \
  TARGET void scaledWeights##SUFFIX(const double* dx, const double* dy, const double* dz, const double* h,       \
    double* weight, Eigen::Index padded, double* sums)                                                           \
  {                                                                                                              \
    scaledWeightsBody(dx, dy, dz, h, weight, padded, sums);                                                      \
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
  }                                                                                                              \
  TARGET void orientedMoments##SUFFIX(const double* w, const double* dx, const double* dy, const double* dz,     \
    const double* nx, const double* ny, const double* nz, Eigen::Index count, double* s)                         \
  {                                                                                                              \
    orientedMomentsBody(w, dx, dy, dz, nx, ny, nz, count, s);                                                    \
  }                                                                                                              \
  TARGET void robustFactors##SUFFIX(const double* dx, const double* dy, const double* dz, const double* nx,      \
    const double* ny, const double* nz, Eigen::Index count, const double* fit, double* robust)                   \
  {                                                                                                              \
    robustFactorsBody(dx, dy, dz, nx, ny, nz, count, fit, robust);                                               \
  }                                                                                                              \
  TARGET void robustSums##SUFFIX(const double* w, const double* robust, const double* k, double k0,              \
    const double* dx, const double* dy, const double* dz, const double* nx, const double* ny, const double* nz,   \
    Eigen::Index count, double* out)                                                                             \
  {                                                                                                              \
    robustSumsBody(w, robust, k, k0, dx, dy, dz, nx, ny, nz, count, out);                                        \
  }

#if defined(PSS_CORE_COPY_X86_64_V3)
// The core's copy for x86-64-v3 (filters/core/CMakeLists.txt): loaded only on CPUs with AVX2 and
// FMA, so it has one copy of the kernels, compiled like the rest of it (with fused multiply-add).
PSS_KERNEL_COPIES(V3, )

} // namespace

const KernelTable& kernels()
{
  static const KernelTable table{ "x86-64-v3", compactCandidatesAvx2, weightsV3, expV3, scatterV3, momentsV3,
    compactScaledCandidatesAvx2, scaledWeightsV3, orientedMomentsV3,
    robustFactorsV3, robustSumsV3 };
  return table;
}
#else
PSS_KERNEL_COPIES(Baseline, )
#if PSS_KERNEL_DISPATCH
PSS_KERNEL_COPIES(Avx2, PSS_TARGET_AVX2)
#endif

} // namespace

const KernelTable& kernels()
{
  static const KernelTable table = [] {
    const KernelTable baseline{ "baseline", compactCandidatesBaseline, weightsBaseline, expBaseline,
      scatterBaseline, momentsBaseline, compactScaledBaseline, scaledWeightsBaseline, orientedMomentsBaseline,
      robustFactorsBaseline, robustSumsBaseline };
#if PSS_KERNEL_DISPATCH
    const KernelTable avx2{ "avx2", compactCandidatesAvx2, weightsAvx2, expAvx2, scatterAvx2, momentsAvx2,
      compactScaledCandidatesAvx2, scaledWeightsAvx2, orientedMomentsAvx2,
      robustFactorsAvx2, robustSumsAvx2 };
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
#endif

} // namespace dispatch

void expNonPositive(const double* x, double* out, Eigen::Index n)
{
  dispatch::kernels().exp(x, out, n);
}

const char* kernelInstructionSet()
{
  return dispatch::kernels().name;
}

} // namespace pss
