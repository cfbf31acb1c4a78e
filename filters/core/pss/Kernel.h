// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Kernel.h
 * @brief Gaussian weights with shifted exponents, the neighbourhood that carries them, and the
 *        weighted quantities every surface definition is built from.
 *
 * theta(y, p) = exp(-|y - p|^2 / h^2) underflows a few dozen h away from the cloud, which would
 * make every normalized quantity 0/0. A Neighbourhood therefore stores
 *   w_i = exp(-(d_i^2 - dmin^2) / h^2)   (the nearest point has w = 1)
 * and the common factor exp(-dmin^2 / h^2) separately as a log-scale. Normalized weights
 * theta_N = w_i / sum_j w_j are then exact at any distance, and unnormalized ones are
 * exp(logScale) * w_i (which may underflow to zero, never to NaN).
 *
 * Truncation: only points with d_i^2 < dmin^2 + (cutoff * h)^2 are gathered, i.e. points whose
 * weight relative to the nearest one is at least exp(-cutoff^2) (cutoff 3: 1.2e-4 per point).
 * The cut is relative to the nearest point, not a fixed radius around y, so a query 100 h away
 * still sees the points that dominate it.
 *
 * Offsets are stored as p_i - y, with the query as local origin, so covariances of clouds with
 * coordinates around 1e6 do not lose their digits.
 *
 * With a scale per point (PointIndex::setScales) every formula above holds with h replaced by the
 * point's own h_i: w_i = exp(-(d_i^2 / h_i^2 - s)), s = min_j d_j^2 / h_j^2 (the point of largest
 * weight has w = 1), the log-scale is -s, and the neighbourhood holds the points with
 * d_i^2 / h_i^2 < s + cutoff^2. Derivatives of the weights then carry each point's 1 / h_i^2
 * (Neighbourhood::inverseSqScale) where the single scale's 1 / h^2 stood.
 */
#pragma once

#include "pss/PointIndex.h"
#include "pss/Types.h"

#include <Eigen/Core>

#include <vector>

namespace pss
{

struct Workspace;

/// Parameters shared by every surface definition.
struct SurfaceParameters
{
  /// Gaussian scale (theta = exp(-d^2/h^2)); must be > 0 and finite. When the index has a scale
  /// per point (PointIndex::hasScales) those are the weights' scales and h is only a typical value
  /// (the unit of the delta lattice and of a distributed run's margins).
  double h = 1.0;
  double cutoff = 3.0;        ///< truncation, in units of h, beyond the nearest point (see above)
  int quadratureOrder = 6;    ///< Gauss-Hermite nodes per in-plane axis for e_I (1..32)
  int integrandPower = 2;     ///< e_I integrates delta^power; the paper uses 2 (appendix: 1 is blind)
  double minStability = 1e-5; ///< n(x) counts as undefined below this stability (docs/paper.md)
  /// Spacing, in units of h, of the lattice from which e_I's quadrature reads delta (DeltaLattice.h);
  /// 0 evaluates delta exactly at every node (the reference). Otherwise within [0.05, 1].
  double deltaLattice = 0.0;
  /// APSS: how much of the fitted sphere's curvature is kept, in [0, 1] (1: the algebraic sphere
  /// of Guennebaud and Gross; 0: its plane through the same points and normals).
  double sphericity = 1.0;
  /// RIMLS: the normal and residual scales of the robust weights (sigma_n, unitless; sigma_r in
  /// units of the local h), and how many times the weights are refitted after the first fit.
  double sigmaNormal = 0.75;
  double sigmaResidual = 0.5;
  int robustRefits = 3;

