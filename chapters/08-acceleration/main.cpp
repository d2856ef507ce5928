// main.cpp — chapter 08's program: Eric Haines' sphereflake through a BVH.
//
// The scene is scenes/ch08-sphereflake.json (or --scene FILE): the SPD's
// "balls" database (common/spd.hpp) on a ground plane, lit by chapter 06's
// shading with shadows. Every sphere and triangle goes into one tree, built
// by YOUR build_sah over the boxes of aabb.hpp; each pixel's ray asks YOUR
// closest_hit, each shadow ray YOUR any_hit, and the leaves call the scene's
// one dispatch (common/object_dispatch.hpp). Planes have no finite box, so
// they stay outside the tree and are asked one by one, as in chapter 03
// (scene_tree.hpp does this split; rt-render's --general uses it too).
//
//   ch08-acceleration [--level N] [--scene FILE] [--heatmap] [the usual options]
//
// The chapter's own scene is drawn at level 4 (7,381 spheres), or at
// --level N (1 + 9 + ... + 9^N spheres; level 6 is 597,871): the scene file
// gives the view, the lights and the materials, and level 2 for the tools
// that draw it as written (rt-render's tests compare its float and double
// paths at 96x64 pixels, where smaller spheres are sub-pixel). With --scene
// FILE, the file is drawn as written. The program prints the size of the
// scene and the tree and how long the build took, then the usual report line.
//
// --heatmap also writes OUT-heatmap.png beside the picture (OUT.png): for
// each pixel's primary ray, the boxes your tree opened, the objects your
// traversal asked, and the objects brute force (chapter 03's loop) asked,
// side by side on one logarithmic colour scale, with a line per map on
// stdout (tree_heatmap.hpp says exactly what is counted). The heatmap's
// passes run after the picture and are included in its reported time.
#include "scene_tree.hpp"
#include "tree_heatmap.hpp"
#include "04-plane/plane.hpp"
#include "06-shading/shading.hpp"
#include "02-sphere/sphere.hpp"
#include "05-triangle/triangle.hpp"

#include "common/object_dispatch.hpp"
#include "common/program.hpp"
#include "common/render.hpp"
#include "common/spd.hpp"
#include "common/timing.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

using namespace rt;

constexpr int default_level = 4;  // the chapter's own picture
int level_option = -1;            // --level N; -1: default_level, or the --scene file as written
bool scene_option = false;        // --scene FILE given
bool heatmap_option = false;      // --heatmap

// OUT.png -> OUT-heatmap.png (a name without .png gets -heatmap.png appended).
std::string heatmap_path(const std::string& out) {
    const std::string stem = out.size() > 4 && out.compare(out.size() - 4, 4, ".png") == 0 ? out.substr(0, out.size() - 4) : out;
    return stem + "-heatmap.png";
}

// The sphereflake at --level N in place of the scene's shapes (its first two
// materials are the ground and the flake, as in scenes/ch08-sphereflake.json).
scene<double> with_level(scene<double> world, int level) {
    world.spheres.clear();
    world.planes.clear();
    world.triangles.clear();
    spd_generate(spd_database::balls, level, world, {0, 1});
    return world;
}

template <class T>
image render_scene(const program_options& opt, long& rays) {
    if (level_option >= 0 && scene_option)
        throw std::invalid_argument("--level draws the chapter's sphereflake; with --scene FILE, give the size in "
                                    "the file's \"generate\" instead");
    const int level = level_option >= 0 ? level_option : (scene_option ? -1 : default_level);
    const scene<T> world = convert_scene<T>(level >= 0 ? with_level(opt.scene.world, level) : opt.scene.world);
    const scene_camera<T> camera(opt.scene.camera, opt.width, opt.height);
    const auto dispatch =
        object_dispatch(world, ch02::intersect_sphere<T>, ch04::intersect_plane<T>, ch05::intersect_triangle<T>);

    stopwatch build_time;
    const ch08::scene_tree<T> a = ch08::build_scene_tree(world);
    std::printf("ch08: %zu objects in the tree (%zu nodes, %.1f ms to build), %zu planes outside it\n",
                a.bounded.size(), a.tree.nodes.size(), build_time.seconds() * 1e3, a.planes.size());

    const ch08::leaf_intersector<T> leaf = ch08::leaf_test(a, dispatch);
    auto closest = [&](const ray<T>& r, const interval<T>& range) {
        return ch08::scene_closest_hit(a, leaf, dispatch, r, range);
    };
    std::atomic<long> shadow_rays{0};
    const ch06::occlusion_test<T> occluded = [&](const ray<T>& r, const interval<T>& range) {
        shadow_rays.fetch_add(1, std::memory_order_relaxed);
        return ch08::scene_any_hit(a, leaf, dispatch, r, range);
    };

    image img = render(opt.width, opt.height, [&](int col, int row) {
        const ray<T> r = camera.primary_ray(col, row);
        const auto hit = closest(r, camera.primary_range());
        if (!hit) return world.background;
        const material m = material_at(world, *hit);
        // Shade the side the viewer sees: the one face rule (common/hit_record.hpp).
        return ch06::shade(hit->point, hit->facing_normal(r), -r.direction, m, world.lights, world.ambient, occluded);
    });
    rays = long(opt.width) * opt.height + shadow_rays.load();
    if (heatmap_option) {
        const std::vector<count_map> maps = ch08::tree_heatmap(world, a, dispatch, camera, opt.width, opt.height);
        const std::string path = heatmap_path(opt.out);
        write_png(draw_heatmap(maps), path);
        std::printf("ch08: heatmap %s (left to right; one colour scale, 0 to %ld, logarithmic):\n%s", path.c_str(),
                    std::max({maps[0].max(), maps[1].max(), maps[2].max()}), heatmap_legend(maps).c_str());
    }
    return img;
}

}  // namespace

int main(int argc, char** argv) {
    for (int i = 1; i < argc; ++i) scene_option = scene_option || std::strcmp(argv[i], "--scene") == 0;
    rt::chapter_program program;
    program.id = "ch08";
    program.title = "acceleration";
    program.draws_scene = true;
    program.render = rt::by_precision(render_scene<float>, render_scene<double>);
    program.add_options = [](CLI::App& app) {
        rt::add_whole_number_option(app, "--level", level_option, 1, spd_max_size(spd_database::balls),
                                    "draw the chapter's sphereflake at level N (1 + 9 + ... + 9^N spheres; default " +
                                        std::to_string(default_level) + "; not with --scene)");
        rt::add_flag_option(app, "--heatmap", heatmap_option,
                            "also write OUT-heatmap.png: boxes opened and objects asked per pixel, by your tree and "
                            "by brute force, on one colour scale");
    };
    return rt::run_chapter_program(argc, argv, program);
}
