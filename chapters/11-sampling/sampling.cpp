// sampling.cpp — YOUR CODE for chapter 11. See sampling.hpp for the contracts
// and README.md for the lecture. Suggested order: stratified_sample,
// filter_weight, pixel_estimate, sample_sphere_light, sphere_light_pdf,
// thin_lens_ray (each one's tests pass on its own).
#include "sampling.hpp"

#include "common/stub.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>

namespace rt::ch11 {

template <class T>
vec2<T> stratified_sample(int k, int n, const vec2<T>& u) {
    // Column k % n, row k / n; move u into that cell of side 1/n, and keep
    // a value that rounded onto the cell's upper edge inside the cell.
    (void)k;
    (void)n;
    (void)u;
    RT_NOT_IMPLEMENTED("chapter 11", "stratified_sample");
}

template <class T>
T filter_weight(filter_kind f, const vec2<T>& offset) {
    // Box: 1 inside the pixel's half-open square. Tent: the product of two
    // triangles that fall from 1 at the centre to 0 a pixel away.
    (void)f;
    (void)offset;
    RT_NOT_IMPLEMENTED("chapter 11", "filter_weight");
}

template <class T>
color pixel_estimate(filter_kind f, const std::vector<pixel_sample<T>>& samples) {
    // The weighted mean of the samples' colours: divide by the sum of the weights.
    (void)f;
    (void)samples;
    RT_NOT_IMPLEMENTED("chapter 11", "pixel_estimate");
}

template <class T>
std::optional<light_sample<T>> sample_sphere_light(const sphere<T>& light, const vec3<T>& from, const vec2<T>& u) {
    // The cone the light fills seen from `from`; a direction uniform in its
    // solid angle; where that direction's ray meets the sphere; the density.
    (void)light;
    (void)from;
    (void)u;
    RT_NOT_IMPLEMENTED("chapter 11", "sample_sphere_light");
}

template <class T>
T sphere_light_pdf(const sphere<T>& light, const vec3<T>& from, const vec3<T>& direction) {
    // The same density for every direction that meets the light, 0 elsewhere.
    (void)light;
    (void)from;
    (void)direction;
    RT_NOT_IMPLEMENTED("chapter 11", "sphere_light_pdf");
}

template <class T>
ray<T> thin_lens_ray(const pinhole_camera<T>& camera, const thin_lens<T>& lens, T px, T py, const vec2<T>& lens_u) {
    // The pinhole's direction through (px, py); a point of the lens's disc;
    // the ray from it through the point in focus.
    (void)camera;
    (void)lens;
    (void)px;
    (void)py;
    (void)lens_u;
    RT_NOT_IMPLEMENTED("chapter 11", "thin_lens_ray");
}

// Compile the exercise for both precisions. Leave these lines as they are.
#define RT_CH11_INSTANTIATE(T)                                                                                  \
    template vec2<T> stratified_sample(int, int, const vec2<T>&);                                              \
    template T filter_weight(filter_kind, const vec2<T>&);                                                     \
    template color pixel_estimate(filter_kind, const std::vector<pixel_sample<T>>&);                           \
    template std::optional<light_sample<T>> sample_sphere_light(const sphere<T>&, const vec3<T>&, const vec2<T>&); \
    template T sphere_light_pdf(const sphere<T>&, const vec3<T>&, const vec3<T>&);                             \
    template ray<T> thin_lens_ray(const pinhole_camera<T>&, const thin_lens<T>&, T, T, const vec2<T>&);
RT_CH11_INSTANTIATE(float)
RT_CH11_INSTANTIATE(double)
#undef RT_CH11_INSTANTIATE

}  // namespace rt::ch11
