// scalar_types.hpp — the scalar types every math-core test runs in, and the tolerance vocabulary.
//
// Tolerances are written as a count of machine epsilons of the scalar type times the magnitude
// of the values involved, so one test body serves float, double and long double; each use says
// why its count is what it is.
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "shadowref/conventions.hpp"

// |a - b| <= tol in the scalar's own precision (gtest's EXPECT_NEAR converts to double, which
// would hide long double differences).
#define EXPECT_CLOSE(a, b, tol) EXPECT_LE(std::abs((a) - (b)), (tol)) << #a " vs " #b << ": " << (a) << " vs " << (b)

namespace shadowref::test {

using Scalars = ::testing::Types<float, double, long double>;
using FloatAndDouble = ::testing::Types<float, double>;

// n machine epsilons of T, relative to `scale`.
template <class T>
T eps(T n, T scale = T(1)) {
  return n * std::numeric_limits<T>::epsilon() * scale;
}

// Element-wise |a - b| <= tol, with the first offending entry in the failure message.
template <class A, class B>
::testing::AssertionResult near_matrix(const Eigen::MatrixBase<A>& a, const Eigen::MatrixBase<B>& b,
                                       typename A::Scalar tol) {
  for (Eigen::Index r = 0; r < a.rows(); ++r)
    for (Eigen::Index c = 0; c < a.cols(); ++c)
      if (!(std::abs(a(r, c) - b(r, c)) <= tol))
        return ::testing::AssertionFailure()
               << "entry (" << r << ", " << c << "): " << a(r, c) << " vs " << b(r, c) << " (tolerance " << tol
               << ")\n"
               << a << "\n---\n"
               << b;
  return ::testing::AssertionSuccess();
}

}  // namespace shadowref::test
