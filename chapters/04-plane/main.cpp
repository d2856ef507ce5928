// main.cpp — chapter 04's program: spheres standing on a checkered ground.
//
// The scene is scenes/ch04-plane.json (or --scene FILE). The ground is an
// infinite plane tested with *your* intersect_plane; the spheres use
// chapter 02's intersect_sphere and chapter 03's closest_hit picks what each
// pixel sees. The checkerboard is there so that depth reads: its squares
// shrink towards the horizon, and a plane that is hit at the wrong t shows
// it as squares that are stretched, swimming or missing.
//
// Shading is a single fixed light direction (Lambert's cosine, plus a
// little ambient light) so the shapes look solid; real lights and shadows
// are chapter 06's subject.
#include "plane.hpp"
#include "03-scene-loop/scene_loop.hpp"
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
    const ch03::object_intersector<T> intersect =
        object_dispatch(world, ch02::intersect_sphere<T>, ch04::intersect_plane<T>).intersector();
    const vec3<T> to_light = normalize(vec3<T>(T(-0.5), T(1.0), T(0.6)));

    return render(opt.width, opt.height, [&](int col, int row) {
        ray<T> r = camera.primary_ray(col, row);
        // t > 1: only what lies beyond the image plane is visible (chapter 01);
        // an orthographic camera from a scene file takes t > 0.
        auto hit = ch03::closest_hit(world.object_count(), intersect, r, camera.primary_range());
        if (!hit) return world.background;
        // The normal on the viewer's side: the ground seen from below is lit like from above.
        const float lambert = float(std::max(T(0), dot(hit->facing_normal(r), to_light)));
        return material_at(world, *hit).diffuse * (0.2f + 0.8f * lambert);
    });
}

}  // namespace

int main(int argc, char** argv) {
    rt::chapter_program program;
    program.id = "ch04";
    program.title = "plane";
    program.draws_scene = true;
    program.draws_triangles = false;  // chapter 05
    program.render = rt::by_precision(render_scene<float>, render_scene<double>);
    return rt::run_chapter_program(argc, argv, program);
}
