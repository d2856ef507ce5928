// fast_path_kernels.hpp — the specialised path's plane and triangle tests.
//
// One ray against one plane or triangle, written for the lane loops of
// fast_path.cpp (no branch in the common case, so a loop over 8 or 32 rays
// is vectorised; the functions are small and inlined into those loops, so
// each instruction-set copy of fast_path.cpp compiles them for its own
// vector units; always_inline makes sure of it). In a header of their own so that tests/numerics can check
// them on inputs built to be hard (render_kernel_test.cpp).
#pragma once

// Exact "is d.n (or e1.(d x e2)) zero?": the course's formulations and this
// path decide parallel rays and degenerate triangles the same way.
#include "solutions/07-precision/formulations/exact_sign.hpp"

#include "common/math.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace rt::render_tool {

// Parallel rays, rays in a plane and degenerate triangles are misses. The
// denominator d.n (a plane) or determinant e1.(d x e2) (a triangle) can come
// out as a tiny non-zero number although the exact one is 0, and the ray
// would then hit at a huge or arbitrary t. So each lane also compares the
// rounded value with a bound on its rounding error: beyond it, the exact
// value is certainly not 0 (the common case, a few operations per lane);
// within it (rare), the lane is left out here and `unsure` is set, and the
// caller runs the scalar *_exact version below on the packet, which decides
// exactly (exact_sign.hpp) and otherwise computes the very same t.
// "Exactly" is for the scene's own shapes rounded to T (for double, the
// scene's shapes): a triangle's corners, a plane's normal as given.
// Directions: any non-zero finite one, subnormal components included (see
// direction_max). Triangles whose edge products underflow are not rescaled.
// The sphere kernels (fast_path_spheres.hpp) compute a = d.d and 1 / a
// plainly, which underflow or overflow for a direction far from length 1
// (|d| about 1e-20 in float already: d.d = 1e-40 is below the normal range).
// They never see one: closest_hits and any_hit (fast_path_queries.hpp) give
// a ray whose direction_scale is not 0 its direction scaled by 2^e and the
// range by 2^-e, and scale the answer back (exact: t = 2^e t').
template <class T>
inline constexpr T half_ulp = std::numeric_limits<T>::epsilon() / 2;

// Below this, d.n may have lost digits to underflow (a product of a
// subnormal direction component with the normal): 2^p times the smallest
// normal number (2 min / epsilon, epsilon being 2^(1-p)), so that what the
// subnormal products lost is below 2^-2p of d.n.
template <class T>
inline constexpr T underflow_den = T(2) * std::numeric_limits<T>::min() / std::numeric_limits<T>::epsilon();

// One plane against one ray; num = n . (point - origin). The bound is
// parallel_exactly's filter (each product and sum rounds relative to
// itself), and a d.n small enough to have lost digits to underflow is left
// to plane_t_exact too, which scales the direction: t keeps its digits for
// a subnormal direction as well.
template <class T>
[[gnu::always_inline]] inline T plane_t(T num, T nx, T ny, T nz, T dx, T dy, T dz, T tmin, int& unsure) {
    const T den = nx * dx + ny * dy + nz * dz;
    const T bound = T(8) * half_ulp<T> * (std::fabs(nx * dx) + std::fabs(ny * dy) + std::fabs(nz * dz)) +
                    underflow_den<T>;
    const bool small = std::fabs(den) <= bound;  // false for NaN (padding): rejected below anyway
    unsure |= int(small);
    const T t = num / den;  // exactly 0: +-inf or NaN, both rejected
    return ((t > tmin) & !small) ? t : infinity<T>;
}

// The same, deciding d.n = 0 exactly: for the lanes plane_t was unsure of.
// The decision is made on the plane's own normal (as given to the renderer,
// rounded to T), not on the unit normal of the lanes: normalising rounds, and
// a ray exactly parallel to the plane need not be parallel to the rounded
// unit normal (d.n within the lane's bound sends such a ray here).
// A direction so small that d.n underflows (non-zero subnormal components)
// is scaled by a power of two first: t = 2^k t' exactly (direction_scale).
template <class T>
T plane_t_exact(T num, T nx, T ny, T nz, T dx, T dy, T dz, T tmin, const vec3<T>& normal) {
    if (formulations::parallel_exactly(vec3<T>(dx, dy, dz), normal)) return infinity<T>;
    const int k = formulations::direction_scale(vec3<T>(dx, dy, dz));
    const T t = std::ldexp(num / (nx * std::ldexp(dx, k) + ny * std::ldexp(dy, k) + nz * std::ldexp(dz, k)), k);
    return t > tmin ? t : infinity<T>;
}

// A bound on the rounding error of Moeller-Trumbore's determinant, over
// d_max = max |d_i| (the lane's part): the error is at most 8 u times
// sum |e1_i| (|d_j e2_k| + |d_k e2_j|) (flat_exactly's filter), and that sum
// is at most 2 d_max ||e1||_1 max |e2_i|. Per triangle, outside the lanes.
template <class T>
inline T flat_scale(T e1x, T e1y, T e1z, T e2x, T e2y, T e2z) {
    return T(16) * half_ulp<T> * (std::fabs(e1x) + std::fabs(e1y) + std::fabs(e1z)) *
           std::max(std::max(std::fabs(e2x), std::fabs(e2y)), std::fabs(e2z));
}

