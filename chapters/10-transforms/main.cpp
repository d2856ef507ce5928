// main.cpp — chapter 10's program: a scene of instances through the
// two-level tree.
//
//   ch10-transforms [--level N] [--copies N] [--scene FILE] [the usual options]
//
// Without --scene: the sphereflake of scenes/ch10-sphereflake.json (its view,
// ground, lights and materials), built as instances of instances
// (sphereflake.hpp) at level 4, or --level N: the flake of level N is ten
// instances, the root sphere and nine copies of the flake of level N - 1, a
// third the size. Level N stores N + 1 models of ten instances, however many
// spheres it shows (1 + 9 + ... + 9^N).
//
// With --scene FILE: the file's spheres and triangles (its meshes, from OBJ
// files too) are one model, in its own chapter 08 tree, placed --copies N
// times (default 1) on a square grid, each copy turned and scaled by a fixed
// pseudo-random rule; its planes stay in the world, outside the tree.
// scenes/instanced-mesh.json with --copies 1000 is the chapter's second
// picture (README.md, "A thousand meshes").
//
// Every ray meets YOUR closest_hit (shadow rays YOUR any_hit) over the top
// level; each instance asks YOUR instance_hit, which takes the ray into the
// model's space with YOUR transform_ray and brings the normal back with YOUR
// transform_normal; the top-level boxes are YOUR instance_box. A model is a
// chapter 08 tree (spheres, triangles) or a scene of instances itself.
//
// The models' spheres are met by YOUR chapter 07 intersect_sphere_robust, not
// chapter 02's formula: a level-4 sphere of the flake is seen from about 440
// radii away, where chapter 02's t is off by hundreds of epsilons; the hit
// point then lies deeper below the surface than chapter 06's shadow offset
// reaches, and its shadow ray finds its own sphere (shadow acne, README, "The
// picture").
#include "instancing.hpp"
#include "sphereflake.hpp"

#include "03-scene-loop/scene_loop.hpp"
#include "08-acceleration/scene_tree.hpp"
#include "02-sphere/sphere.hpp"
#include "04-plane/plane.hpp"
#include "07-precision/robust_sphere.hpp"
#include "05-triangle/triangle.hpp"
#include "06-shading/shading.hpp"

#include "common/object_dispatch.hpp"
#include "common/program.hpp"
#include "common/render.hpp"
#include "common/timing.hpp"

#include <algorithm>
#include <atomic>
#include <climits>
#include <cstdint>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

using namespace rt;

constexpr int default_level = 4;  // the chapter's own picture
constexpr int max_level = 10;     // 3.9 billion spheres: instancing stores 11 models
int level_option = -1;            // --level N (the flake only)
int copies_option = -1;           // --copies N (--scene only)
bool scene_option = false;

// The models a scene of instances is made of, and how to ask each one.
// Model 0 is a shape set in a chapter 08 tree (the flake's root sphere, or a
// --scene file's spheres and triangles); models 1 .. are scenes of instances.
template <class T>
struct instanced_world {
    scene<T> shapes;                              // model 0's objects
    std::unique_ptr<ch08::scene_tree<T>> shape_tree;
    std::vector<ch10::instance_tree<T>> composites;  // composites[k - 1] is model k
    ch10::model_intersector<T> model_hit;
    int top = 0;                                  // the model the world shows
};

template <class T>
void set_up_model_hit(instanced_world<T>& w) {
    // Chapter 07's sphere test: t within a few ULPs however far the sphere (see the top of this file).
    using dispatch_t = decltype(object_dispatch(w.shapes, ch07::intersect_sphere_robust<T>, ch04::intersect_plane<T>,
                                                ch05::intersect_triangle<T>));
    auto dispatch = std::make_shared<dispatch_t>(w.shapes, ch07::intersect_sphere_robust<T>, ch04::intersect_plane<T>,
                                                 ch05::intersect_triangle<T>);
    auto leaf = std::make_shared<ch08::leaf_intersector<T>>(ch08::leaf_test(*w.shape_tree, *dispatch));
    w.model_hit = [&w, dispatch, leaf](int m, const ray<T>& r, const interval<T>& range) -> std::optional<hit_record<T>> {
        if (m == 0) return ch08::scene_closest_hit(*w.shape_tree, *leaf, *dispatch, r, range);
        return ch10::closest_hit(w.composites[size_t(m - 1)], w.model_hit, r, range);
    };
}

