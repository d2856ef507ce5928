// test_support.hpp — small helpers shared by the course's tests.
//
// Tests for float and double are written once with TEST_CASE_TEMPLATE and
// the RT_SCALARS list below. Failure messages are written for a student:
// they say which idea of the lecture went wrong, then show the numbers.
#pragma once

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
template <class T>
bool close(T a, T b, T scale = T(1)) {
    const T tol = sizeof(T) == sizeof(float) ? T(1e-4) : T(1e-10);
    return std::fabs(a - b) <= tol * std::fmax(scale, std::fmax(std::fabs(a), std::fabs(b)));
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

}  // namespace rt::test