  /// Throws std::invalid_argument with a readable message when a value is out of range.
  void validate() const;
};

/**
 * The cloud points that influence a query point y, with their shifted Gaussian weights, stored as
 * structure-of-arrays so the sums over neighbours vectorize. Only the first size() entries of each
 * array are meaningful (the arrays keep their capacity between queries).
 *
 * Neighbours are ordered by their index in the PointIndex, and offsets are computed as p_i - y
 * from the stored coordinates, so a neighbourhood, and every sum over it, is bitwise the same
 * however it was gathered (see gatherNeighbourhood).
 */
struct Neighbourhood
{
  Vec3 origin = Vec3::Zero();  ///< the query point y
  double minSqDist = 0.0;      ///< squared distance from y to the nearest point
  double invH2 = 1.0;          ///< 1 / h^2
  double weightSum = 0.0;      ///< sum of the weights (>= 1 whenever the cloud is not empty)
  Vec3 moment = Vec3::Zero();  ///< sum of w_i (p_i - y)
  Eigen::Index count = 0;      ///< number of neighbours
  Eigen::ArrayXd dx, dy, dz;   ///< p_i - y, per coordinate
  Eigen::ArrayXd sqDist;       ///< |p_i - y|^2
  Eigen::ArrayXd weight;       ///< exp(-(|p_i - y|^2 - minSqDist) / h^2), in (0, 1]
  /// A scale per point (PointIndex::hasScales): weight is exp(-(|p_i - y|^2 / h_i^2 -
  /// minScaledSqDist)), inverseSqScale holds each neighbour's 1 / h_i^2 and invH2 is not used.
  bool scaled = false;
  double minScaledSqDist = 0.0;   ///< scaled: min_i |p_i - y|^2 / h_i^2
  Eigen::ArrayXd inverseSqScale;  ///< scaled: 1 / h_i^2 per neighbour
  /// The scale at y: sum_i theta_N(y, p_i) h_i, the weighted mean of the neighbours' scales (h
  /// itself without a scale per point). What "units of h" mean at y: tolerances, steps, the
  /// domain's distances, e_I's window.
  double localScale = 0.0;
  Eigen::ArrayXd pointScale;      ///< scaled: h_i per neighbour
  /// The neighbours' unit normals (withNormals: whenever the index has normals; the padding's
  /// are 0); robust is scratch for the fits that reweigh the neighbours (RIMLS).
  bool withNormals = false;
  Eigen::ArrayXd nx, ny, nz, robust;
  /// What the contents were gathered for (index serial, h, cutoff; 0 = nothing yet), so that a
  /// second gather of the same query is free.
  std::uint64_t indexSerial = 0;
  double h = 0.0;
  double cutoff = 0.0;

