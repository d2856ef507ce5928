// sampling.cpp — reference solution for chapter 11.
#include "11-sampling/sampling.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>

namespace rt::ch11 {

namespace {

template <class T>
constexpr T pi = T(3.14159265358979323846264338327950288L);

// u in [0,1)^2, written so that NaN fails it.
template <class T>
bool in_unit_square(const vec2<T>& u) {
    return u.x >= T(0) && u.x < T(1) && u.y >= T(0) && u.y < T(1);
}

template <class T>
void require_unit_square(const vec2<T>& u, const char* who) {
    if (!in_unit_square(u)) throw std::invalid_argument(std::string(who) + ": u must lie in [0,1)^2");
}

// (i + x) / n moved into the half-open cell [i/n, (i+1)/n): the division
// is monotone, so only the upper edge can be reached, by rounding i + x up.
template <class T>
T into_cell(int i, int n, T x) {
    const T value = (T(i) + x) / T(n);
    const T upper = T(i + 1) / T(n);
    return value < upper ? value : std::nextafter(upper, T(0));
}

template <class T>
void require_sphere_light(const sphere<T>& light, const vec3<T>& from, const char* who) {
    if (!(light.radius > T(0) && std::isfinite(light.radius)))
        throw std::invalid_argument(std::string(who) + ": the light's radius must be > 0 and finite");
    if (!is_finite(light.center) || !is_finite(from))
        throw std::invalid_argument(std::string(who) + ": the light's centre and the point must be finite");
}

// The cone in which `from` sees the sphere: its axis and 1 - cos(theta_max).
template <class T>
struct light_cone {
    vec3<T> axis;            // unit, from `from` towards the centre
    T distance;              // from `from` to the centre
    T one_minus_cos_max;     // > 0 when there is a cone
};

template <class T>
std::optional<light_cone<T>> cone_of(const sphere<T>& light, const vec3<T>& from) {
    const vec3<T> to_centre = light.center - from;
    const T d = length(to_centre);
    if (!(d > light.radius)) return std::nullopt;  // on or inside the light: no cone
    const T ratio = light.radius / d;              // r / d, without squaring r or d (no overflow)
    const T s = ratio * ratio;                     // sin^2(theta_max)
    // 1 - cos = (1 - cos^2) / (1 + cos) = s / (1 + sqrt(1 - s)): no cancellation for a small light.
    const T one_minus_cos_max = s / (T(1) + std::sqrt(T(1) - s));
    if (!(one_minus_cos_max > T(0))) return std::nullopt;  // too small to see in T
    return light_cone<T>{to_centre / d, d, one_minus_cos_max};
}

template <class T>
T cone_pdf(const light_cone<T>& cone) {
    return T(1) / (T(2) * pi<T> * cone.one_minus_cos_max);
}

}  // namespace

template <class T>
vec2<T> stratified_sample(int k, int n, const vec2<T>& u) {
    if (!(n >= 1 && n <= 4096)) throw std::invalid_argument("stratified_sample: n must be in 1 .. 4096");
    if (!(k >= 0 && k < n * n)) throw std::invalid_argument("stratified_sample: k must be in 0 .. n*n - 1");
    require_unit_square(u, "stratified_sample");
    const int column = k % n, row = k / n;
    return {into_cell(column, n, u.x), into_cell(row, n, u.y)};
}

template <class T>
T filter_weight(filter_kind f, const vec2<T>& offset) {
    if (f == filter_kind::box) {
        const bool inside = offset.x >= T(-0.5) && offset.x < T(0.5) && offset.y >= T(-0.5) && offset.y < T(0.5);
        return inside ? T(1) : T(0);
    }
    // The tent: each factor falls linearly from 1 at the centre to 0 one pixel away.
    const T wx = T(1) - std::fabs(offset.x);
    const T wy = T(1) - std::fabs(offset.y);
    if (!(wx > T(0) && wy > T(0))) return T(0);  // outside the support, or NaN
    return wx * wy;
}

template <class T>
color pixel_estimate(filter_kind f, const std::vector<pixel_sample<T>>& samples) {
    T weight_sum = 0, r = 0, g = 0, b = 0;
    for (const pixel_sample<T>& s : samples) {
        if (!(std::isfinite(s.value.r) && std::isfinite(s.value.g) && std::isfinite(s.value.b)))
            throw std::invalid_argument("pixel_estimate: a sample's colour is not finite");
        const T w = filter_weight(f, s.offset);
        weight_sum += w;
        r += w * T(s.value.r);
        g += w * T(s.value.g);
        b += w * T(s.value.b);
    }
    if (!(weight_sum > T(0))) return color(0.0f);
    // The weighted mean: its weights add up to 1, so a constant stays that constant.
    return color(float(r / weight_sum), float(g / weight_sum), float(b / weight_sum));
}

template <class T>
std::optional<light_sample<T>> sample_sphere_light(const sphere<T>& light, const vec3<T>& from, const vec2<T>& u) {
    require_unit_square(u, "sample_sphere_light");
    require_sphere_light(light, from, "sample_sphere_light");
    const std::optional<light_cone<T>> cone = cone_of(light, from);
    if (!cone) return std::nullopt;

    // Uniform in solid angle over the cone: cos(theta) uniform in [cos(theta_max), 1].
    const T e = u.x * cone->one_minus_cos_max;  // 1 - cos(theta), without cancellation
    const T cos_theta = T(1) - e;
    const T sin_theta = std::sqrt(e * (T(2) - e));
    const T phi = T(2) * pi<T> * u.y;

    // An orthonormal frame around the axis (Duff et al. 2017), branch-free.
    const vec3<T>& w = cone->axis;
    const T sg = std::copysign(T(1), w.z);
    const T a = T(-1) / (sg + w.z);
    const T c = w.x * w.y * a;
    const vec3<T> t(T(1) + sg * w.x * w.x * a, sg * c, -sg * w.x);
    const vec3<T> b(c, sg + w.y * w.y * a, -w.y);

    light_sample<T> s;
    s.direction = sin_theta * std::cos(phi) * t + sin_theta * std::sin(phi) * b + cos_theta * w;
    // The near root of |from + x direction - centre| = r.
    const T d = cone->distance;
    const T half_chord_sq = light.radius * light.radius - d * d * (e * (T(2) - e));
    s.distance = d * cos_theta - std::sqrt(std::fmax(T(0), half_chord_sq));
    s.point = from + s.distance * s.direction;
    s.normal = (s.point - light.center) / light.radius;
    s.pdf = cone_pdf(*cone);
    return s;
}

template <class T>
T sphere_light_pdf(const sphere<T>& light, const vec3<T>& from, const vec3<T>& direction) {
    require_sphere_light(light, from, "sphere_light_pdf");
    const std::optional<light_cone<T>> cone = cone_of(light, from);
    if (!cone) return T(0);
    const T len = length(direction);
    if (!(len > T(0) && std::isfinite(len))) return T(0);
    const vec3<T> dir = direction / len;
    // The ray meets the sphere when it heads towards the centre and passes
    // within r of it (the perpendicular distance: no cancellation near the rim).
    const vec3<T> to_centre = light.center - from;
    const T along = dot(to_centre, dir);
    if (!(along > T(0))) return T(0);
    const vec3<T> perpendicular = to_centre - along * dir;
    if (!(dot(perpendicular, perpendicular) <= light.radius * light.radius)) return T(0);
    return cone_pdf(*cone);
}

template <class T>
ray<T> thin_lens_ray(const pinhole_camera<T>& camera, const thin_lens<T>& lens, T px, T py, const vec2<T>& lens_u) {
    if (!(lens.aperture >= T(0) && std::isfinite(lens.aperture)))
        throw std::invalid_argument("thin_lens_ray: the aperture must be >= 0 and finite");
    if (!(lens.focus_distance > T(0) && std::isfinite(lens.focus_distance)))
        throw std::invalid_argument("thin_lens_ray: the focus distance must be > 0 and finite");
    if (!(std::isfinite(px) && std::isfinite(py))) throw std::invalid_argument("thin_lens_ray: px, py must be finite");
    require_unit_square(lens_u, "thin_lens_ray");

    // The pinhole's direction, as common/camera.hpp computes it.
    const camera_frame<T>& f = camera.frame;
    const T x = px / T(camera.width) * T(2) - T(1);
    const T y = T(1) - py / T(camera.height) * T(2);
    const vec3<T> d = x * camera.half_height * camera.aspect() * f.u + y * camera.half_height * f.v - f.w;
    if (lens.aperture == T(0)) return {f.eye, d};  // a lens of no size is the pinhole, to the last bit

    // A point of the lens, uniform over its disc.
    const T radius = lens.aperture * std::sqrt(lens_u.x);
    const T angle = T(2) * pi<T> * lens_u.y;
    const vec3<T> offset = radius * std::cos(angle) * f.u + radius * std::sin(angle) * f.v;
    // Through the point in focus, eye + focus_distance * d, from the lens point.
    return {f.eye + offset, d - offset / lens.focus_distance};
}

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
