// transform.hpp — affine transforms, and chapter 10's first exercises:
//   transform_ray     (transform.cpp)  a ray taken into another space, t kept
//   transform_normal  (transform.cpp)  a normal brought back, by the inverse transpose
//   instance_box      (transform.cpp)  the box of a transformed box, widened against rounding
//
// An affine transform maps a point x to A x + b: A is a 3x3 matrix (rotation,
// scale, shear), b a translation. Stored as 3x4: the three columns of A, then
// b. The given part of this file makes transforms (translate, scale, rotate,
// compose) and pairs each with its inverse (make_placement, which refuses a
// transform that has none). README.md, "Affine transforms", is the lecture.
#pragma once

#include "08-acceleration/aabb.hpp"

#include "common/math.hpp"
#include "common/ray.hpp"

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>

namespace rt::ch10 {

// x -> linear * x + translation. glm matrices are column-major: linear[c] is
// column c, linear[c][r] the entry in row r. The identity by default.
template <class T>
struct affine3 {
    glm::mat<3, 3, T, glm::defaultp> linear{T(1)};
    vec3<T> translation{0, 0, 0};
};

// The same transform in another precision (each entry rounded once).
template <class To, class From>
affine3<To> convert_affine(const affine3<From>& m) {
    affine3<To> out;
    for (int c = 0; c < 3; ++c) out.linear[c] = convert<To>(m.linear[c]);
    out.translation = convert<To>(m.translation);
    return out;
}

// gamma(n) = n u / (1 - n u), u = epsilon / 2 the unit roundoff: a sum of n
// rounded terms (a dot product of n products, say) is within gamma(n) times
// the sum of the terms' magnitudes of the exact sum (Higham, "Accuracy and
// Stability of Numerical Algorithms", section 3.1; pbrt-v4 uses the same).
template <class T>
constexpr T gamma(int n) {
    const T u = std::numeric_limits<T>::epsilon() / 2;
    return T(n) * u / (T(1) - T(n) * u);
}

// ---- making transforms (given) ------------------------------------------

inline affine3<double> translate(const vec3d& offset) {
    affine3<double> m;
    m.translation = offset;
    return m;
}

inline affine3<double> scale(const vec3d& factors) {
    affine3<double> m;
    for (int k = 0; k < 3; ++k) m.linear[k][k] = factors[k];
    return m;
}

// A turn of `degrees` about `axis` (any non-zero length), right-handed.
inline affine3<double> rotate(const vec3d& axis, double degrees) {
    const double radians = degrees * std::acos(-1.0) / 180;
    affine3<double> m;
    m.linear = glm::mat<3, 3, double>(glm::rotate(glm::mat<4, 4, double>(1.0), radians, glm::normalize(axis)));
    return m;
}

// The transform whose columns are the images of the axes, u v w, and origin o.
inline affine3<double> frame(const vec3d& u, const vec3d& v, const vec3d& w, const vec3d& o = vec3d(0)) {
    affine3<double> m;
    m.linear = glm::mat<3, 3, double>(u, v, w);
    m.translation = o;
    return m;
}

// outer after inner: x -> outer(inner(x)).
inline affine3<double> compose(const affine3<double>& outer, const affine3<double>& inner) {
    affine3<double> m;
    m.linear = outer.linear * inner.linear;
    m.translation = outer.linear * inner.translation + outer.translation;
    return m;
}

// A transform and its inverse: to_world takes an object's own coordinates to
// the world, to_object takes world coordinates back (to_object(to_world(x))
// = x, up to rounding).
template <class T>
struct placement {
    affine3<T> to_world;
    affine3<T> to_object;
};

// How far from singular a transform may be: |det A| / (|a0| |a1| |a2|) is the
// volume of the box spanned by A's columns made unit length (1 for any
// rotation times scale, 0 for columns in one plane). Below this, A flattens
// space (or nearly): a ray cannot be taken into the object's space.
inline constexpr double least_column_volume = 1e-9;

// make_placement — the transform and its inverse, each rounded once to T.
// The inverse is computed in long double from the adjugate (A^-1 = adj(A) /
// det A, b' = -A^-1 b), so the rounding to T is its only error that matters.
// Throws std::invalid_argument, naming `what` (a scene file's line, say),
// for a transform with a non-finite entry or a singular (or nearly singular)
// linear part: a scale of 0, two columns parallel, all three in one plane.
template <class T>
placement<T> make_placement(const affine3<double>& to_world, const std::string& what = "a transform") {
    using L = long double;
    for (int c = 0; c < 3; ++c)
        if (!is_finite(to_world.linear[c]))
            throw std::invalid_argument(what + ": a matrix entry is not a finite number");
    if (!is_finite(to_world.translation))
        throw std::invalid_argument(what + ": the translation is not a finite number");
    const glm::mat<3, 3, L> a(to_world.linear);
    const L det = glm::dot(a[0], glm::cross(a[1], a[2]));
    const L lengths = glm::length(a[0]) * glm::length(a[1]) * glm::length(a[2]);
    if (!(std::fabs(det) > L(least_column_volume) * lengths)) {
        std::ostringstream s;
        s.precision(3);
        s << what << " is singular (determinant " << double(det)
          << "): it flattens space, so it has no inverse and a ray cannot be taken into the object's space; "
             "give a linear part whose three columns are independent (no scale of 0)";
        throw std::invalid_argument(s.str());
    }
    // Rows of the inverse are the cross products of pairs of columns, over det.
    const vec3<L> r0 = glm::cross(a[1], a[2]) / det;
    const vec3<L> r1 = glm::cross(a[2], a[0]) / det;
    const vec3<L> r2 = glm::cross(a[0], a[1]) / det;
    const glm::mat<3, 3, L> inverse = glm::transpose(glm::mat<3, 3, L>(r0, r1, r2));
    affine3<L> back;
    back.linear = inverse;
    back.translation = -(inverse * vec3<L>(to_world.translation));
    affine3<L> forth;
    forth.linear = a;
    forth.translation = vec3<L>(to_world.translation);
    return {convert_affine<T>(forth), convert_affine<T>(back)};
}

// ---- the exercises ------------------------------------------------------

// transform_ray — the ray r as seen in the space m maps to.
//
// Inputs
//   m  an affine transform x -> A x + b (placement::to_object, to take a world
//      ray into an object's space)
//   r  a ray o + t d; d of any non-zero length (not unit in general)
//
// Returns the ray o' + t d' with
//     o' = A o + b    (a point: it moves with the translation)
//     d' = A d        (a direction, a difference of two points: the
//                      translation cancels; NOT normalised)
// so that o' + t d' = m(o + t d) for every t: the same t names the same point
// in both spaces, and an object's hit at t in its own space is the world
// ray's hit at t. Computed in T as written: each component of A o is a sum of
// three products, then b is added.
//
// Bound (what the tests check, against the same inputs in higher precision):
// every component k is within
//     gamma(4) * (|A| |o| + |b|)_k   of the exact o'_k, and
//     gamma(3) * (|A| |d|)_k         of the exact d'_k,
// where |A| is A with every entry made non-negative.
template <class T>
ray<T> transform_ray(const affine3<T>& m, const ray<T>& r);

// transform_normal — an object's normal, in the world.
//
// Inputs
//   p  the instance's placement (p.to_world has linear part A, p.to_object
//      holds A^-1, as make_placement makes them)
//   n  a normal of the object at a point, in the object's space, non-zero
//
// Returns the unit world normal  normalize((A^-1)^T n)  = normalize of
// p.to_object.linear transposed times n. Not A n: a tangent t (dot(n, t) = 0)
// goes to A t, and dot((A^-1)^T n, A t) = dot(n, A^-1 A t) = 0, so the
// inverse transpose keeps the normal perpendicular to the surface under any
// non-uniform scale or shear, where A n does not. The translation plays no
// part (a normal is a direction).
// Bound: for every tangent t, |dot(result, A t)| <= 16 epsilon |A t| for
// transforms with scales from 0.2 to 5 and shears up to 1 (the tests' range;
// the error grows with how far A is from a rotation: README, "Rounding,
// measured"), and the result's length is 1 within 4 epsilon.
template <class T>
vec3<T> transform_normal(const placement<T>& p, const vec3<T>& n);

// instance_box — the box, in the world, of whatever lies inside `box` in the
// object's own space.
//
// Inputs
//   to_world  the instance's transform x -> A x + b
//   box       a box in the object's space (ch08::aabb); may be empty, flat or
//             a point
//
// Returns the empty box for an empty box; otherwise the box around the eight
// corners of `box`, each mapped by to_world in T (as transform_ray maps an
// origin), widened: lo_k -= pad_k and hi_k += pad_k with
//     pad_k = 3 * gamma(4) * M_k,   M_k = max over the corners c of (|A| |c| + |b|)_k.
// Why the corners: an affine map takes the box to a parallelepiped whose
// extreme points are images of corners, so the box of the eight images holds
// it (the box's own lo and hi alone do not: a rotation moves the other
// corners outside). Why widened: each computed corner, and each hit point a
// renderer computes as A p + b (instance_hit), is within gamma(4) M_k of
// exact; twice that covers both, and the third gamma(4) the rounding of the
// subtraction and addition that widen. The promise the tests check: the box
// contains every point A p + b, p inside `box`, exact or computed in T.
template <class T>
ch08::aabb<T> instance_box(const affine3<T>& to_world, const ch08::aabb<T>& box);

}  // namespace rt::ch10
