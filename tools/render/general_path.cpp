#include "general_path.hpp"

#include "chapters_setup.hpp"
#include "look.hpp"

#include "04-plane/plane.hpp"
#include "03-scene-loop/scene_loop.hpp"
#include "06-shading/shading.hpp"
#include "08-acceleration/scene_tree.hpp"
#include "08-acceleration/tree_heatmap.hpp"
#include "09-reflection/whitted.hpp"  // surface_point_of: a hit point put back on its surface
#include "02-sphere/sphere.hpp"
#include "05-triangle/triangle.hpp"

#include "common/object_dispatch.hpp"
#include "common/render.hpp"

#include <atomic>

namespace rt::render_tool {

namespace {

// Chapter 02's, 04's and 05's shape tests, picked by the object's kind.
template <class T>
auto chapters_dispatch(const scene<T>& world) {
    return object_dispatch(world, ch02::intersect_sphere<T>, ch04::intersect_plane<T>, ch05::intersect_triangle<T>);
}

template <class T>
image render_typed(const scene_description& d, bool use_tree, int width, int height, render_stats& stats) {
    const setup_timer setup;
    const chapters_scene<T> s(d, width, height);
    const scene<T>& world = s.world;
    const auto dispatch = chapters_dispatch(world);
    const ch03::object_intersector<T> intersect = dispatch.intersector();
    // Chapter 08's tree, when the plan says it pays (the same rule as the
    // specialised path's); an empty tree otherwise, never asked.
    const ch08::scene_tree<T> tree = use_tree ? ch08::build_scene_tree(world) : ch08::scene_tree<T>{};
    const ch08::leaf_intersector<T> leaf = ch08::leaf_test(tree, dispatch);
    setup.done(stats);
    auto closest = [&](const ray<T>& r, const interval<T>& range) {
        return use_tree ? ch08::scene_closest_hit(tree, leaf, dispatch, r, range)
                        : ch03::closest_hit(world.object_count(), intersect, r, range);
    };
    std::atomic<long> shadow_rays{0};
    const ch06::occlusion_test<T> occluded = [&](const ray<T>& r, const interval<T>& range) {
        shadow_rays.fetch_add(1, std::memory_order_relaxed);
        return use_tree ? ch08::scene_any_hit(tree, leaf, dispatch, r, range) : closest(r, range).has_value();
    };

    image img = render(width, height, [&](int col, int row) {
        const ray<T> r = s.camera.primary_ray(col, row);
        const auto hit = closest(r, s.camera.primary_range());
        if (!hit) return world.background;
        const material m = material_at(world, *hit);
        const vec3<T> n = hit->facing_normal(r);  // the side the viewer sees, as the chapters shade it
        if (world.lights.empty()) return unlit_colour(m, n, r.direction);
        // Shaded from the point put back on its surface, as the specialised
        // path does (fast_path.cpp, surface_point: why a far eye needs it).
        return ch06::shade(ch09::surface_point_of(world, *hit).point, n, -r.direction, m, world.lights, world.ambient,
                           occluded);
    });
    stats.rays = long(width) * long(height) + shadow_rays.load();
    return img;
}

template <class T>
std::vector<count_map> heatmap_typed(const scene_description& d, int width, int height) {
    const chapters_scene<T> s(d, width, height);
    return ch08::tree_heatmap(s.world, ch08::build_scene_tree(s.world), chapters_dispatch(s.world), s.camera, width,
                              height);
}

}  // namespace

std::vector<count_map> heatmap_general(const scene_description& scene, const scene_plan& plan, int width, int height) {
    return plan.prec == precision::single ? heatmap_typed<float>(scene, width, height)
                                          : heatmap_typed<double>(scene, width, height);
}

image render_general(const scene_description& scene, const scene_plan& plan, int width, int height, render_stats& stats) {
    return plan.prec == precision::single ? render_typed<float>(scene, plan.tree, width, height, stats)
                                          : render_typed<double>(scene, plan.tree, width, height, stats);
}

}  // namespace rt::render_tool
