#include "general_path.hpp"

#include "look.hpp"

#include "checker.hpp"
#include "plane.hpp"
#include "scene_loop.hpp"
#include "shading.hpp"
#include "sphere.hpp"
#include "triangle.hpp"

#include "common/render.hpp"

#include <atomic>

namespace rt::render_tool {

namespace {

template <class T>
int material_of(const scene<T>& s, int object) {
    size_t i = size_t(object);
    if (i < s.spheres.size()) return s.spheres[i].material;
    i -= s.spheres.size();
    if (i < s.planes.size()) return s.planes[i].material;
    return s.triangles[i - s.planes.size()].material;
}

template <class T>
image render_typed(const scene_description& d, int width, int height, long& rays) {
    const scene<T> world = convert_scene<T>(d.world);
    const scene_camera<T> camera(d.camera, width, height);

    // Objects are numbered spheres, then planes, then triangles (scene.hpp).
    const ch03::object_intersector<T> intersect = [&](int i, const ray<T>& r, const interval<T>& range) {
        size_t k = size_t(i);
        if (k < world.spheres.size()) return ch02::intersect_sphere(world.spheres[k], r, range);
        k -= world.spheres.size();
        if (k < world.planes.size()) return ch04::intersect_plane(world.planes[k], r, range);
        return ch05::intersect_triangle(world.triangles[k - world.planes.size()], r, range);
    };
    std::atomic<long> shadow_rays{0};
    const ch06::occlusion_test<T> occluded = [&](const ray<T>& r, const interval<T>& range) {
        shadow_rays.fetch_add(1, std::memory_order_relaxed);
        return ch03::closest_hit(world.object_count(), intersect, r, range).has_value();
    };

    image img = render(width, height, [&](int col, int row) {
        const ray<T> r = camera.primary_ray(col, row);
        const auto hit = ch03::closest_hit(world.object_count(), intersect, r, camera.primary_range());
        if (!hit) return world.background;
        const material m = ch06::material_at(world.materials[size_t(material_of(world, hit->object))], hit->point);
        if (world.lights.empty()) return unlit_colour(m, hit->normal, r.direction);
        return ch06::shade(hit->point, hit->normal, -r.direction, m, world.lights, world.ambient, occluded);
    });
    rays = long(width) * long(height) + shadow_rays.load();
    return img;
}

}  // namespace

image render_general(const scene_description& scene, precision prec, int width, int height, long& rays) {
    return prec == precision::single ? render_typed<float>(scene, width, height, rays)
                                     : render_typed<double>(scene, width, height, rays);
}

}  // namespace rt::render_tool
