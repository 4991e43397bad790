// Rational numbers (GMP) where double cannot decide: the exact fallbacks of the closest-point
// kernel (geometry.cpp) and of the normal line's crossings (normal_line.cpp).
#pragma once

#include <gmpxx.h>

namespace roving {

// The double nearest q (mpq_class::get_d truncates).
double nearest_double(const mpq_class& q);

}  // namespace roving
