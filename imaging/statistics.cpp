// Tail probabilities and critical values for the reference test.
#include "imaging/statistics.h"

#include <cmath>

#include "common/error.h"

namespace arbor::imaging {

namespace {

constexpr double kTiny = 1e-300;
constexpr double kEpsilon = 1e-15;

// The continued fraction of the regularised incomplete beta function I_x(a, b) (modified
// Lentz's method), valid for x < (a + 1) / (a + b + 2).
double beta_fraction(double a, double b, double x) {
  double c = 1.0, d = 1.0 - (a + b) * x / (a + 1.0);
  if (std::fabs(d) < kTiny) d = kTiny;
  d = 1.0 / d;
  double f = d;
  for (int m = 1; m < 10000; ++m) {
    const double m2 = 2.0 * m;
    // Even step.
    double num = m * (b - m) * x / ((a + m2 - 1.0) * (a + m2));
    d = 1.0 + num * d;
    c = 1.0 + num / c;
    if (std::fabs(d) < kTiny) d = kTiny;
    if (std::fabs(c) < kTiny) c = kTiny;
    d = 1.0 / d;
    f *= d * c;
    // Odd step.
    num = -(a + m) * (a + b + m) * x / ((a + m2) * (a + m2 + 1.0));
    d = 1.0 + num * d;
    c = 1.0 + num / c;
    if (std::fabs(d) < kTiny) d = kTiny;
    if (std::fabs(c) < kTiny) c = kTiny;
    d = 1.0 / d;
    const double step = d * c;
    f *= step;
    if (std::fabs(step - 1.0) < kEpsilon) break;
  }
  return f;
}

// I_x(a, b).
double incomplete_beta(double a, double b, double x) {
  if (x <= 0) return 0.0;
  if (x >= 1) return 1.0;
  const double front = std::exp(std::lgamma(a + b) - std::lgamma(a) - std::lgamma(b) +
                                a * std::log(x) + b * std::log1p(-x));
  if (x < (a + 1.0) / (a + b + 2.0)) return front * beta_fraction(a, b, x) / a;
  return 1.0 - front * beta_fraction(b, a, 1.0 - x) / b;
}

// The regularised upper incomplete gamma function Q(a, x).
double upper_incomplete_gamma(double a, double x) {
  if (x <= 0) return 1.0;
  const double log_front = a * std::log(x) - x - std::lgamma(a);
  if (x < a + 1.0) {
    // The series of P(a, x).
    double term = 1.0 / a, sum = term;
    for (int n = 1; n < 100000; ++n) {
      term *= x / (a + n);
      sum += term;
      if (std::fabs(term) < std::fabs(sum) * kEpsilon) break;
    }
    return 1.0 - sum * std::exp(log_front);
  }
  // The continued fraction of Q(a, x) (modified Lentz).
  double b = x + 1.0 - a, c = 1.0 / kTiny, d = 1.0 / b, f = d;
  for (int i = 1; i < 100000; ++i) {
    const double an = -i * (i - a);
    b += 2.0;
    d = an * d + b;
    if (std::fabs(d) < kTiny) d = kTiny;
    c = b + an / c;
    if (std::fabs(c) < kTiny) c = kTiny;
    d = 1.0 / d;
    const double step = d * c;
    f *= step;
    if (std::fabs(step - 1.0) < kEpsilon) break;
  }
  return std::exp(log_front) * f;
}

// Bisects a tail that falls monotonically in t from 1 at 0: the t where tail(t) = p.
template <class Tail>
double bisect_tail(double p, const Tail& tail) {
  double lo = 0, hi = 1;
  while (tail(hi) > p && hi < 1e12) hi *= 2;
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    (tail(mid) > p ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

}  // namespace

double normal_two_sided_critical(double p) {
  ARBOR_CHECK(p > 0 && p < 1);
  return bisect_tail(p, [](double z) { return std::erfc(z / std::sqrt(2.0)); });
}

double student_t_two_sided_tail(double t, double dof) {
  // P(|T| > t) = I_{ν/(ν+t²)}(ν/2, 1/2).
  return incomplete_beta(0.5 * dof, 0.5, dof / (dof + t * t));
}

double student_t_two_sided_critical(double p, double dof) {
  ARBOR_CHECK(p > 0 && p < 1 && dof > 0);
  return bisect_tail(p, [dof](double t) { return student_t_two_sided_tail(t, dof); });
}

double chi_square_upper_tail(double x, double dof) {
  ARBOR_CHECK(dof > 0);
  return upper_incomplete_gamma(0.5 * dof, 0.5 * x);
}

}  // namespace arbor::imaging
