// optics.cpp — YOUR CODE for chapter 09, part 1. See optics.hpp for the
// contracts and README.md for the lecture. Suggested order: reflect,
// refract, fresnel_dielectric, schlick (each one's tests pass on its own).
#include "optics.hpp"

#include "common/stub.hpp"

#include <algorithm>
#include <cmath>

namespace rt::ch09 {

template <class T>
vec3<T> reflect(const vec3<T>& d, const vec3<T>& n) {
    // Keep d's part along the surface, flip its part along n.
    (void)d;
    (void)n;
    RT_NOT_IMPLEMENTED("chapter 09", "reflect");
}

template <class T>
std::optional<vec3<T>> refract(const vec3<T>& d, const vec3<T>& n, T eta) {
    // cos_i from the unit d, sin^2 of the transmitted angle from Snell's law;
    // past 1, no transmitted ray. Otherwise scale the tangential part by eta.
    (void)d;
    (void)n;
    (void)eta;
    RT_NOT_IMPLEMENTED("chapter 09", "refract");
}

template <class T>
T fresnel_dielectric(T cos_i, T eta) {
    // cos_t as in refract (total internal reflection: 1), then the average
    // of the two polarisations' squared amplitude ratios.
    (void)cos_i;
    (void)eta;
    RT_NOT_IMPLEMENTED("chapter 09", "fresnel_dielectric");
}

template <class T>
T schlick(T cos_i, T eta) {
    // R0 from eta, and the cosine on the side of the lower index.
    (void)cos_i;
    (void)eta;
    RT_NOT_IMPLEMENTED("chapter 09", "schlick");
}

// Compile the exercise for both precisions. Leave these lines as they are.
template vec3<float> reflect(const vec3<float>&, const vec3<float>&);
template vec3<double> reflect(const vec3<double>&, const vec3<double>&);
template std::optional<vec3<float>> refract(const vec3<float>&, const vec3<float>&, float);
template std::optional<vec3<double>> refract(const vec3<double>&, const vec3<double>&, double);
template float fresnel_dielectric(float, float);
template double fresnel_dielectric(double, double);
template float schlick(float, float);
template double schlick(double, double);

}  // namespace rt::ch09
