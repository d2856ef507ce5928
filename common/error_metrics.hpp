// error_metrics.hpp — how far a computed number is from the true one.
//
// Two measures, both used throughout the precision chapter:
//   * ULP distance: how many representable numbers of type T lie between
//     the computed value and the reference rounded to T. One ULP is the best
//     any single rounding can do; "a few ULPs" is a good routine; millions
//     of ULPs is a formula that lost most of its digits.
//   * relative error |computed - exact| / |exact|, computed in long double.
#pragma once

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <type_traits>

namespace rt {

namespace detail {
// Maps a float or double onto an integer line where consecutive
// representable numbers are consecutive integers (and -0 == +0).
template <class T>
auto ordered_bits(T x) {
    using U = std::conditional_t<sizeof(T) == 4, std::int32_t, std::int64_t>;
    static_assert(sizeof(T) == sizeof(U), "ordered_bits needs float or double");
    U i;
    std::memcpy(&i, &x, sizeof x);
    return i < 0 ? U(std::numeric_limits<U>::min() - i) : i;
}
}  // namespace detail

// Number of representable values of T between a and b (0 when equal).
// NaN on either side gives the largest possible distance.
template <class T>
double ulp_distance(T a, T b) {
    static_assert(std::is_floating_point_v<T>, "ulp_distance needs a floating-point type");
    if (std::isnan(a) || std::isnan(b)) return std::numeric_limits<double>::infinity();
    if (a == b) return 0;
    long double ia = static_cast<long double>(detail::ordered_bits(a));
    long double ib = static_cast<long double>(detail::ordered_bits(b));
    return static_cast<double>(ia > ib ? ia - ib : ib - ia);
}

// |computed - exact| / |exact|; the absolute error when exact is zero.
template <class T, class R>
double relative_error(T computed, R exact) {
    long double c = static_cast<long double>(computed), e = static_cast<long double>(exact);
    if (std::isnan(c) || std::isnan(e)) return std::numeric_limits<double>::infinity();
    long double diff = std::fabs(c - e);
    return static_cast<double>(e == 0 ? diff : diff / std::fabs(e));
}

}  // namespace rt