// One triangle against one ray (Moeller-Trumbore). s = origin - a and
// q = s x e1 depend only on the origin and the triangle. flat_bound =
// flat_scale * d_max + a few subnormals (products of three that underflow).
// Not watertight: u, v and t are rounded per triangle, so a ray through an
// edge shared by two triangles of a closed mesh can miss both (the study's
// Moeller-Trumbore formulation, the same arithmetic, leaks 1716 of its
// closed-mesh rays in float: tools/study/results); a stray pixel
// on such an edge is what the renderer accepts for its speed. The
// formulations' watertight test (Woop, Benthin and Wald) leaks none.
template <class T>
[[gnu::always_inline]] inline T triangle_t(T sx, T sy, T sz, T qx, T qy, T qz, T e1x, T e1y, T e1z, T e2x, T e2y, T e2z, T dx, T dy, T dz,
                    T tmin, T flat_bound, int& unsure) {
    const T px = dy * e2z - dz * e2y, py = dz * e2x - dx * e2z, pz = dx * e2y - dy * e2x;
    const T det = e1x * px + e1y * py + e1z * pz;
    const bool small = std::fabs(det) <= flat_bound;  // false for NaN (padding): rejected below anyway
    unsure |= int(small);
    const T inv_det = T(1) / det;
    const T u = (sx * px + sy * py + sz * pz) * inv_det;
    const T v = (dx * qx + dy * qy + dz * qz) * inv_det;
    const T t = (e2x * qx + e2y * qy + e2z * qz) * inv_det;
    // Edges count as inside; NaN fails every test.
    return ((u >= T(0)) & (v >= T(0)) & (u + v <= T(1)) & (t > tmin) & !small) ? t : infinity<T>;
}

// The same, deciding e1.(d x e2) = 0 (a ray parallel to the triangle's
// plane or in it, or a degenerate triangle) exactly: for the lanes
// triangle_t was unsure of. The decision is made on the triangle's corners
// a, b, c (as given to the renderer, rounded to T), not on the edges: an
// edge b - a is rounded, and the rounded edges of a triangle with exactly
// collinear corners, or one with the ray exactly in its plane, need not be
// flat.
// A non-zero direction too small for its products to stay normal (the lane
// was sent here by direction_max's infinite bound) is scaled by a power of
// two first: o + t' (2^k d) is o + t d with t = 2^k t', so t scales back
// exactly and u, v do not change.
template <class T>
T triangle_t_exact(T sx, T sy, T sz, T qx, T qy, T qz, T e1x, T e1y, T e1z, T e2x, T e2y, T e2z, T dx, T dy, T dz,
                   T tmin, const vec3<T>& a, const vec3<T>& b, const vec3<T>& c) {
    if (formulations::flat_exactly(vec3<T>(dx, dy, dz), a, b, c)) return infinity<T>;
    const int k = formulations::direction_scale(vec3<T>(dx, dy, dz));
    int ignored = 0;
    const T t = triangle_t(sx, sy, sz, qx, qy, qz, e1x, e1y, e1z, e2x, e2y, e2z, std::ldexp(dx, k), std::ldexp(dy, k),
                           std::ldexp(dz, k), -infinity<T>, T(-1), ignored);
    const T back = std::ldexp(t, k);  // infinity (a miss) stays infinity
    return back > tmin ? back : infinity<T>;
}

// The absolute part of the determinant's bound: a product of three numbers
// that underflows is off by up to half a subnormal, more than any relative bound.
template <class T>
inline T flat_tiny() {
    return T(16) * std::numeric_limits<T>::denorm_min();
}

// max |d_i|, the ray's part of the determinant's bound; infinite for a
// non-zero direction so small that the lane's products would underflow
// (subnormal components: the rounded u, v, t would be meaningless), or so
// large that they could overflow (exact_sign.hpp's direction_scale). With an
// infinite bound every lane of that ray is "unsure", and triangle_t_exact
// answers it on the direction scaled by a power of two. One compare per ray,
// none per triangle. (A zero direction keeps d_max = 0: the determinant is 0
// and the lane misses.)
template <class T>
inline T direction_max(T dx, T dy, T dz) {
    const T m = std::max(std::max(std::fabs(dx), std::fabs(dy)), std::fabs(dz));
    return formulations::direction_scale(vec3<T>(dx, dy, dz)) != 0 ? infinity<T> : m;
}

// One slab of a ray's box test, chapter 08's rule (solutions/08-acceleration),
// for every walk in tools/render: inv = 1 / d, infinite for a zero
// component; the near face is lo for a positive reciprocal and hi for a
// negative one (-0's reciprocal is -inf: negative too); the exit is widened
// by `widen` (a few ulps, Ize 2013); and the running entry and exit are
// updated by comparisons that keep the old value when the new one is NaN.
// A NaN, (face - o) * inf = 0 * inf, comes only from a ray parallel to the
// slab with its origin on one of its face planes; such a ray lies in the
// closed slab for every t, so the slab constrains nothing, which is what
// keeping the old value gives. Only selects: a loop over rays is vectorised.
//
// slab_faces is the part after the choice of faces, for a caller that has
// already chosen them (a packet whose rays all point the same way along the
// axis chooses once per box: rays_entering in fast_path_traversal.hpp).
template <class T>
[[gnu::always_inline]] inline void slab_faces(T near, T far, T o, T inv, T widen, T& enter, T& leave) {
    const T t0 = (near - o) * inv;
    const T t1 = (far - o) * inv * widen;
    enter = t0 > enter ? t0 : enter;
    leave = t1 < leave ? t1 : leave;
}

template <class T>
[[gnu::always_inline]] inline void slab_axis(T lo, T hi, T o, T inv, T widen, T& enter, T& leave) {
    const bool down = inv < 0;
    slab_faces(down ? hi : lo, down ? lo : hi, o, inv, widen, enter, leave);
}

}  // namespace rt::render_tool
