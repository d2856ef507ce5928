// main.cpp — chapter 06's program: a lit scene with highlights and shadows.
//
// The scene is scenes/ch06-shading.json (or --scene FILE): three spheres and
// an icosahedron (20 triangles) stand on a checkered ground plane, lit by
// two point lights and a little ambient light. Each pixel's ray finds its
// closest hit with chapter 03's loop, which asks chapters 02, 04 and 05
// about spheres, the plane and the triangles; then *your* shade() colours
// the hit, sending one shadow ray per light through the same loop. What to
// look for (README, "the expected picture"): soft falloff across each ball,
// a small bright highlight on the glossy ones, two shadows per object on the
// ground, and no speckles (shadow acne).
#include "04-plane/plane.hpp"
#include "03-scene-loop/scene_loop.hpp"
#include "shading.hpp"
#include "02-sphere/sphere.hpp"
#include "05-triangle/triangle.hpp"

#include "common/object_dispatch.hpp"
#include "common/program.hpp"
#include "common/render.hpp"

#include <atomic>

namespace {

using namespace rt;

template <class T>
image render_scene(const program_options& opt, long& rays) {
    const scene<T> world = convert_scene<T>(opt.scene.world);
    const scene_camera<T> camera(opt.scene.camera, opt.width, opt.height);
    const ch03::object_intersector<T> intersect =
        object_dispatch(world, ch02::intersect_sphere<T>, ch04::intersect_plane<T>, ch05::intersect_triangle<T>).intersector();

    std::atomic<long> shadow_rays{0};
    const ch06::occlusion_test<T> occluded = [&](const ray<T>& r, const interval<T>& range) {
        shadow_rays.fetch_add(1, std::memory_order_relaxed);
        return ch03::closest_hit(world.object_count(), intersect, r, range).has_value();
    };

    image img = render(opt.width, opt.height, [&](int col, int row) {
        const ray<T> r = camera.primary_ray(col, row);
        // t > 1: only what lies beyond the image plane is visible (chapter 01);
        // an orthographic camera from a scene file takes t > 0.
        const auto hit = ch03::closest_hit(world.object_count(), intersect, r, camera.primary_range());
        if (!hit) return world.background;
        const material m = material_at(world, *hit);  // the checker pattern resolved
        // Shade the side the viewer sees: the one face rule (common/hit_record.hpp).
        return ch06::shade(hit->point, hit->facing_normal(r), -r.direction, m, world.lights, world.ambient, occluded);
    });
    rays = long(opt.width) * opt.height + shadow_rays.load();
    return img;
}

}  // namespace

int main(int argc, char** argv) {
    rt::chapter_program program;
    program.id = "ch06";
    program.title = "shading";
    program.draws_scene = true;
    program.render = rt::by_precision(render_scene<float>, render_scene<double>);  // counts its shadow rays
    return rt::run_chapter_program(argc, argv, program);
}
