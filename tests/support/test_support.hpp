// test_support.hpp — small helpers shared by the course's tests.
//
// Tests for float and double are written once with TEST_CASE_TEMPLATE and
// the RT_SCALARS list below. Failure messages are written for a student:
// they say which idea of the lecture went wrong, then show the numbers.
#pragma once

#include "common/hit_record.hpp"
#include "common/interval.hpp"
#include "common/math.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <optional>
#include <sstream>
#include <string>

#define RT_SCALARS float, double

namespace rt::test {

// Human-readable name of the scalar type, for messages.
template <class T>
const char* scalar_name() {
    return sizeof(T) == sizeof(float) ? "float" : "double";
}

// True when a and b agree to a relative tolerance suited to T
// (about 1e-4 for float, 1e-10 for double) or an absolute one near zero.
// Never for infinity or NaN: a tolerance scaled by |a| would call +inf close
// to anything (|inf - b| <= tol * inf), so a wrong answer of +inf would pass.
// A test whose contract wants a non-finite value checks it on its own.
template <class T>
bool close(T a, T b, T scale = T(1)) {
    if (!std::isfinite(a) || !std::isfinite(b) || !std::isfinite(scale)) return false;
    const T tol = sizeof(T) == sizeof(float) ? T(1e-4) : T(1e-10);
    return std::fabs(a - b) <= tol * std::fmax(scale, std::fmax(std::fabs(a), std::fabs(b)));
}

// Vectors agree component by component, as close() above.
template <class T>
bool close(const vec3<T>& a, const vec3<T>& b) {
    return close(a.x, b.x) && close(a.y, b.y) && close(a.z, b.z);
}

template <class T>
bool is_unit(const vec3<T>& v) {
    return close(length(v), T(1));
}

// The range "anywhere in front of the ray's origin": (0, infinity).
template <class T>
interval<T> everything_ahead() {
    return {T(0), infinity<T>};
}

template <class T>
std::string describe(const vec3<T>& v) {
    std::ostringstream s;
    s.precision(sizeof(T) == 4 ? 9 : 17);
    s << "(" << v.x << ", " << v.y << ", " << v.z << ")";
    return s.str();
}

template <class T>
std::string describe(const std::optional<T>& t) {
    if (!t) return "a miss (std::nullopt)";
    std::ostringstream s;
    s.precision(sizeof(T) == 4 ? 9 : 17);
    s << "t = " << *t;
    return s.str();
}

template <class T>
std::string describe_hit(const std::optional<hit_record<T>>& hit) {
    if (!hit) return "a miss (std::nullopt)";
    return describe(std::optional<T>(hit->t)) + ", point " + describe(hit->point) + ", normal " +
           describe(hit->normal);
}

}  // namespace rt::test