// Models 1 .. of the parts given, bottom up; model 0's box is its tree's root.
// A hit's object number is an int: past 2^31 objects (the flake from level
// 10) each instance is numbered by its place in its model instead, which
// keeps the order the tree's tie rule needs (only shading reads the number).
template <class T>
void build_composites(instanced_world<T>& w, const std::vector<ch10::composite_model>& models) {
    const bool numbered = models.back().objects <= std::int64_t(INT32_MAX);
    std::vector<ch08::aabb<T>> boxes{w.shape_tree->tree.nodes.empty() ? ch08::aabb<T>{} : w.shape_tree->tree.nodes[0].box};
    for (size_t k = 1; k < models.size(); ++k) {
        std::vector<ch10::instance<T>> instances;
        for (size_t j = 0; j < models[k].parts.size(); ++j) {
            const ch10::part& p = models[k].parts[j];
            const std::string what = "model " + std::to_string(k) + ", instance " + std::to_string(j);
            instances.push_back({ch10::make_placement<T>(p.to_world, what), p.model, numbered ? int(p.first_object) : int(j)});
        }
        w.composites.push_back(ch10::build_instance_tree(std::move(instances), boxes));
        boxes.push_back(ch10::scene_box(w.composites.back()));
    }
    w.top = int(models.size()) - 1;
}

// --copies N of a model on a square grid in the x-z plane (y up, as the
// course's own scenes), each turned about y and tilted, scaled 0.6 to 1.
std::vector<ch10::composite_model> grid_parts(long copies, const ch08::aabb<double>& box, long model_objects) {
    std::vector<ch10::composite_model> models(2);
    models[0].objects = model_objects;
    const long side = long(std::ceil(std::sqrt(double(copies))));
    const vec3d extent = box.hi - box.lo;
    const double spacing = 1.25 * std::max({extent.x, extent.y, extent.z});
    const vec3d base = (box.lo + box.hi) * 0.5;
    std::uint64_t state = 0x2545F4914F6CDD1Dull;  // a fixed generator: the same picture every run
    auto next = [&state] {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        return double(state >> 11) * 0x1.0p-53;
    };
    for (long k = 0; k < copies; ++k) {
        const double x = (double(k % side) - 0.5 * double(side - 1)) * spacing;
        const double z = -double(k / side) * spacing;
        const double turn = 360 * next(), tilt = 20 * (next() - 0.5), size = 0.6 + 0.4 * next();
        ch10::affine3<double> m = ch10::compose(ch10::rotate({0, 1, 0}, turn),
                                                ch10::compose(ch10::rotate({1, 0, 0}, tilt), ch10::scale(vec3d(size))));
        m = ch10::compose(ch10::translate(vec3d(x, 0, z) + vec3d(0, -box.lo.y * size, 0)),
                          ch10::compose(m, ch10::translate(-vec3d(base.x, 0, base.z))));
        models[1].parts.push_back({m, 0, std::int64_t(k) * model_objects});
    }
    models[1].objects = std::int64_t(copies) * model_objects;
    return models;
}

// The two groups of the world's objects: the planes, outside the tree, and
// the top level's instances.
template <class T>
struct world_groups {
    int plane_count;
    const ch03::object_intersector<T>& plane_hit;
    const ch10::instance_tree<T>& top;
    const ch10::model_intersector<T>& model_hit;

    std::optional<hit_record<T>> hit(int group, const ray<T>& r, const interval<T>& range) const {
        if (group == 0) return ch03::closest_hit(plane_count, plane_hit, r, range);
        return ch10::closest_hit(top, model_hit, r, range);
    }
};

