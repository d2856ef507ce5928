// scene.hpp — what a picture is made of: shapes, their materials, lights.
//
// A scene is plain data. Each shape has a material index; lights are points
// with an intensity, plus one ambient term. Chapters 03 to 06 read theirs
// from scenes/chNN-*.json (scene_file.hpp) and hand it to the students' code.
// Below the data: how an object number names a shape, and the material of a
// hit (with the checker pattern) - bookkeeping, no intersection or shading.
#pragma once

#include "hit_record.hpp"
#include "math.hpp"
#include "shapes.hpp"

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

namespace rt {

// How a surface responds to light: the parameters chapter 06 shades with,
// the two chapter 09 traces secondary rays for, and the light chapter 12's
// surfaces give off.
struct material {
    color diffuse{0.8f, 0.8f, 0.8f};   // diffuse reflectance, per channel, in [0, 1]
    color specular{0.0f, 0.0f, 0.0f};  // highlight colour
    float shininess = 32.0f;           // highlight exponent: larger is a smaller, sharper highlight
    bool checker = false;              // planes: alternate diffuse and checker_color in unit squares
    color checker_color{0.2f, 0.2f, 0.2f};
    color mirror{0.0f, 0.0f, 0.0f};    // chapter 09: the fraction reflected in the mirror direction, per channel
    float ior = 0.0f;                  // chapter 09: > 0 makes the surface glass with this index of refraction
                                       // (light split between reflection and refraction by Fresnel's equations)
    color emission{0.0f, 0.0f, 0.0f};  // chapter 12: the radiance the surface gives off, the same in every
                                       // direction (a lamp you can see and hit); chapters before 12 ignore it
};

struct point_light {
    vec3d position{0, 0, 0};
    color intensity{1, 1, 1};  // radiant intensity; falls off as 1 / distance^2
    // 0: a point. > 0: a sphere light of this radius around `position`
    // (chapter 11), glowing with radiance intensity / (pi radius^2), so that
    // seen from afar it lights a surface as the point light would; only its
    // shadows are soft. Chapters before 11 treat it as the point.
    double radius = 0;
};

template <class T>
struct scene {
    std::vector<sphere<T>> spheres;
    std::vector<plane<T>> planes;
    std::vector<triangle<T>> triangles;
    std::vector<material> materials;  // each shape's `material` indexes this
    std::vector<point_light> lights;
    color ambient{0.05f, 0.05f, 0.05f};
    color background{0.5f, 0.7f, 1.0f};

    // Objects are numbered spheres first, then planes, then triangles: the
    // number a hit_record's `object` field carries.
    int object_count() const { return int(spheres.size() + planes.size() + triangles.size()); }
};

// Which shape an object number names: object_count() numbers are spheres,
// then planes, then triangles; index is the position in that kind's list.
enum class shape_kind { sphere, plane, triangle };
struct object_ref {
    shape_kind kind;
    size_t index;
};

// Throws std::out_of_range, with a message a student can act on, for a
// number that names no object (a closest_hit that forgot to set `object`).
template <class T>
object_ref locate(const scene<T>& s, int object) {
    if (!(object >= 0 && object < s.object_count()))
        throw std::out_of_range("a hit with object index " + std::to_string(object) +
                                ": the scene loop must set hit.object to the index of the object hit (0 to " +
                                std::to_string(s.object_count() - 1) + ")");
    size_t i = size_t(object);
    if (i < s.spheres.size()) return {shape_kind::sphere, i};
    i -= s.spheres.size();
    if (i < s.planes.size()) return {shape_kind::plane, i};
    return {shape_kind::triangle, i - s.planes.size()};
}

template <class T>
int material_index(const scene<T>& s, int object) {
    const object_ref o = locate(s, object);
    if (o.kind == shape_kind::sphere) return s.spheres[o.index].material;
    if (o.kind == shape_kind::plane) return s.planes[o.index].material;
    return s.triangles[o.index].material;
}

// The two unit directions a checker pattern is laid out along: squares are
// [i, i + 1) x [j, j + 1) in (point . u, point . v).
struct checker_axes {
    vec3d u{1, 0, 0}, v{0, 0, 1};  // the x-z plane: a ground at y = const
};

// A plane's own checker axes: the two world axes other than the one its
// normal points along most, each made perpendicular to the normal (and v to
// u). For a plane perpendicular to a world axis they are exactly the other
// two world axes, in order: x and z for a ground at y = const (the chapters'
// scenes), x and y for one at z = const (the SPD scenes, z up). Along the
// normal they do not change, so a hit point a rounding error off the plane
// never flickers between squares. A normal of any finite non-zero length.
inline checker_axes checker_axes_of(const vec3d& normal) {
    const vec3d a = glm::abs(normal);
    const int up = a.x >= a.y && a.x >= a.z ? 0 : a.y >= a.z ? 1 : 2;
    const vec3d n = normalize(normal / a[up]);  // divided first: no square under- or overflows
    vec3d u(0), v(0);
    u[up == 0 ? 1 : 0] = 1;
    v[up == 2 ? 1 : 2] = 1;
    u = normalize(u - dot(u, n) * n);
    v = normalize(v - dot(v, n) * n - dot(v, u) * u);
    return {u, v};
}

// m as seen at `point`: a checker material alternates m.diffuse and
// m.checker_color in unit squares along the two axes (default: the x-z
// plane; a plane's hit uses checker_axes_of its normal, see below). The
// third direction does not pick the square: it would make the colour flicker
// on a plane at y = 0, where computed hit points land a rounding error above
// or below zero at random. m is returned unchanged when it has no pattern or
// the point is not finite.
template <class T>
material material_at(const material& m, const vec3<T>& point, const checker_axes& axes = {}) {
    if (!m.checker || !is_finite(point)) return m;
    const vec3d p(point);
    // fmod rather than a cast to an integer: a huge coordinate stays defined.
    const double squares = std::floor(dot(p, axes.u)) + std::floor(dot(p, axes.v));
    material here = m;
    if (std::fmod(squares, 2.0) != 0.0) here.diffuse = m.checker_color;
    return here;
}

// The material at a hit of the scene (hit.object names the object).
template <class T>
material material_at(const scene<T>& s, const hit_record<T>& hit) {
    const material& m = s.materials[size_t(material_index(s, hit.object))];
    const object_ref o = locate(s, hit.object);
    if (!m.checker || o.kind != shape_kind::plane) return material_at(m, hit.point);
    return material_at(m, hit.point, checker_axes_of(vec3d(s.planes[o.index].normal)));
}

}  // namespace rt
