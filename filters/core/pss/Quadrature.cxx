// SPDX-License-Identifier: BSD-3-Clause
#include "pss/Quadrature.h"

#include <Eigen/Eigenvalues>

#include <cmath>
#include <stdexcept>
#include <string>

namespace pss
{

GaussHermiteRule gaussHermite(int n)
{
  if (n < 1 || n > 64)
  {
    throw std::invalid_argument("gaussHermite: the number of nodes must be in [1, 64], got " + std::to_string(n));
  }
  // Golub-Welsch: the nodes are the eigenvalues of the symmetric Jacobi matrix of the Hermite
  // recurrence (off-diagonal sqrt(k/2)); each weight is sqrt(pi) times the squared first
  // component of its normalized eigenvector.
  Eigen::MatrixXd jacobi = Eigen::MatrixXd::Zero(n, n);
  for (int k = 1; k < n; ++k)
  {
    jacobi(k, k - 1) = jacobi(k - 1, k) = std::sqrt(0.5 * k);
  }
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> solver(jacobi);
  GaussHermiteRule rule;
  rule.nodes.resize(n);
  rule.weights.resize(n);
  const double sqrtPi = std::sqrt(M_PI);
  for (int i = 0; i < n; ++i)
  {
    rule.nodes[i] = solver.eigenvalues()(i);
    const double v0 = solver.eigenvectors()(0, i);
    rule.weights[i] = sqrtPi * v0 * v0;
  }
  // Symmetrize so that odd integrands cancel to rounding, as they do analytically.
  for (int i = 0; i < n / 2; ++i)
  {
    const int j = n - 1 - i;
    const double x = 0.5 * (rule.nodes[j] - rule.nodes[i]);
    const double w = 0.5 * (rule.weights[i] + rule.weights[j]);
    rule.nodes[i] = -x;
    rule.nodes[j] = x;
    rule.weights[i] = rule.weights[j] = w;
  }
  if (n % 2 == 1)
  {
    rule.nodes[n / 2] = 0.0;
  }
  return rule;
}

} // namespace pss
