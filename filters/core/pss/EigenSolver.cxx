// SPDX-License-Identifier: BSD-3-Clause
#include "pss/Kernel.h"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <limits>

namespace pss
{

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

} // namespace pss
