// main.cpp — chapter 05's program: a closed triangle mesh among spheres.
//
// The scene is scenes/ch05-triangle-mesh.json (or --scene FILE). The
// icosahedron in the middle is twenty triangles, each tested with *your*
// intersect_triangle; the spheres and the checkered ground come from
// chapters 02 and 04, and chapter 03's closest_hit picks what each pixel
// sees. The mesh is closed: neighbouring faces share their edges exactly,
// so a crack (a pixel where the background or the ground shows through an
// edge) means an edge test that rejects points lying on the edge itself.
//
// Each face is drawn with a thin dark outline where one of your barycentric
// coordinates is close to 0, i.e. near an edge: if the outlines run along
// the wrong edges or cover whole faces, the coordinates are in the wrong
// order or unnormalised.
//
// Shading is one fixed light direction (Lambert's cosine plus a little
// ambient light); real lights and shadows are chapter 06's subject.
#include "04-plane/plane.hpp"
#include "03-scene-loop/scene_loop.hpp"
#include "02-sphere/sphere.hpp"
#include "triangle.hpp"

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
        object_dispatch(world, ch02::intersect_sphere<T>, ch04::intersect_plane<T>, ch05::intersect_triangle<T>).intersector();
    const vec3<T> to_light = normalize(vec3<T>(T(-0.5), T(1.0), T(0.7)));

    return render(opt.width, opt.height, [&](int col, int row) {
        ray<T> r = camera.primary_ray(col, row);
        // t > 1: only what lies beyond the image plane is visible (chapter 01);
        // an orthographic camera from a scene file takes t > 0.
        auto hit = ch03::closest_hit(world.object_count(), intersect, r, camera.primary_range());
        if (!hit) return world.background;

        color albedo = material_at(world, *hit).diffuse;
        const object_ref o = locate(world, hit->object);
        if (o.kind == shape_kind::triangle) {
            // Near an edge one barycentric coordinate is close to 0: draw an outline there.
            const vec3<T> w = ch05::barycentric(world.triangles[o.index], hit->point);
            if (std::min({w.x, w.y, w.z}) < T(0.025)) albedo *= 0.35f;
        }
        // The normal on the viewer's side: a face seen from behind is lit like from the front.
        const float lambert = float(std::max(T(0), dot(hit->facing_normal(r), to_light)));
        return albedo * (0.2f + 0.8f * lambert);
    });
}

}  // namespace

int main(int argc, char** argv) {
    rt::chapter_program program;
    program.id = "ch05";
    program.title = "triangle";
    program.draws_scene = true;
    program.render = rt::by_precision(render_scene<float>, render_scene<double>);
    return rt::run_chapter_program(argc, argv, program);
}
