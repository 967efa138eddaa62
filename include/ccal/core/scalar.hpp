#pragma once
// The scalar types ccal's templates are instantiated with: double, and Eigen's forward-mode AutoDiffScalar
// (for exact derivatives with respect to error sources). value_of() (value_of.hpp) strips the derivatives.

#include <Eigen/Dense>  // must precede the AutoDiff module
#include <unsupported/Eigen/AutoDiff>

#include "ccal/core/value_of.hpp"

namespace ccal {}  // namespace ccal

namespace ccal {

// True when x is zero and, for an AutoDiff scalar, carries no derivative either: only then may a term be
// dropped without losing a sensitivity.
inline bool is_exactly_zero(double x) { return x == 0.0; }

template <class Derivatives>
bool is_exactly_zero(const Eigen::AutoDiffScalar<Derivatives>& x) {
  return x.value() == 0.0 && (x.derivatives().size() == 0 || x.derivatives().isZero(0.0));
}

}  // namespace ccal

namespace ccal {

// Forward-mode dual number carrying kDualWidth directional derivatives in a fixed-size vector: no heap
// allocation, and constants convert with zero derivatives of the right size (AutoDiffScalar with a dynamic
// derivative vector leaves constants with an empty one, which mixed expressions do not always reconcile).
// Jacobians with more columns are computed in passes of kDualWidth.
inline constexpr int kDualWidth = 8;
using Dual = Eigen::AutoDiffScalar<Eigen::Matrix<double, kDualWidth, 1>>;

// A dual with value v and derivative 1 in direction `slot` (or none if slot < 0).
inline Dual make_dual(double v, int slot) {
  Dual d(v);
  d.derivatives().setZero();
  if (slot >= 0) d.derivatives()[slot] = 1.0;
  return d;
}

}  // namespace ccal
