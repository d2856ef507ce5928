// path_scene.hpp — the world a path tracer walks through, and the plumbing
// around chapter 12's exercise (nothing here is an exercise answer).
//
// A path_scene is plain data: spheres and planes (chapters 02 and 04), each
// with a surface saying how it reflects (a Lambertian albedo, or smooth glass)
// and what it emits (radiance), a list of the spheres that are lights (the
// ones next-event estimation samples), and the radiance of the background. It
// is read from a scene file (path_scene_of, below: scenes/README.md's format).
// Its closest hit is chapter 03's loop over chapters 02 and 04's tests; a ray
// leaves a matte surface from chapter 06's offset origin, and glass by chapter
// 09's optics and offset (glass_bounce).
//
// Units: colours are linear RGB. Emission and background are radiance (what
// a camera pixel shows when it sees them directly); an albedo in [0, 1] is
// the fraction of the light arriving at a point that leaves it again.
#pragma once

#include "02-sphere/sphere.hpp"
#include "03-scene-loop/scene_loop.hpp"
#include "04-plane/plane.hpp"
#include "06-shading/shading.hpp"
#include "09-reflection/whitted.hpp"

#include "common/object_dispatch.hpp"
#include "common/scene.hpp"
#include "common/scene_file.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

namespace rt::ch12 {

template <class T>
inline constexpr T pi = T(3.14159265358979323846);

// How one surface reflects and emits.
struct surface {
    color albedo{0.0f};    // Lambertian reflectance, each channel in [0, 1]
    color emission{0.0f};  // emitted radiance, the same in every direction
    float ior = 0.0f;      // > 0: smooth glass of this index of refraction (chapter 09), not matte:
                           // it reflects or refracts every ray (glass_bounce) and the albedo is unused
};

template <class T>
struct path_scene {
    scene<T> geometry;              // spheres and planes; each shape's `material` indexes `surfaces`
    std::vector<surface> surfaces;
    std::vector<int> lights;        // indices into geometry.spheres: the sphere lights NEE samples
    color background{0.0f};         // radiance of a ray that leaves the scene
};

// The path tracer's world as a scene file describes it (scenes/README.md).
// Each material becomes a surface: its diffuse colour is the albedo (the
// reader keeps it in [0, 1]), its emission the radiance it gives off. Every
// sphere whose material emits is a light that next-event estimation samples;
// an emitting plane still shines on what it sees, found only by bounces. A
// sphere light of the file's "lights" (chapter 11: radius > 0, radiance
// intensity / (pi radius^2)) becomes such a sphere too, after the file's own.
// A material with an "ior" is glass (chapter 09), whatever its diffuse colour.
// Left out, because this path tracer of matte surfaces and glass has no use for them
// (the chapter's program says which a file has): point lights (no area, so
// no bounce can ever hit one), triangles, highlights, mirrors, checker
// patterns and the ambient term (the bounces compute the light it stood for).
template <class T>
path_scene<T> path_scene_of(const scene_description& d) {
    path_scene<T> s;
    s.geometry = convert_scene<T>(d.world);
    s.geometry.triangles.clear();
    s.geometry.lights.clear();
    for (const material& m : d.world.materials) s.surfaces.push_back({m.diffuse, m.emission, m.ior});
    for (const point_light& l : d.world.lights) {
        if (!(T(l.radius) > T(0))) continue;  // a point: no area to hit or sample
        const float area = float(3.14159265358979323846 * l.radius * l.radius);
        s.surfaces.push_back({color(0.0f), l.intensity / area});
        s.geometry.spheres.push_back({convert<T>(l.position), T(l.radius), int(s.surfaces.size()) - 1});
    }
    for (size_t i = 0; i < s.geometry.spheres.size(); ++i) {
        const color& e = s.surfaces.at(size_t(s.geometry.spheres[i].material)).emission;
        if (e.r > 0.0f || e.g > 0.0f || e.b > 0.0f) s.lights.push_back(int(i));
    }
    s.background = d.world.background;
    return s;
}

// A ray's closest hit and the surface there.
template <class T>
struct surface_hit {
    hit_record<T> hit;        // hit.normal is unit and faces the ray: the face rule's facing_normal
    bool front_face = true;   // the ray arrived on the outward normal's side (entering a glass ball)
    surface material;
};

// The closest hit of r in range, through chapter 03's loop (chapters 02 and 04
// answer for each shape). The normal is turned to face the ray: a diffuse
// surface reflects on the side it is seen from.
template <class T>
std::optional<surface_hit<T>> closest_surface(const path_scene<T>& s, const ray<T>& r, const interval<T>& range) {
    const ch03::object_intersector<T> intersect =
        object_dispatch(s.geometry, ch02::intersect_sphere<T>, ch04::intersect_plane<T>).intersector();
    const std::optional<hit_record<T>> hit = ch03::closest_hit(s.geometry.object_count(), intersect, r, range);
    if (!hit) return std::nullopt;
    surface_hit<T> out{*hit, hit->front_face(r), {}};
    out.hit.normal = hit->facing_normal(r);  // the face rule (common/hit_record.hpp)
    const object_ref o = locate(s.geometry, hit->object);
    const int m = o.kind == shape_kind::sphere ? s.geometry.spheres[o.index].material : s.geometry.planes[o.index].material;
    out.material = s.surfaces.at(size_t(m));
    return out;
}

// Whether object number `object` is one of the scene's sphere lights.
template <class T>
bool is_light(const path_scene<T>& s, int object) {
    return std::find(s.lights.begin(), s.lights.end(), object) != s.lights.end();
}

// glass_bounce — the ray that leaves smooth glass (chapter 09's optics) when
// ray r meets it at h: reflected or refracted, one of the two, chosen by u.
//
// Glass reflects the share F of the light (fresnel_dielectric, with eta =
// 1 / ior entering and ior leaving) and lets 1 - F through (refract). A path
// cannot follow both rays, so it follows one at random: reflected when u < F,
// else refracted (total internal reflection: F = 1, always reflected). Each
// is chosen as often as its share of the light, so the share divided by the
// probability of the choice is F / F or (1 - F) / (1 - F): the throughput
// goes on unchanged. The new ray starts at chapter 09's offset origin, on the
// side it leaves by (spawn_ray), and its hits count for t > 0.
//
// Glass is a *specular* surface: it sends light arriving from one direction
// into one or two directions only, never spread over the hemisphere, so a
// light sample's direction is never one it reflects into the eye (that is
// why the path loop samples no light at a glass vertex).
template <class T>
ray<T> glass_bounce(const path_scene<T>& s, const surface_hit<T>& h, const ray<T>& r, T u) {
    const vec3<T>& n = h.hit.normal;  // faces the ray
    const T ior = T(h.material.ior);
    const T eta = h.front_face ? T(1) / ior : ior;  // n_incident / n_transmitted
    const std::optional<vec3<T>> refracted = ch09::refract(r.direction, n, eta);
    const T reflected_share = ch09::fresnel_dielectric(-dot(normalize(r.direction), n), eta);
    const vec3<T> next = refracted && !(u < reflected_share) ? *refracted : ch09::reflect(r.direction, n);
    return ch09::spawn_ray(ch09::surface_point_of(s.geometry, h.hit), n, next);
}

// An orthonormal frame (t, b, n) around a unit normal n, without a branch on
// a "not parallel" helper vector: Duff et al., "Building an Orthonormal Basis,
// Revisited" (JCGT 2017). Every sampling function of the chapter builds its
// local directions in this frame, so two correct solutions agree to rounding.
template <class T>
struct tangent_frame {
    vec3<T> t, b, n;
    explicit tangent_frame(const vec3<T>& unit_normal) : n(unit_normal) {
        const T sign = std::copysign(T(1), n.z);
        const T a = T(-1) / (sign + n.z);
        const T c = n.x * n.y * a;
        t = vec3<T>(T(1) + sign * n.x * n.x * a, sign * c, -sign * n.x);
        b = vec3<T>(c, sign + n.y * n.y * a, -n.y);
    }
    // local (x, y, z) -> world: x along t, y along b, z along n
    vec3<T> to_world(T x, T y, T z) const { return x * t + y * b + z * n; }
};

// The worked example of the lecture: a direction drawn uniformly over the
// hemisphere around `normal` (unit), from u1, u2 in [0, 1): z = cos(theta) =
// 1 - u1 is uniform in (0, 1], phi = 2 pi u2. Its density is 1 / (2 pi) per
// steradian, whatever the direction. Chapter 12's exercise is the cosine-
// weighted version.
template <class T>
vec3<T> uniform_hemisphere(const vec3<T>& normal, T u1, T u2) {
    const T z = T(1) - u1;
    const T r = std::sqrt(std::max(T(0), T(1) - z * z));
    const T phi = T(2) * pi<T> * u2;
    return tangent_frame<T>(normal).to_world(r * std::cos(phi), r * std::sin(phi), z);
}
template <class T>
inline constexpr T uniform_hemisphere_pdf = T(1) / (T(2) * pi<T>);

}  // namespace rt::ch12
