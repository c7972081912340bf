#pragma once
// Double-double arithmetic on the CPU: the reference for the DoubleFloat library's own accuracy.
// float64 alone is not enough (LWC-BRIEF §6): its 2^-53 is only ~32x below the u^2 = 2^-48 the
// library's bounds are stated in; a double-double carries ~2^-104. Needs an exact std::fma (the
// C library's is) and no contraction of the steps (the build passes -ffp-contract=off).
#include <cmath>

namespace lwc::dd {

struct Value {
  double hi = 0, lo = 0;
  double approx() const { return hi + lo; }
};

inline Value two_sum(double a, double b) {
  double s = a + b, v = s - a;
  return {s, (a - (s - v)) + (b - v)};
}
inline Value fast_two_sum(double a, double b) {
  double s = a + b;
  return {s, b - (s - a)};
}
inline Value from(double a, double b = 0) { return two_sum(a, b); }
inline Value neg(Value a) { return {-a.hi, -a.lo}; }

inline Value add(Value a, Value b) {
  Value s = two_sum(a.hi, b.hi), t = two_sum(a.lo, b.lo);
  Value v = fast_two_sum(s.hi, s.lo + t.hi);
  return fast_two_sum(v.hi, t.lo + v.lo);
}
inline Value sub(Value a, Value b) { return add(a, neg(b)); }

inline Value mul(Value a, Value b) {
  double p = a.hi * b.hi;
  double e = std::fma(a.hi, b.hi, -p) + (a.hi * b.lo + a.lo * b.hi);
  return fast_two_sum(p, e);
}

inline Value div(Value a, Value b) {
  double q1 = a.hi / b.hi;
  Value r = sub(a, mul(b, {q1, 0}));
  double q2 = r.hi / b.hi;
  r = sub(r, mul(b, {q2, 0}));
  double q3 = r.hi / b.hi;
  return add(fast_two_sum(q1, q2), {q3, 0});
}

inline Value sqrt(Value a) {
  if (a.hi <= 0) return {std::sqrt(a.hi), 0};
  double s = std::sqrt(a.hi);
  Value r = sub(a, mul({s, 0}, {s, 0}));
  return fast_two_sum(s, r.hi / (2 * s));
}

inline Value abs(Value a) { return a.hi < 0 || (a.hi == 0 && a.lo < 0) ? neg(a) : a; }

}  // namespace lwc::dd
