// main.cpp — chapter 04's program: spheres standing on a checkered ground.
//
// The ground is an infinite plane tested with *your* intersect_plane; the
// spheres use chapter 02's intersect_sphere and chapter 03's closest_hit
// picks what each pixel sees. The checkerboard is there so that depth reads:
// its squares shrink towards the horizon, and a plane that is hit at the
// wrong t shows it as squares that are stretched, swimming or missing.
//
// Shading is a single fixed light direction (Lambert's cosine, plus a
// little ambient light) so the shapes look solid; real lights and shadows
// are chapter 06's subject.
#include "plane.hpp"
#include "scene_loop.hpp"
#include "sphere.hpp"

#include "common/camera.hpp"
#include "common/program.hpp"
#include "common/render.hpp"
#include "common/scene.hpp"
#include "common/scene_file.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace {

using namespace rt;

template <class T>
scene<T> spheres_on_the_ground() {
    scene<T> s;
    material ground;
    ground.diffuse = color(0.85f, 0.85f, 0.8f);
    ground.checker = true;
    ground.checker_color = color(0.15f, 0.2f, 0.3f);
    s.materials = {
        ground,
        {color(0.9f, 0.2f, 0.15f)},  // red
        {color(0.2f, 0.7f, 0.3f)},   // green
        {color(0.2f, 0.35f, 0.9f)},  // blue
    };
    // Each sphere rests on the ground: its centre is one radius above y = 0.
    s.spheres = {
        {{T(-1.6), T(0.7), T(-1.0)}, T(0.7), 1},
        {{T(0.2), T(1.0), T(-2.6)}, T(1.0), 2},
        {{T(1.5), T(0.5), T(0.2)}, T(0.5), 3},
    };
    s.planes = {{{0, 0, 0}, {0, 1, 0}, 0}};
    return s;
}

// The checkerboard: unit squares on the plane, alternating colours. The two
// coordinates used are the ones across the plane (for the ground, x and z):
// the coordinate along the normal is ~0 on the plane and, with rounding, a
// hair above or below it, which would make the pattern flicker.
template <class T>
color checker(const material& m, const vec3<T>& point, const vec3<T>& normal) {
    const vec3<T> n(std::fabs(normal.x), std::fabs(normal.y), std::fabs(normal.z));
    T u = point.x, v = point.z;                  // ground-like plane: normal mostly along y
    if (n.x >= n.y && n.x >= n.z) u = point.z, v = point.y;
    else if (n.z >= n.x && n.z >= n.y) u = point.x, v = point.y;
    // fmod, not a cast to an integer: far out near the horizon the coordinates
    // can exceed any integer type, and an out-of-range cast is undefined.
    const T squares = std::fmod(std::floor(u) + std::floor(v), T(2));  // 0 or +-1
    return squares == T(0) ? m.diffuse : m.checker_color;
}

template <class T>
image render_scene(const program_options& opt) {
    scene<T> world = spheres_on_the_ground<T>();
    camera_description view;
    view.eye = {0, 1.6, 5};
    view.look_at = {0, 0.6, -1};
    view.fov_degrees = 50;
    if (opt.scene_file) {  // --scene FILE: your own scene; this chapter draws its spheres and planes
        world = convert_scene<T>(opt.scene_file->world);
        view = opt.scene_file->camera;
        if (!world.triangles.empty())
            std::fprintf(stderr, "ch04: the scene's %zu triangles are left out (chapter 05)\n", world.triangles.size());
        world.triangles.clear();
    }
    const int sphere_count = int(world.spheres.size());
    const scene_camera<T> camera(view, opt.width, opt.height);

    // Objects are numbered spheres first, then planes (common/scene.hpp).
    const ch03::object_intersector<T> intersect = [&](int i, const ray<T>& r, const interval<T>& range) {
        if (i < sphere_count) return ch02::intersect_sphere(world.spheres[size_t(i)], r, range);
        return ch04::intersect_plane(world.planes[size_t(i - sphere_count)], r, range);
    };
    const vec3<T> to_light = normalize(vec3<T>(T(-0.5), T(1.0), T(0.6)));

    return render(opt.width, opt.height, [&](int col, int row) {
        ray<T> r = camera.primary_ray(col, row);
        // t > 1: only what lies beyond the image plane is visible (chapter 01);
        // an orthographic camera from a scene file takes t > 0.
        auto hit = ch03::closest_hit(world.object_count(), intersect, r, camera.primary_range());
        if (!hit) return world.background;

        color albedo;
        if (hit->object < sphere_count) {
            albedo = world.materials[size_t(world.spheres[size_t(hit->object)].material)].diffuse;
        } else {
            const plane<T>& p = world.planes[size_t(hit->object - sphere_count)];
            albedo = checker(world.materials[size_t(p.material)], hit->point, hit->normal);
        }
        const float lambert = float(std::max(T(0), dot(hit->normal, to_light)));
        return albedo * (0.2f + 0.8f * lambert);
    });
}

}  // namespace

int main(int argc, char** argv) {
    rt::chapter_program program;
    program.id = "ch04";
    program.title = "plane";
    program.accepts_scene_file = true;  // --scene FILE renders your own scene with your code
    program.render = [](const rt::program_options& opt, long& rays) {
        rays = long(opt.width) * opt.height;
        return opt.prec == rt::precision::single ? render_scene<float>(opt) : render_scene<double>(opt);
    };
    return rt::run_chapter_program(argc, argv, program);
}
