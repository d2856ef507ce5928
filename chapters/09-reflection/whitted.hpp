// whitted.hpp — chapter 09's last exercise: the recursive ray tracer of
// Turner Whitted (1980). A ray that hits a mirror continues as a reflected
// ray; one that hits glass splits into a reflected and a refracted ray,
// weighted by Fresnel; every hit is also lit directly, with shadows
// (chapter 06). Your code goes in whitted.cpp.
//
// Above the exercise: given code that finds a hit and lights it with the
// earlier chapters' exercises, so trace() is only the recursion.
#pragma once

#include "optics.hpp"
#include "spawn.hpp"
#include "surface_error.hpp"

#include "02-sphere/sphere.hpp"
#include "03-scene-loop/scene_loop.hpp"
#include "04-plane/plane.hpp"
#include "05-triangle/triangle.hpp"
#include "06-shading/shading.hpp"

#include "common/interval.hpp"
#include "common/object_dispatch.hpp"
#include "common/ray.hpp"
#include "common/scene.hpp"

#include <optional>

namespace rt::ch09 {

// A hit, made ready for secondary rays (given code).
template <class T>
struct surface_hit {
    hit_record<T> hit;          // the shape's own answer (chapters 02, 04, 05), hit.object set
    surface_point<T> surface;   // hit.point put back on the surface, with its error bound
    vec3<T> outward{};          // the surface's unit normal on its outside (hit.normal)
    bool front_face = true;     // the ray arrived from the outside: dot(direction, outward) < 0
    material m;                 // the material at the hit (checker pattern resolved)

    // The normal on the side the ray came from: what reflect and refract take.
    vec3<T> facing_normal() const { return front_face ? outward : -outward; }
};

// hit.point put back on the object's surface, with its error bound.
template <class T>
surface_point<T> surface_point_of(const scene<T>& world, const hit_record<T>& hit) {
    const object_ref o = locate(world, hit.object);
    if (o.kind == shape_kind::sphere) return on_sphere(world.spheres[o.index], hit.point);
    if (o.kind == shape_kind::plane) return on_plane(world.planes[o.index], hit.point);
    return on_triangle(world.triangles[o.index], hit.point);
}

// The closest hit of r in range over the world's objects (chapter 03's loop
// with chapters 02, 04 and 05), made into a surface_hit; nullopt on a miss.
template <class T>
std::optional<surface_hit<T>> closest_surface_hit(const scene<T>& world, const ray<T>& r, const interval<T>& range) {
    const auto dispatch =
        object_dispatch(world, ch02::intersect_sphere<T>, ch04::intersect_plane<T>, ch05::intersect_triangle<T>);
    const ch03::object_intersector<T> intersect = dispatch.intersector();
    const std::optional<hit_record<T>> hit = ch03::closest_hit(world.object_count(), intersect, r, range);
    if (!hit) return std::nullopt;
    surface_hit<T> h;
    h.hit = *hit;
    h.surface = surface_point_of(world, *hit);
    h.outward = hit->normal;  // every shape reports its outward normal (common/hit_record.hpp)
    h.front_face = hit->front_face(r);
    h.m = material_at(world, *hit);
    return h;
}

// The light reaching the eye from h directly: chapter 06's shade(), its
// shadow rays answered by chapter 03's loop over the same world.
template <class T>
color local_light(const scene<T>& world, const surface_hit<T>& h, const ray<T>& r) {
    const auto dispatch =
        object_dispatch(world, ch02::intersect_sphere<T>, ch04::intersect_plane<T>, ch05::intersect_triangle<T>);
    const ch03::object_intersector<T> intersect = dispatch.intersector();
    const ch06::occlusion_test<T> occluded = [&](const ray<T>& shadow, const interval<T>& segment) {
        return ch03::closest_hit(world.object_count(), intersect, shadow, segment).has_value();
    };
    return ch06::shade(h.surface.point, h.facing_normal(), -r.direction, h.m, world.lights, world.ambient, occluded);
}

// How many bounces the chapter's program follows unless told (--depth N).
inline constexpr int default_depth = 5;

// A secondary ray whose colour would be scaled by less than this on its way
// to the eye is not traced: it could change the pixel by less than a quarter
// of one step of an 8-bit PNG.
inline constexpr float min_throughput = 1.0f / 1024.0f;

// trace — the colour seen along ray r (Whitted's recursion).
//
// Inputs   world       the scene (its materials' mirror and ior say what is shiny or glass)
//          r, range    the ray and where its hits count (primary rays: the camera's range;
//                      secondary rays: (0, infinity), from an offset origin)
//          depth       how many more bounces may follow (0: none; never below 0)
//          throughput  by how much this ray's colour will be scaled on its way to the eye
//                      (1 for a primary ray): the product of the weights on its path
// Returns
//   * No hit in range: world.background.
//   * A hit h = closest_surface_hit(world, r, range), with n = h.facing_normal():
//       local_light(world, h, r)
//     + when depth > 0, for each secondary ray with weight w (a colour), traced only if
//       throughput * max(w.r, w.g, w.b) >= min_throughput:
//         w * trace(world, s, (0, infinity), depth - 1, throughput * max(w.r, w.g, w.b))
//       where the secondary rays are
//         mirror (any component of h.m.mirror > 0): s = spawn_ray(h.surface, n, reflect(r.direction, n)),
//                                                    w = h.m.mirror
//         glass (h.m.ior > 0):  eta = 1 / ior entering (h.front_face), ior leaving; cos_i = the cosine
//                               between -r.direction and n; F = fresnel_dielectric(cos_i, eta):
//                                 reflected as for a mirror, with w = color(F);
//                                 refracted, s = spawn_ray(h.surface, n, *refract(r.direction, n, eta)),
//                                 with w = color(1 - F), unless refract finds total internal reflection.
//   * depth < 0 is a caller's mistake: throws std::invalid_argument.
//   Never NaN; never negative.
template <class T>
color trace(const scene<T>& world, const ray<T>& r, const interval<T>& range, int depth, float throughput);

}  // namespace rt::ch09
