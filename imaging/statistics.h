// The distributions the reference test needs: critical values of the normal and Student's t,
// the upper tail of chi-square. Written from the definitions (regularised incomplete beta and
// gamma functions by their continued fractions and series).
#pragma once

namespace arbor::imaging {

// The two-sided standard-normal critical value: P(|Z| > z) = p.
double normal_two_sided_critical(double p);

// The two-sided critical value of Student's t with `dof` degrees of freedom: P(|T| > t) = p.
double student_t_two_sided_critical(double p, double dof);

// P(|T| > t) for Student's t with `dof` degrees of freedom.
double student_t_two_sided_tail(double t, double dof);

// P(X > x) for X chi-square with `dof` degrees of freedom.
double chi_square_upper_tail(double x, double dof);

}  // namespace arbor::imaging
