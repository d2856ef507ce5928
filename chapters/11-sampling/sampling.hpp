// sampling.hpp — chapter 11's exercise: many samples per pixel, soft shadows, depth of field.
//
// Four small jobs, each a pure function: every random number it needs comes
// in as an argument (a point u of the unit square [0,1)^2), so the same
// arguments always give the same bits, and a test can check a call exactly.
// The chapter's program draws the numbers from a seeded generator, one
// stream per pixel (common/random.hpp), which makes its picture the same on
// every run and every thread count. Your code goes in sampling.cpp; README.md
// is the lecture behind the contracts.
//
//   stratified_sample     the jittered sample of stratum k of an n x n grid
//   filter_weight,        how much a sample counts towards its pixel, and the
//   pixel_estimate        pixel's value from its weighted samples
//   sample_sphere_light,  a point on a sphere light seen from a point, chosen
//   sphere_light_pdf      uniformly in the cone the light subtends, and the
//                         density of that choice per unit solid angle
//   thin_lens_ray         the primary ray of a camera with a lens (depth of field)
//
// Every function throws std::invalid_argument for an argument outside its
// contract (a u outside [0,1)^2, a NaN, a stratum that does not exist): a
// sample from a made-up number would be a silently wrong picture.
#pragma once

#include "common/camera.hpp"
#include "common/math.hpp"
#include "common/ray.hpp"
#include "common/shapes.hpp"

#include <optional>
#include <vector>

