// property_support.hpp — what every property file shares: the tolerance vocabulary, the readable
// printing of Eigen values in counterexamples, and how a property is run (as a GoogleTest, or
// against a deliberately wrong implementation that it must catch).
#pragma once

#include <gtest/gtest.h>  // before rapidcheck/gtest.h (docs/dependencies.md)
#include <rapidcheck.h>
#include <rapidcheck/gtest.h>

#include <cmath>
#include <iomanip>
#include <limits>
#include <sstream>
#include <string>

#include "shadowref/conventions.hpp"

namespace shadowref::prop {

// The wide type the properties CHECK in, so that the check adds no rounding of its own worth
// mentioning next to the implementation's (long double has 11 more bits than double on x86-64).
using Wide = long double;

// Tolerances are counts of rounding errors of the scalar T under test times the magnitude the
// computation went through (its condition): tol = ops · ε(T) · magnitude. Each use says where its
// count of operations and its magnitude come from; no bare tolerance literal anywhere.
template <class T>
Wide rounding(Wide ops, Wide magnitude) {
  return ops * static_cast<Wide>(std::numeric_limits<T>::epsilon()) * magnitude;
}

template <class T>
const char* scalar_name() {
  return std::is_same_v<T, float> ? "float" : "double";
}

// Readable one-line vectors and matrices for RC_LOG and the counterexamples.
template <class Derived>
std::string str(const Eigen::MatrixBase<Derived>& m) {
  std::ostringstream os;
  os << std::setprecision(std::numeric_limits<typename Derived::Scalar>::max_digits10);
  if (m.cols() == 1) {
    os << "(";
    for (Eigen::Index i = 0; i < m.rows(); ++i) os << (i ? ", " : "") << m(i);
    os << ")";
    return os.str();
  }
  os << "[";
  for (Eigen::Index r = 0; r < m.rows(); ++r) {
    os << (r ? "; " : "");
    for (Eigen::Index c = 0; c < m.cols(); ++c) os << (c ? ", " : "") << m(r, c);
  }
  os << "]";
  return os.str();
}

inline std::string str(const ClipConvention& c) {
  return std::string(to_string(c.hand)) + "/" + to_string(c.depth) + "/" + to_string(c.order);
}

// How many cases a costly property runs: max_success / divisor of the current RC_PARAMS (at least
// one), so that `RC_PARAMS="max_success=2000"` scales them too.
inline int scaled_cases(int divisor) {
  const int n = rc::detail::configuration().testParams.maxSuccess / divisor;
  return n < 1 ? 1 : n;
}

// Runs `property` as part of the current GoogleTest with `cases` successes (default: RC_PARAMS'
// max_success), printing the reproduce string and the shrunk counterexample on failure.
// `shrink` = false for properties whose cases cost a render each (shrinking would take minutes;
// the failing case is printed unshrunk, with its reproduce string).
template <class Property>
void check_property(Property&& property, int cases = 0, bool shrink = true) {
  const auto info = ::testing::UnitTest::GetInstance()->current_test_info();
  rc::detail::TestMetadata metadata;
  metadata.id = std::string(info->test_suite_name()) + "/" + info->name();
  metadata.description = info->name();
  rc::detail::TestParams params = rc::detail::configuration().testParams;
  if (cases > 0) params.maxSuccess = cases;
  if (!shrink) params.disableShrinking = true;
  // With the default count, the configuration's reproduce= map applies too.
  const auto result = (cases > 0 || !shrink) ? rc::detail::checkTestable(std::forward<Property>(property), metadata, params)
                                : rc::detail::checkTestable(std::forward<Property>(property), metadata);
  std::ostringstream os;
  rc::detail::printResultMessage(result, os);
  if (!result.template is<rc::detail::SuccessResult>()) FAIL() << os.str();
}

// The teeth: runs `property` on a deliberately wrong implementation and succeeds only when
// RapidCheck finds a counterexample (within `cases` tries), which it prints, shrunk. Fails the
// test when the property lets the wrong implementation pass.
template <class Property>
void expect_counterexample(Property&& property, int cases) {
  const auto info = ::testing::UnitTest::GetInstance()->current_test_info();
  rc::detail::TestMetadata metadata;
  metadata.id = std::string(info->test_suite_name()) + "/" + info->name();
  metadata.description = info->name();
  rc::detail::TestParams params = rc::detail::configuration().testParams;
  params.maxSuccess = cases;
  const auto result = rc::detail::checkTestable(std::forward<Property>(property), metadata, params);
  std::ostringstream os;
  rc::detail::printResultMessage(result, os);
  if (result.template is<rc::detail::FailureResult>()) {
    std::cout << "caught, as it must be. The shrunk counterexample:\n" << os.str() << "\n";
  } else {
    ADD_FAILURE() << "the property did NOT catch the wrong implementation in " << cases << " cases:\n" << os.str();
  }
}

}  // namespace shadowref::prop
