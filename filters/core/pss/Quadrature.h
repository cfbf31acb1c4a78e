// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Quadrature.h
 * @brief Gauss-Hermite rules for integrals of the form  int f(u) exp(-u^2) du  over the real line.
 *
 * e_I (Sec. 5) integrates delta^2 against the Gaussian theta(y, x) over a line or plane through
 * x, so with u = |y - x| / h the weight is exactly exp(-u^2) per in-plane axis. An n-node rule is
 * exact for polynomials of degree 2n - 1; far from the cloud delta^2 is a quartic in u, which
 * three nodes already integrate exactly.
 */
#pragma once

#include <vector>

namespace pss
{

struct GaussHermiteRule
{
  std::vector<double> nodes;   ///< symmetric about zero, ascending
  std::vector<double> weights; ///< sum to sqrt(pi)
};

/// The @p n-node rule (1 <= n <= 64), computed by the Golub-Welsch eigenvalue method.
/// Throws std::invalid_argument outside that range.
GaussHermiteRule gaussHermite(int n);

} // namespace pss
