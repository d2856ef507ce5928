// main.cpp — chapter 03's program: several overlapping spheres.
//
// Every pixel's ray goes through *your* closest_hit, which asks chapter 02's
// intersect_sphere about each sphere in turn. Each sphere has its own
// colour, so where the loop picks the wrong sphere the picture shows it: a
// far sphere painted over a near one means the closest hit was not kept.
// The shade is the sphere's colour, darker where the surface turns away
// from the viewer, so the spheres read as round and their overlaps as depth.
#include "scene_loop.hpp"
#include "sphere.hpp"

#include "common/camera.hpp"
#include "common/program.hpp"
#include "common/render.hpp"
#include "common/scene.hpp"
#include "common/scene_file.hpp"

#include <algorithm>
#include <cstdio>
#include <stdexcept>
#include <string>

namespace {

using namespace rt;

template <class T>
scene<T> overlapping_spheres() {
    scene<T> s;
    s.materials = {
        {color(0.9f, 0.15f, 0.1f)},   // red
        {color(0.1f, 0.7f, 0.2f)},    // green
        {color(0.15f, 0.3f, 0.9f)},   // blue
        {color(0.95f, 0.8f, 0.1f)},   // yellow
        {color(0.6f, 0.2f, 0.8f)},    // purple
    };
    // Listed neither near to far nor far to near, on purpose: a loop that
    // keeps the first hit, or the last one, paints a far sphere over a near one.
    s.spheres = {
        {{T(1.2), T(-0.2), T(-5.5)}, T(1.1), 1},   // green, middle distance
        {{T(0.3), T(0.5), T(-3.6)}, T(0.55), 3},   // yellow, nearest
        {{T(-0.6), T(0.3), T(-7)}, T(1.6), 2},     // blue, farthest
        {{T(-1.0), T(-0.6), T(-4.2)}, T(0.8), 0},  // red, near
        {{T(1.6), T(1.1), T(-4.5)}, T(0.5), 4},    // purple, small, off to the side
    };
    return s;
}

template <class T>
image render_scene(const program_options& opt) {
    scene<T> world = overlapping_spheres<T>();
    camera_description view;  // from the origin down -z, 60 degrees
    view.eye = {0, 0, 0};
    view.look_at = {0, 0, -1};
    view.fov_degrees = 60;
    if (opt.scene_file) {  // --scene FILE: your own scene; this chapter draws its spheres
        world = convert_scene<T>(opt.scene_file->world);
        view = opt.scene_file->camera;
        if (!world.planes.empty() || !world.triangles.empty())
            std::fprintf(stderr, "ch03: the scene's %zu planes and %zu triangles are left out (chapters 04 and 05)\n",
                         world.planes.size(), world.triangles.size());
        world.planes.clear();
        world.triangles.clear();
    }
    const scene_camera<T> camera(view, opt.width, opt.height);
    const ch03::object_intersector<T> intersect = [&](int i, const ray<T>& r, const interval<T>& range) {
        return ch02::intersect_sphere(world.spheres[size_t(i)], r, range);
    };
    return render(opt.width, opt.height, [&](int col, int row) {
        ray<T> r = camera.primary_ray(col, row);
        // t > 1: only what lies beyond the image plane is visible (chapter 01);
        // an orthographic camera from a scene file takes t > 0.
        auto hit = ch03::closest_hit(world.object_count(), intersect, r, camera.primary_range());
        if (!hit) return world.background;
        // A wrong index would read past the list of spheres: say so instead of crashing.
        if (!(hit->object >= 0 && hit->object < world.object_count()))
            throw std::runtime_error("closest_hit returned a hit with object index " + std::to_string(hit->object) +
                                     ": it must set hit.object to the index of the object hit (0 to " +
                                     std::to_string(world.object_count() - 1) + ")");
        const material& m = world.materials[size_t(world.spheres[size_t(hit->object)].material)];
        // How squarely the surface faces the viewer: 1 head-on, 0 at the silhouette.
        const float facing = float(std::max(T(0), -dot(hit->normal, normalize(r.direction))));
        return m.diffuse * (0.3f + 0.7f * facing);
    });
}

}  // namespace

int main(int argc, char** argv) {
    rt::chapter_program program;
    program.id = "ch03";
    program.title = "scene loop";
    program.accepts_scene_file = true;  // --scene FILE renders your own scene with your code
    program.render = [](const rt::program_options& opt, long& rays) {
        rays = long(opt.width) * opt.height;
        return opt.prec == rt::precision::single ? render_scene<float>(opt) : render_scene<double>(opt);
    };
    return rt::run_chapter_program(argc, argv, program);
}