template <class T>
image render_scene(const program_options& opt, long& rays) {
    if (scene_option && level_option >= 0)
        throw std::invalid_argument("--level draws the chapter's sphereflake; with --scene FILE, use --copies N");
    if (!scene_option && copies_option >= 0)
        throw std::invalid_argument("--copies places a --scene FILE's objects N times (the flake has --level)");
    const scene<double>& file = opt.scene.world;
    const scene_camera<T> camera(opt.scene.camera, opt.width, opt.height);
    scene<T> world = convert_scene<T>(file);  // lights, materials, planes; the shapes go into the model
    instanced_world<T> w;
    w.shapes.materials = world.materials;
    stopwatch build_time;
    std::vector<ch10::composite_model> models;
    if (scene_option) {
        w.shapes.spheres = world.spheres;
        w.shapes.triangles = world.triangles;
        w.shape_tree = std::make_unique<ch08::scene_tree<T>>(ch08::build_scene_tree(w.shapes));
        ch08::aabb<double> box;
        if (!w.shape_tree->tree.nodes.empty()) {
            box.lo = vec3d(w.shape_tree->tree.nodes[0].box.lo);
            box.hi = vec3d(w.shape_tree->tree.nodes[0].box.hi);
        }
        models = grid_parts(copies_option > 0 ? copies_option : 1, box, w.shapes.object_count());
    } else {
        const int level = level_option >= 0 ? level_option : default_level;
        w.shapes.spheres.push_back(ch10::flake_root_sphere<T>(1));
        w.shape_tree = std::make_unique<ch08::scene_tree<T>>(ch08::build_scene_tree(w.shapes));
        models = ch10::flake_models(level);
    }
    world.spheres.clear();
    world.triangles.clear();
    build_composites(w, models);
    set_up_model_hit(w);
    std::printf("ch10: %lld objects shown, %zu models stored (%zu instances in all), %.1f ms to build\n",
                (long long)models.back().objects, models.size(),
                [&] { size_t n = 0; for (const auto& m : models) n += m.parts.size(); return n; }(),
                build_time.seconds() * 1e3);

    const ch10::instance_tree<T>& top = w.composites[size_t(w.top - 1)];
    const auto planes = object_dispatch(world, ch02::intersect_sphere<T>, ch04::intersect_plane<T>);
    const ch03::object_intersector<T> plane_hit = planes.intersector();
    // The world is two groups, and chapter 03's loop (YOUR closest_hit) picks
    // the nearer: group 0 the planes (scene objects 0 .., that same loop over
    // them), group 1 the instances (YOUR chapter 10 closest_hit). The loop
    // numbers its hit by group, so each group's own object number (a plane's
    // scene number, an instance's object in its model) is kept on the side.
    const world_groups<T> groups{planes.count(), plane_hit, top, w.model_hit};
    auto closest = [&groups](const ray<T>& r, const interval<T>& range, bool& on_plane) {
        int inner[2] = {-1, -1};
        const ch03::object_intersector<T> group = [&groups, &inner](int g, const ray<T>& ray_in, const interval<T>& within) {
            auto h = groups.hit(g, ray_in, within);
            if (h) inner[g] = h->object;
            return h;
        };
        std::optional<hit_record<T>> best = ch03::closest_hit(2, group, r, range);
        if (best) on_plane = best->object == 0, best->object = inner[best->object];
        return best;
    };
    std::atomic<long> shadow_rays{0};
    const ch06::occlusion_test<T> occluded = [&](const ray<T>& r, const interval<T>& range) {
        shadow_rays.fetch_add(1, std::memory_order_relaxed);
        if (groups.hit(0, r, range)) return true;
        return ch10::any_hit(top, w.model_hit, r, range);
    };
    const long model_objects = w.shapes.object_count();
    image img = render(opt.width, opt.height, [&](int col, int row) {
        const ray<T> r = camera.primary_ray(col, row);
        bool on_plane = false;
        const auto hit = closest(r, camera.primary_range(), on_plane);
        if (!hit) return world.background;
        material m;
        if (on_plane) {
            m = material_at(world, *hit);
        } else {
            // A copy's object j of the model is scene object first + j; its material is the model's.
            hit_record<T> in_model = *hit;
            in_model.object = int(std::llabs((long long)hit->object) % model_objects);
            m = material_at(w.shapes, in_model);
        }
        // Shade the side the viewer sees: the one face rule (common/hit_record.hpp).
        return ch06::shade(hit->point, hit->facing_normal(r), -r.direction, m, world.lights, world.ambient, occluded);
    });
    rays = long(opt.width) * opt.height + shadow_rays.load();
    return img;
}

}  // namespace

int main(int argc, char** argv) {
    for (int i = 1; i < argc; ++i) scene_option = scene_option || std::strcmp(argv[i], "--scene") == 0;
    rt::chapter_program program;
    program.id = "ch10";
    program.title = "transforms";
    program.draws_scene = true;
    program.render = rt::by_precision(render_scene<float>, render_scene<double>);
    program.add_options = [](CLI::App& app) {
        rt::add_whole_number_option(app, "--level", level_option, 1, max_level,
                                    "the sphereflake at level N, as instances of instances (default " +
                                        std::to_string(default_level) + "; not with --scene)");
        rt::add_whole_number_option(app, "--copies", copies_option, 1, 1'000'000,
                                    "with --scene FILE: place the file's objects N times");
    };
    return rt::run_chapter_program(argc, argv, program);
}
