// SPDX-License-Identifier: BSD-3-Clause
#include "pss/Variants.h"

namespace pss
{

Direction LevinMLS::direction(const Vec3& x) const
{
  DirectionMemory none; // no earlier fit: the decomposition starts from scratch
  return directionNear(x, none);
}

Direction LevinMLS::directionNear(const Vec3& x, DirectionMemory& memory) const
{
  Neighbourhood& nb = threadNeighbourhood();
  gatherNeighbourhood(Index, Params, x, nb);
  // The shift factor exp(logScale) scales C(x) and cannot move its eigenvectors; normalizing
  // (NormalizedMLS) divides it by a positive number, which cannot either.
  return smallestEigenDirection(covarianceAboutQuery(nb), dimension(), Params.minStability, &memory.frame);
}

Direction LevinMLS::planeFit(const Vec3& x, Vec3& offset, DirectionMemory& memory) const
{
  // One gather for both: directionNear (this class's or CenterOfMass's) leaves x's neighbourhood
  // in the thread's shared one.
  const Direction d = directionNear(x, memory);
  offset = centroidOffset(threadNeighbourhood());
  return d;
}

LineSample LevinMLS::lineSample(const Vec3& y, const Vec3& a) const
{
  Neighbourhood& nb = threadNeighbourhood();
  gatherNeighbourhood(Index, Params, y, nb);
  // Eq. 1 along y + t a: with s_i = <a, p_i - y>, d theta_i/dt = theta_i 2 s_i / h^2 and
  // d s_i/dt = -1, so d/dt sum theta_i s_i^2 = sum theta_i (2 s_i^3 / h^2 - 2 s_i), and once more
  // d2/dt2 = sum theta_i (4 s_i^4 / h^4 - 10 s_i^2 / h^2 + 2).
  LineSample out;
  const LineMoments m = lineMoments(nb, a);
  const double k = nb.invH2;
  out.value = m.s2;
  out.slope = 2.0 * k * m.s3 - 2.0 * m.s1;
  out.curvature = 4.0 * k * k * m.s4 - 10.0 * k * m.s2 + 2.0 * nb.weightSum;
  out.logScale = nb.logScale();
  out.nearestSqDist = nb.minSqDist;
  return out;
}

} // namespace pss
