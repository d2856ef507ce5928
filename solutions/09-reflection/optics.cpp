// optics.cpp — reference solution for chapter 09's optics.
#include "09-reflection/optics.hpp"

#include <algorithm>
#include <cmath>

namespace rt::ch09 {

namespace {

template <class T>
T clamp01(T x) {
    return std::clamp(x, T(0), T(1));  // a NaN stays NaN: callers never pass one
}

// sin^2 of the transmitted angle, eta^2 (1 - cos_i^2): past 1 there is no
// transmitted ray. 1 - cos_i^2 is formed as (1 - cos_i)(1 + cos_i), which
// keeps its small values near normal incidence exact to a few ulps.
template <class T>
T transmitted_sin2(T cos_i, T eta) {
    return eta * eta * ((T(1) - cos_i) * (T(1) + cos_i));
}

}  // namespace

template <class T>
vec3<T> reflect(const vec3<T>& d, const vec3<T>& n) {
    // Take d's component along n away twice: the tangential part stays, the
    // normal part flips. Linear in d, so |r| = |d| for any length of d.
    return d - (T(2) * dot(d, n)) * n;
}

template <class T>
std::optional<vec3<T>> refract(const vec3<T>& d, const vec3<T>& n, T eta) {
    const vec3<T> u = d / length(d);
    const T cos_i = clamp01(-dot(u, n));
    const T sin2_t = transmitted_sin2(cos_i, eta);
    if (sin2_t > T(1)) return std::nullopt;  // total internal reflection
    const T cos_t = std::sqrt(T(1) - sin2_t);
    // The tangential part scales by eta (Snell), the normal part is -cos_t n.
    return eta * u + (eta * cos_i - cos_t) * n;
}

template <class T>
T fresnel_dielectric(T cos_i, T eta) {
    cos_i = clamp01(cos_i);
    const T sin2_t = transmitted_sin2(cos_i, eta);
    if (sin2_t >= T(1)) return T(1);  // total internal reflection: all of it
    const T cos_t = std::sqrt(T(1) - sin2_t);
    const T r_s = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
    const T r_p = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
    return clamp01((r_s * r_s + r_p * r_p) / T(2));
}

template <class T>
T schlick(T cos_i, T eta) {
    cos_i = clamp01(cos_i);
    const T r0 = ((T(1) - eta) / (T(1) + eta)) * ((T(1) - eta) / (T(1) + eta));
    T c = cos_i;
    if (eta > T(1)) {  // inside the denser medium: Schlick's angle is the transmitted one
        const T sin2_t = transmitted_sin2(cos_i, eta);
        if (sin2_t >= T(1)) return T(1);
        c = std::sqrt(T(1) - sin2_t);
    }
    const T m = T(1) - c;
    return clamp01(r0 + (T(1) - r0) * (m * m) * (m * m) * m);
}

template vec3<float> reflect(const vec3<float>&, const vec3<float>&);
template vec3<double> reflect(const vec3<double>&, const vec3<double>&);
template std::optional<vec3<float>> refract(const vec3<float>&, const vec3<float>&, float);
template std::optional<vec3<double>> refract(const vec3<double>&, const vec3<double>&, double);
template float fresnel_dielectric(float, float);
template double fresnel_dielectric(double, double);
template float schlick(float, float);
template double schlick(double, double);

}  // namespace rt::ch09
