// path_tracing.cpp — YOUR CODE for chapter 12. See path_tracing.hpp for the
// contracts and README.md for the lecture. Suggested order:
// cosine_hemisphere_pdf, cosine_hemisphere, light_contribution,
// roulette_weight, path_radiance (each one's tests pass on its own).
#include "path_tracing.hpp"

#include "common/stub.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace rt::ch12 {

template <class T>
T cosine_hemisphere_pdf(const vec3<T>& normal, const vec3<T>& direction) {
    // cos(theta) / pi above the surface, 0 below (and for a NaN).
    (void)normal;
    (void)direction;
    RT_NOT_IMPLEMENTED("chapter 12", "cosine_hemisphere_pdf");
}

template <class T>
direction_sample<T> cosine_hemisphere(const vec3<T>& normal, T u1, T u2) {
    // A uniform point on the unit disc (radius sqrt(u1), angle 2 pi u2),
    // lifted onto the hemisphere, in tangent_frame(normal); its density.
    (void)normal;
    (void)u1;
    (void)u2;
    RT_NOT_IMPLEMENTED("chapter 12", "cosine_hemisphere");
}

template <class T>
color light_contribution(const color& albedo, const vec3<T>& normal, const light_sample<T>& l) {
    // BRDF times radiance times cosine, divided by the sample's density.
    (void)albedo;
    (void)normal;
    (void)l;
    RT_NOT_IMPLEMENTED("chapter 12", "light_contribution");
}

template <class T>
T roulette_weight(const color& throughput, T u) {
    // Survive with probability p = min(1, largest channel); weigh a survivor by 1/p.
    (void)throughput;
    (void)u;
    RT_NOT_IMPLEMENTED("chapter 12", "roulette_weight");
}

template <class T>
color path_radiance(const path_scene<T>& s, const ray<T>& camera_ray, const interval<T>& camera_range,
                    const std::vector<bounce_numbers<T>>& numbers, const path_settings& settings) {
    // The loop of path_tracing.hpp, steps 1-7: emission (unless the light
    // sample counted it), the light sample, the next direction, roulette.
    (void)s;
    (void)camera_ray;
    (void)camera_range;
    (void)numbers;
    (void)settings;
    RT_NOT_IMPLEMENTED("chapter 12", "path_radiance");
}

// Compile the exercise for both precisions. Leave these lines as they are.
template float cosine_hemisphere_pdf(const vec3<float>&, const vec3<float>&);
template double cosine_hemisphere_pdf(const vec3<double>&, const vec3<double>&);
template direction_sample<float> cosine_hemisphere(const vec3<float>&, float, float);
template direction_sample<double> cosine_hemisphere(const vec3<double>&, double, double);
template color light_contribution(const color&, const vec3<float>&, const light_sample<float>&);
template color light_contribution(const color&, const vec3<double>&, const light_sample<double>&);
template float roulette_weight(const color&, float);
template double roulette_weight(const color&, double);
template color path_radiance(const path_scene<float>&, const ray<float>&, const interval<float>&,
                             const std::vector<bounce_numbers<float>>&, const path_settings&);
template color path_radiance(const path_scene<double>&, const ray<double>&, const interval<double>&,
                             const std::vector<bounce_numbers<double>>&, const path_settings&);

}  // namespace rt::ch12