  Eigen::Index size() const { return count; }
  auto x() const { return dx.head(count); }
  auto y() const { return dy.head(count); }
  auto z() const { return dz.head(count); }
  auto d2() const { return sqDist.head(count); }
  auto w() const { return weight.head(count); }
  auto k() const { return inverseSqScale.head(count); }
  Vec3 offset(Eigen::Index i) const { return Vec3(dx[i], dy[i], dz[i]); }
  /// log of the factor that turns weight into the true Gaussian theta(y, p_i).
  double logScale() const { return scaled ? -minScaledSqDist : -minSqDist * invH2; }
  /// Sets size() to @p n, growing the arrays' capacity when needed (with room for one vector
  /// more: the arrays are processed in whole vectors, padded with weight 0 after the last entry).
  void resize(Eigen::Index n);
};

/// Sets ws.leftCompleteRegion when the ball of squared radius @p sqRadius around @p y (what an
/// evaluation at y reads of the cloud) reaches beyond @p index's complete region.
void noteReach(const PointIndex& index, const Vec3& y, double sqRadius, Workspace& ws);

/**
 * Fills @p nb with the neighbourhood of @p y (see the file comment). Requires a non-empty index.
 * Returns at once when @p nb already holds this query (same index, h, cutoff and point).
 *
 * @p ws keeps the candidate points of its last k-d tree query, fetched with a margin
 * (half of h, or a twentieth of the distance to the cloud if larger, up to 2 h: far from the
 * cloud a wider margin would hold much of the cloud, per workspace). A later query
 * within that margin of the last fetch is answered from the candidates, which provably contain
 * its whole neighbourhood: the nearest point is at most dmin + delta away, so every point within
 * sqrt((dmin + delta)^2 + (cutoff h)^2) of y lies inside the fetched ball. Iterations of a
 * projection and samples along a line thus rarely touch the tree. @p nb may be one of @p ws's.
 */
void gatherNeighbourhood(const PointIndex& index, const SurfaceParameters& params, const Vec3& y,
  Neighbourhood& nb, Workspace& ws);

/**
 * gatherNeighbourhood, with each neighbour's normal as well (the first size() entries of
 * Neighbourhood::nx, ny, nz). Requires PointIndex::hasNormals(). Defined in
 * OrientedNeighbourhood.cxx.
 */
void gatherOrientedNeighbourhood(const PointIndex& index, const SurfaceParameters& params, const Vec3& y,
  Neighbourhood& nb, Workspace& ws);

/**
 * out[i] = exp(x[i]) for x[i] <= 0, several at a time: within one ulp of std::exp on [-708, 0],
 * 0 below -708, NaN for NaN. The Gaussian weights are computed with it.
 */
void expNonPositive(const double* x, double* out, Eigen::Index n);

/// The instruction set the core runs: "x86-64-v3" when the loader took the core's copy for
/// x86-64-v3 (AVX2 and FMA throughout; see filters/core/CMakeLists.txt); in the baseline copy
/// that of its vector kernels, "avx2" where the CPU has it, else "baseline" (x86-64's SSE2),
/// chosen at the first call (the environment variable PSS_SIMD=baseline forces "baseline"). The
/// baseline copy's two give bitwise the same results; the x86-64-v3 copy fuses multiply-adds, so
/// its results differ from them in the last bits (see KernelDispatch.cxx).
const char* kernelInstructionSet();

/**
 * Makes @p ws's candidates (see gatherNeighbourhood) cover every query within @p reach of
 * @p center, with at most one k-d tree query. For evaluations that spread over a known region,
 * such as the quadrature nodes of e_I, so they do not each query the tree. The fetch reaches h/2
 * further, so that a centre moved by less than that is still covered.
 */
void prefetchNeighbourhoods(
  const PointIndex& index, const SurfaceParameters& params, const Vec3& center, double reach, Workspace& ws);

/**
 * Like prefetchNeighbourhoods, for a smaller region inside a prefetched one: keeps, in @p ws's
 * second candidate cache, just the prefetched candidates that queries within @p reach of
 * @p center can need, so that each of them scans those instead of the whole prefetch. e_I calls
 * it for each quarter of its quadrature nodes. Neighbourhoods are the same bit for bit whichever
 * cache serves them.
 */
void focusNeighbourhoods(
  const PointIndex& index, const SurfaceParameters& params, const Vec3& center, double reach, Workspace& ws);

/// The gradient in y of Neighbourhood::localScale: 2 sum_i theta_N k_i (h_i - localScale) r_i
/// (zero without a scale per point).
Vec3 localScaleGradient(const Neighbourhood& nb);

/// c(y) - y, where c(y) = sum_i theta_N(y, p_i) p_i is the weighted centre of mass.
Vec3 centroidOffset(const Neighbourhood& nb);

/// How fast the centre of mass follows y along a unit vector a: d<a, c(y + s a)>/ds at s = 0,
/// which is 2 Cov_w(z, k z) for z_i = <a, p_i - y> and k_i = 1 / h_i^2 (1 / h^2 with one h),
/// the derivative of the Gaussian weights (2 sigma^2 / h^2 for a variance sigma^2 along a). A
/// step onto the plane through c along a leaves this fraction of the distance to its fixed point.
double centroidContraction(const Neighbourhood& nb, const Vec3& a);

/// sum_i w_i s_i^k for k = 1..4 with s_i = <a, p_i - y> (shifted weights): the moments along a
/// line that e(y + t a, a) and its derivatives in t are built from, in one pass.
struct LineMoments
{
  double s1 = 0.0, s2 = 0.0, s3 = 0.0, s4 = 0.0;
};
LineMoments lineMoments(const Neighbourhood& nb, const Vec3& a);

/// sum_i w_i (p_i - y - m)(p_i - y - m)^T with the shifted weights (m an offset from y).
Mat3 weightedScatter(const Neighbourhood& nb, const Vec3& m);

/// The weighted sums (shifted weights) an algebraic sphere is fitted from, in one pass over a
/// neighbourhood with normals: sum_i w_i n_i, sum_i w_i r_i . n_i and sum_i w_i |r_i|^2 (r_i = p_i - y).
struct OrientedMoments
{
  Vec3 normal = Vec3::Zero();
  double offsetAlongNormal = 0.0;
  double squaredOffset = 0.0;
};
OrientedMoments orientedMoments(const Neighbourhood& nb);

/// RIMLS's refit factors, robust[i] = exp(min(0, -(f_i - f)^2 residualFactor - |n_i - g|^2
/// normalFactor)) with f_i = (y - p_i) . n_i, for the neighbours (and the padding) of @p nb, which
/// must carry normals; @p robust needs room for size() plus one vector.
void robustFactors(const Neighbourhood& nb, double f, const Vec3& g, double residualFactor, double normalFactor,
  double* robust);

/// RIMLS's sums for one fit, in one pass: with w_i the shifted weight (times robust[i] unless
/// @p robust is null), k_i = 1 / h_i^2 and f_i = (y - p_i) . n_i: sum w, sum w f_i, sum 2 w k r,
/// sum 2 w k f_i r and sum w n (r_i = p_i - y).
struct RobustSums
{
  double weight = 0.0;
  double value = 0.0;
  Vec3 offset = Vec3::Zero();
  Vec3 valueOffset = Vec3::Zero();
  Vec3 normal = Vec3::Zero();
};
RobustSums robustSums(const Neighbourhood& nb, const double* robust);

/// sum_i w_i (p_i - y)(p_i - y)^T (shifted weights): Levin's C(y), up to the factor exp(logScale).
Mat3 covarianceAboutQuery(const Neighbourhood& nb);

/// sum_i theta_N(y, p_i)(p_i - c)(p_i - c)^T: the centre-of-mass covariance (Sec. 5).
Mat3 covarianceAboutCentroid(const Neighbourhood& nb);

/// The eigenvectors of an earlier fit, to start a later one from (see smallestEigenDirection).
struct EigenFrame
{
  Mat3 vectors = Mat3::Identity(); ///< orthonormal columns
  bool valid = false;              ///< false: no earlier fit, start from scratch
};

/**
 * Eigenvector of the smallest eigenvalue of a symmetric positive semi-definite matrix, with the
 * stability (lambda_1 - lambda_0) / (lambda_1 + lambda_0). In 2D only the xy block is used.
 *
 * With a valid @p frame (the eigenvectors of a nearby matrix, such as the previous iterate's in
 * a projection) the decomposition starts from it and takes a few sweeps of Jacobi rotations
 * instead of a QR iteration from scratch; the two agree to rounding. @p frame, when given,
 * receives the eigenvectors found (smallest first).
 */
Direction smallestEigenDirection(const Mat3& C, int dimension, double minStability, EigenFrame* frame = nullptr);

/// delta(y) = sum_i theta_N(y, p_i) |y - p_i|^2, the approximate squared distance (Sec. 5).
double approximateSqDistance(const Neighbourhood& nb);

/// delta, its gradient and its second derivative along a unit direction a, from one neighbourhood.
struct DeltaJet
{
  double value = 0.0;
  Vec3 gradient = Vec3::Zero();
  double curvature = 0.0; ///< a^T (Hessian of delta) a
};

/**
 * delta, grad delta and a^T H a, H the Hessian of delta. With theta_N the normalized weights,
 * r_i = p_i - y, m = sum theta_N r_i (= c - y) and T = sum theta_N (d_i^2 - delta) r_i,
 * differentiating the normalized weights gives
 *   grad delta = -2 m + (2 / h^2) T,
 * and differentiating once more
 *   H = 2 I - (8 / h^2) Cov + (4 / h^4) (sum theta_N (d_i^2 - delta) r_i r_i^T - T m^T - m T^T),
 * Cov the covariance about the centroid; along a it needs two more weighted sums of <a, r_i>^2.
 * (A single point gives H = 2 I, the Hessian of |y - p|^2.)
 */
DeltaJet approximateSqDistanceJet(const Neighbourhood& nb, const Vec3& a);

/// delta, its gradient and its whole Hessian (the formula above), from one neighbourhood.
struct DeltaHessian
{
  double value = 0.0;
  Vec3 gradient = Vec3::Zero();
  Mat3 hessian = Mat3::Zero();
};
DeltaHessian approximateSqDistanceHessian(const Neighbourhood& nb);

/// delta(y) and its gradient evaluated straight from the index, in Workspace::field.
class DistanceField
{
public:
  DistanceField(const PointIndex& index, const SurfaceParameters& params);
  double delta(const Vec3& y, Workspace& ws) const;
  /// delta, its gradient and its curvature along @p a (see approximateSqDistanceJet); optionally
  /// the squared distance from y to the nearest cloud point.
  DeltaJet jet(const Vec3& y, const Vec3& a, Workspace& ws, double* nearestSqDist = nullptr) const;
  /// delta, its gradient and its Hessian at y (a lattice node's data, DeltaLattice.h).
  DeltaHessian hessian(const Vec3& y, Workspace& ws) const;

  const PointIndex& index() const { return Index; }
  const SurfaceParameters& parameters() const { return Params; }

private:
  const PointIndex& Index;
  SurfaceParameters Params;
};

} // namespace pss
