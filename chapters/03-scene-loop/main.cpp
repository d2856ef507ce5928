// main.cpp — chapter 03's program: several overlapping spheres.
//
// The scene is scenes/ch03-overlapping-spheres.json (or --scene FILE). Every
// pixel's ray goes through *your* closest_hit, which asks chapter 02's
// intersect_sphere about each sphere in turn. Each sphere has its own
// colour, so where the loop picks the wrong sphere the picture shows it: a
// far sphere painted over a near one means the closest hit was not kept.
// The shade is the sphere's colour, darker where the surface turns away
// from the viewer, so the spheres read as round and their overlaps as depth.
#include "scene_loop.hpp"
#include "02-sphere/sphere.hpp"

#include "common/object_dispatch.hpp"
#include "common/program.hpp"
#include "common/render.hpp"

#include <algorithm>

namespace {

using namespace rt;

template <class T>
image render_scene(const program_options& opt) {
    const scene<T> world = convert_scene<T>(opt.scene.world);
    const scene_camera<T> camera(opt.scene.camera, opt.width, opt.height);
    const ch03::object_intersector<T> intersect = object_dispatch(world, ch02::intersect_sphere<T>).intersector();
    return render(opt.width, opt.height, [&](int col, int row) {
        ray<T> r = camera.primary_ray(col, row);
        // t > 1: only what lies beyond the image plane is visible (chapter 01);
        // an orthographic camera from a scene file takes t > 0.
        auto hit = ch03::closest_hit(world.object_count(), intersect, r, camera.primary_range());
        if (!hit) return world.background;
        // How squarely the surface faces the viewer: 1 head-on, 0 at the silhouette
        // (the normal on the viewer's side, so the inside of a sphere reads too).
        const float facing = float(std::max(T(0), -dot(hit->facing_normal(r), normalize(r.direction))));
        return material_at(world, *hit).diffuse * (0.3f + 0.7f * facing);
    });
}

}  // namespace

int main(int argc, char** argv) {
    rt::chapter_program program;
    program.id = "ch03";
    program.title = "scene loop";
    program.draws_scene = true;
    program.draws_planes = program.draws_triangles = false;  // chapters 04 and 05
    program.render = rt::by_precision(render_scene<float>, render_scene<double>);
    return rt::run_chapter_program(argc, argv, program);
}
