// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file KernelDispatch.h
 * @brief Private to the core: the table of the vector kernels' copy in use (baseline SSE2 or
 *        AVX2, chosen at the first call), which KernelDispatch.cxx alone compiles, so that no
 *        other file of the core's baseline copy holds an AVX instruction. (The core's copy for
 *        x86-64-v3 has one copy of the kernels, like the rest of it.)
 */
#ifndef pss_KernelDispatch_h
#define pss_KernelDispatch_h

#include "pss/Kernel.h"

namespace pss
{
namespace dispatch
{

// Doubles per vector on every path: the partial sums, and so every result, do not depend on the
// instruction set chosen.
constexpr int SimdLanes = 4;

// The candidates of a neighbourhood (CandidateCache's arrays): coordinates, squared distances and,
// when the cloud has them (else null), unit normals, compacted with the rest.
struct Candidates
{
  const double* px;
  const double* py;
  const double* pz;
  const double* sq;
  const double* nx;
  const double* ny;
  const double* nz;
  Eigen::Index count;
};

// The same with a scale per point: also the scaled squared distances |p - y|^2 / h_i^2, 1 / h_i^2
// and h_i.
struct ScaledCandidates : Candidates
{
  const double* scaledSq;
  const double* pk;
  const double* ph;
};

// One copy of every kernel per instruction set, and the table of the copy in use.
struct KernelTable
{
  const char* name;
  Eigen::Index (*compact)(const Candidates&, const Vec3&, double, double, Neighbourhood&);
  void (*weights)(const double*, const double*, const double*, const double*, double*, Eigen::Index, double, double,
    double*);
  void (*exp)(const double*, double*, Eigen::Index);
  void (*scatter)(const double*, const double*, const double*, const double*, Eigen::Index, double, double, double,
    double*);
  void (*moments)(const double*, const double*, const double*, const double*, Eigen::Index, double, double, double,
    double*);
  Eigen::Index (*compactScaled)(const ScaledCandidates&, const Vec3&, double, double, Neighbourhood&);
  void (*scaledWeights)(const double*, const double*, const double*, const double*, double*, Eigen::Index, double*);
  void (*orientedMoments)(const double*, const double*, const double*, const double*, const double*, const double*,
    const double*, Eigen::Index, double*);
  void (*robustFactors)(const double*, const double*, const double*, const double*, const double*, const double*,
    Eigen::Index, const double*, double*);
  void (*robustSums)(const double*, const double*, const double*, double, const double*, const double*,
    const double*, const double*, const double*, const double*, Eigen::Index, double*);
};

/// The copy of the kernels in use: AVX2 when the CPU has it, unless PSS_SIMD=baseline.
const KernelTable& kernels();

} // namespace dispatch
} // namespace pss

#endif