namespace rt::ch11 {

// A point of the plane: a sample u of the unit square, an offset in pixels.
template <class T>
using vec2 = glm::vec<2, T, glm::defaultp>;

// --- 1. stratified (jittered) sampling ----------------------------------------------------------------

// stratified_sample — sample k of n x n strata, jittered inside its stratum.
//
// The unit square is cut into n x n equal cells ("strata"). Stratum k is
// column i = k % n, row j = k / n, the cell [i/n, (i+1)/n) x [j/n, (j+1)/n).
// The sample is the point u of the unit square moved into that cell:
//     x = (i + u.x) / n,   y = (j + u.y) / n          (computed in T as written)
// Rounding can push x onto the cell's upper edge: for u.x just below 1 and
// i >= 1, i + u.x rounds up to i + 1. The cell is half-open, so such an x
// is replaced by the largest T below T(i + 1) / T(n) (the same for y). Then
// every sample lies in its own cell, and never in its neighbour's:
//     T(i) / T(n) <= x < T(i + 1) / T(n)        (both bounds one division in T)
// so the n * n samples k = 0 .. n*n-1 put exactly one sample in each cell.
//   * Throws std::invalid_argument unless 1 <= n <= 4096, 0 <= k < n * n and
//     u is in [0,1)^2 (NaN is not).
template <class T>
vec2<T> stratified_sample(int k, int n, const vec2<T>& u);

// --- 2. reconstruction filters -----------------------------------------------------------------------

// The filters a pixel's samples are weighted with. A sample's offset is its
// position minus the pixel's centre, in pixels (+x right, +y down the rows).
enum class filter_kind {
    box,   // the pixel's own square, every sample alike: support [-1/2, 1/2)^2
    tent,  // a pyramid over the 2 x 2 pixels around the centre: support (-1, 1)^2
};

// Half the side of the square a filter's samples are drawn from: 1/2 for the
// box, 1 for the tent. A sample's offset is (2 s - 1) * filter_radius for a
// sample s of the unit square.
template <class T>
constexpr T filter_radius(filter_kind f) {
    return f == filter_kind::box ? T(0.5) : T(1);
}

// filter_weight — how much a sample at `offset` from the pixel's centre counts.
//   box:  1 when -1/2 <= offset.x < 1/2 and -1/2 <= offset.y < 1/2, else 0
//         (half-open, so the pixels' squares tile the image plane);
//   tent: max(0, 1 - |offset.x|) * max(0, 1 - |offset.y|), computed in T as written.
// Never negative. An offset with a NaN component weighs 0.
template <class T>
T filter_weight(filter_kind f, const vec2<T>& offset);

// One sample of a pixel: where it was taken and the colour it saw there.
template <class T>
struct pixel_sample {
    vec2<T> offset;  // from the pixel's centre, in pixels
    color value;     // the radiance the sample's ray brought back
};

// pixel_estimate — the pixel's colour: the samples' colours weighted by the filter,
//     sum_k w_k * value_k / sum_k w_k,      w_k = filter_weight(f, samples[k].offset)
// both sums accumulated in T, in the samples' order, per channel; the result
// rounded to float. Dividing by the sum of the weights (not by the number of
// samples) is what keeps a pixel of one constant colour that colour under
// every filter.
//   * No sample, or all weights 0: black (0, 0, 0).
//   * Throws std::invalid_argument for a sample whose value is not finite.
template <class T>
color pixel_estimate(filter_kind f, const std::vector<pixel_sample<T>>& samples);

// --- 3. sampling a sphere light by solid angle -------------------------------------------------------

// A point chosen on a light, as seen from a point `from` in the scene.
template <class T>
struct light_sample {
    vec3<T> point;      // on the light's surface, facing `from`
    vec3<T> normal;     // the light's outward unit normal at `point`
    vec3<T> direction;  // unit vector from `from` towards `point`
    T distance = 0;     // |point - from|: a shadow ray's blockers lie in (0, distance)
    T pdf = 0;          // the density with which `direction` was chosen, per steradian
};

// sample_sphere_light — a point of the sphere light, chosen uniformly over
// the cone of directions in which `from` sees the light.
//
// Seen from `from`, the sphere (centre c, radius r) fills a cone around the
// axis w = (c - from) / d, d = |c - from|, of half-angle theta_max with
//     sin^2(theta_max) = s = (r / d)^2,   1 - cos(theta_max) = s / (1 + sqrt(1 - s))
// (that form of 1 - cos never subtracts two nearly equal numbers: for a small
// or far light, cos(theta_max) is 1 to many digits). The direction is
//     e = u.x * (1 - cos(theta_max))       (that is 1 - cos(theta))
//     cos(theta) = 1 - e,   sin(theta) = sqrt(e * (2 - e)),   phi = 2 pi u.y
//     direction  = sin(theta) cos(phi) t + sin(theta) sin(phi) b + cos(theta) w
// in the frame (t, b, w) of Duff et al., "Building an orthonormal basis,
// revisited" (JCGT 2017): with sg = copysign(1, w.z), a = -1 / (sg + w.z),
// c = w.x * w.y * a,
//     t = (1 + sg * w.x * w.x * a, sg * c, -sg * w.x),   b = (c, sg + w.y * w.y * a, -w.y)
// (no branch, and no division by a small number for any unit w). The
// choice spreads the directions uniformly over the cone's solid angle,
// 2 pi (1 - cos(theta_max)), so
//     pdf = 1 / (2 pi (1 - cos(theta_max)))      per steradian, the same for every direction
// The point is where the ray from `from` in that direction first meets the
// sphere, at the distance (the near root of chapter 01's quadratic, from
// d^2 sin^2(theta) = d^2 e (2 - e))
//     distance = d cos(theta) - sqrt(max(0, r^2 - d^2 e (2 - e))),   point = from + distance * direction
// and normal = (point - c) / r. On the cone's rim, where the ray only grazes
// the sphere, rounding may make r^2 - d^2 sin^2(theta) a hair negative: the
// max(0, ...) takes the tangent point then.
//   * nullopt when there is no cone: `from` on or inside the sphere (d <= r),
//     or the light too small or far for 1 - cos(theta_max) > 0 in T.
//   * Throws std::invalid_argument for u outside [0,1)^2, a radius that is
//     not > 0 and finite, or a non-finite centre or `from`.
template <class T>
std::optional<light_sample<T>> sample_sphere_light(const sphere<T>& light, const vec3<T>& from, const vec2<T>& u);

// sphere_light_pdf — the density per steradian with which sample_sphere_light
// picks `direction` (any length > 0) from `from`: 1 / (2 pi (1 - cos(theta_max)))
// when the ray from `from` along `direction` meets the sphere (the direction
// points towards the light and passes within r of the centre), else 0. Over
// all directions it integrates to 1. It is what a renderer needs to weigh a
// direction it found another way (chapter 12).
//   * 0 when there is no cone (as sample_sphere_light's nullopt) or for a
//     zero or non-finite direction.
//   * Throws std::invalid_argument for a bad radius, centre or `from` as above.
template <class T>
T sphere_light_pdf(const sphere<T>& light, const vec3<T>& from, const vec3<T>& direction);

// --- 4. the thin-lens camera -----------------------------------------------------------------------------

// A lens in front of the pinhole camera: a disc of radius `aperture` around
// the eye, perpendicular to the view direction, focused on the plane at
// distance `focus_distance` along the view direction.
template <class T>
struct thin_lens {
    T aperture = 0;        // the lens's radius; 0 is the pinhole camera
    T focus_distance = 1;  // > 0: what lies on this plane is sharp
};

// thin_lens_ray — the ray through the image point (px, py) and the lens point chosen by lens_u.
//
// (px, py) is a point of the image in pixels: pixel (col, row) covers
// [col, col + 1) x [row, row + 1), its centre is (col + 1/2, row + 1/2).
// Its normalised coordinates, as common/camera.hpp's pixel_center has them,
//     x = px / width * 2 - 1,   y = 1 - py / height * 2,
// give the pinhole's direction (the image plane at distance 1)
//     d = x * half_height * aspect * u + y * half_height * v - w
// (camera.half_height, camera.aspect(), camera.frame's u, v, w). The lens point is
//     offset = aperture * (sqrt(lens_u.x) cos(2 pi lens_u.y) u + sqrt(lens_u.x) sin(2 pi lens_u.y) v)
// (uniform over the disc: the square root makes equal areas equally likely),
// and the ray is
//     origin    = eye + offset
//     direction = d - offset / focus_distance
// so every lens point's ray passes through eye + focus_distance * d, the
// point that is in focus, and reaches the image plane at t = 1 as the
// pinhole's ray does (hits count for t > 1, chapter 01).
//   * aperture 0: exactly the pinhole camera's ray {eye, d}, bit for bit
//     (for px = col + 1/2, py = row + 1/2 that is camera.primary_ray(col, row)).
//   * Throws std::invalid_argument for a negative or non-finite aperture, a
//     focus_distance that is not > 0 and finite, a non-finite px or py, or
//     lens_u outside [0,1)^2.
template <class T>
ray<T> thin_lens_ray(const pinhole_camera<T>& camera, const thin_lens<T>& lens, T px, T py, const vec2<T>& lens_u);

}  // namespace rt::ch11
