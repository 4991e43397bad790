// Exact numbers for the geometric kernel's fallbacks that never compute a gcd. GMP's mpq_class
// reduces every result to lowest terms, and those gcds (with their reallocations) were 3/4 of the
// time of a line through a vertex (tests/gl_colour_test's seams). Sums and products of doubles are
// dyadic (an integer times a power of two), so a Dyadic keeps them exactly with an integer
// mantissa shifted into line; a quotient is kept as an UnreducedRational, numerator and
// denominator apart, its sign the product of theirs. Reduced once, at the end, by to_mpq.
#pragma once

#include <gmpxx.h>

#include <cmath>

namespace roving {

struct Dyadic {
  mpz_class mantissa;  // the value is mantissa * 2^exponent
  long exponent = 0;
};

inline Dyadic dyadic(double v) {
  int e = 0;
  const double f = std::frexp(v, &e);  // v = f 2^e, |f| in [0.5, 1): f 2^53 is an integer
  return {mpz_class(std::ldexp(f, 53)), static_cast<long>(e) - 53};
}

inline Dyadic operator+(const Dyadic& a, const Dyadic& b) {
  if (a.mantissa == 0) return b;
  if (b.mantissa == 0) return a;
  if (a.exponent == b.exponent) return {a.mantissa + b.mantissa, a.exponent};
  if (a.exponent > b.exponent) return {(a.mantissa << (a.exponent - b.exponent)) + b.mantissa, b.exponent};
  return {a.mantissa + (b.mantissa << (b.exponent - a.exponent)), a.exponent};
}
inline Dyadic operator-(const Dyadic& a) { return {-a.mantissa, a.exponent}; }
inline Dyadic operator-(const Dyadic& a, const Dyadic& b) { return a + (-b); }
inline Dyadic operator*(const Dyadic& a, const Dyadic& b) {
  return {a.mantissa * b.mantissa, a.exponent + b.exponent};
}

inline mpq_class to_mpq(const Dyadic& d) {
  mpq_class q(d.mantissa);
  if (d.exponent > 0) mpq_mul_2exp(q.get_mpq_t(), q.get_mpq_t(), d.exponent);
  if (d.exponent < 0) mpq_div_2exp(q.get_mpq_t(), q.get_mpq_t(), -d.exponent);
  return q;
}

// numerator / denominator, not reduced; `whole` while the denominator is 1 (no division yet), so
// that the polynomial part of an expression costs what Dyadic's arithmetic costs.
struct UnreducedRational {
  Dyadic numerator, denominator{mpz_class(1), 0};
  bool whole = true;

  UnreducedRational() = default;
  explicit UnreducedRational(double v) : numerator(dyadic(v)) {}
  UnreducedRational(Dyadic n, Dyadic d, bool w) : numerator(std::move(n)), denominator(std::move(d)), whole(w) {}
};

inline UnreducedRational operator+(const UnreducedRational& a, const UnreducedRational& b) {
  if (a.whole && b.whole) return {a.numerator + b.numerator, a.denominator, true};
  return {a.numerator * b.denominator + b.numerator * a.denominator, a.denominator * b.denominator, false};
}
inline UnreducedRational operator-(const UnreducedRational& a, const UnreducedRational& b) {
  if (a.whole && b.whole) return {a.numerator - b.numerator, a.denominator, true};
  return {a.numerator * b.denominator - b.numerator * a.denominator, a.denominator * b.denominator, false};
}
inline UnreducedRational operator*(const UnreducedRational& a, const UnreducedRational& b) {
  if (a.whole && b.whole) return {a.numerator * b.numerator, a.denominator, true};
  return {a.numerator * b.numerator, a.denominator * b.denominator, false};
}
inline UnreducedRational operator/(const UnreducedRational& a, const UnreducedRational& b) {
  return {a.numerator * b.denominator, a.denominator * b.numerator, false};
}

inline int sgn(const UnreducedRational& q) {
  return sgn(q.numerator.mantissa) * (q.whole ? 1 : sgn(q.denominator.mantissa));
}

inline mpq_class to_mpq(const UnreducedRational& q) {
  if (q.whole) return to_mpq(q.numerator);
  return to_mpq(q.numerator) / to_mpq(q.denominator);
}

}  // namespace roving
