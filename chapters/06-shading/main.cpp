// main.cpp — chapter 06's program: a lit scene with highlights and shadows.
//
// Three spheres and an icosahedron (20 triangles) stand on a checkered
// ground plane, lit by two point lights and a little ambient light. Each
// pixel's ray finds its closest hit with chapter 03's loop, which asks
// chapters 02, 04 and 05 about spheres, the plane and the triangles; then
// *your* shade() colours the hit, sending one shadow ray per light through
// the same loop. What to look for (README, "the expected picture"): soft
// falloff across each ball, a small bright highlight on the glossy ones,
// two shadows per object on the ground, and no speckles (shadow acne).
#include "checker.hpp"
#include "plane.hpp"
#include "scene_loop.hpp"
#include "shading.hpp"
#include "sphere.hpp"
#include "triangle.hpp"

#include "common/camera.hpp"
#include "common/program.hpp"
#include "common/render.hpp"
#include "common/scene.hpp"
#include "common/scene_file.hpp"

#include <atomic>
#include <cmath>

namespace {

using namespace rt;

// The 20 faces of a regular icosahedron with the given centre and
// circumradius, each wound counter-clockwise seen from outside (so the
// triangle normal points outwards). The 12 corners are the cyclic
// permutations of (0, +-1, +-phi); a face is any three corners that are
// pairwise one edge (length 2) apart.
template <class T>
void add_icosahedron(scene<T>& s, vec3<T> center, T radius, int material_index) {
    const T phi = (T(1) + std::sqrt(T(5))) / T(2);
    std::vector<vec3<T>> corners;
    for (T a : {T(-1), T(1)})
        for (T b : {-phi, phi}) {
            corners.push_back({T(0), a, b});
            corners.push_back({a, b, T(0)});
            corners.push_back({b, T(0), a});
        }
    auto one_edge_apart = [](const vec3<T>& p, const vec3<T>& q) { return std::fabs(length(p - q) - T(2)) < T(1e-3); };
    const T scale = radius / std::sqrt(T(1) + phi * phi);
    const size_t n = corners.size();
    for (size_t i = 0; i < n; ++i)
        for (size_t j = i + 1; j < n; ++j)
            for (size_t k = j + 1; k < n; ++k) {
                const vec3<T>&a = corners[i], &b = corners[j], &c = corners[k];
                if (!one_edge_apart(a, b) || !one_edge_apart(b, c) || !one_edge_apart(a, c)) continue;
                const bool outward = dot(cross(b - a, c - a), a + b + c) > T(0);
                triangle<T> tri{center + scale * a, center + scale * (outward ? b : c),
                                center + scale * (outward ? c : b), material_index};
                s.triangles.push_back(tri);
            }
}

template <class T>
scene<T> lit_scene() {
    scene<T> s;
    material ground;
    ground.diffuse = color(0.85f, 0.85f, 0.8f);
    ground.checker = true;
    ground.checker_color = color(0.25f, 0.25f, 0.28f);
    material red{color(0.8f, 0.15f, 0.1f), color(0.6f, 0.6f, 0.6f), 64.0f};
    material blue{color(0.15f, 0.3f, 0.85f), color(0.3f, 0.3f, 0.3f), 16.0f};
    material matte_yellow{color(0.9f, 0.75f, 0.15f)};
    material green_gem{color(0.15f, 0.65f, 0.3f), color(0.5f, 0.5f, 0.5f), 128.0f};
    s.materials = {ground, red, blue, matte_yellow, green_gem};

    s.planes = {{{0, 0, 0}, {0, 1, 0}, 0}};
    s.spheres = {
        {{T(-1.3), T(1), T(-4.5)}, T(1), 1},
        {{T(1.4), T(0.6), T(-3.6)}, T(0.6), 2},
        {{T(0.1), T(0.35), T(-2.6)}, T(0.35), 3},
    };
    add_icosahedron(s, vec3<T>(T(0.9), T(0.9), T(-6.2)), T(0.9), 4);

    // A bright key light up and to the left, a dimmer warm fill to the right:
    // intensities are what each delivers at distance 1 (falls off as 1/d^2).
    s.lights = {
        {{-4, 6, 1}, color(70, 70, 65)},
        {{5, 3, -1}, color(14, 11, 8)},
    };
    s.ambient = color(0.06f, 0.06f, 0.08f);
    s.background = color(0.55f, 0.7f, 0.95f);
    return s;
}

template <class T>
int material_of(const scene<T>& s, int object) {
    const size_t i = size_t(object);
    if (i < s.spheres.size()) return s.spheres[i].material;
    if (i < s.spheres.size() + s.planes.size()) return s.planes[i - s.spheres.size()].material;
    return s.triangles[i - s.spheres.size() - s.planes.size()].material;
}

template <class T>
image render_scene(const program_options& opt, long& rays) {
    scene<T> world = lit_scene<T>();
    camera_description view;
    view.eye = {0, 1.4, 1.5};
    view.look_at = {0, 0.6, -4};
    view.fov_degrees = 50;
    if (opt.scene_file) {  // --scene FILE: your own scene, lit and shaded by your code
        world = convert_scene<T>(opt.scene_file->world);
        view = opt.scene_file->camera;
    }
    const scene_camera<T> camera(view, opt.width, opt.height);

    // Objects are numbered spheres, then planes, then triangles (scene.hpp).
    const ch03::object_intersector<T> intersect = [&](int i, const ray<T>& r, const interval<T>& range) {
        size_t k = size_t(i);
        if (k < world.spheres.size()) return ch02::intersect_sphere(world.spheres[k], r, range);
        k -= world.spheres.size();
        if (k < world.planes.size()) return ch04::intersect_plane(world.planes[k], r, range);
        k -= world.planes.size();
        return ch05::intersect_triangle(world.triangles[k], r, range);
    };

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
        const material m = ch06::material_at(world.materials[size_t(material_of(world, hit->object))], hit->point);
        return ch06::shade(hit->point, hit->normal, -r.direction, m, world.lights, world.ambient, occluded);
    });
    rays = long(opt.width) * opt.height + shadow_rays.load();
    return img;
}

}  // namespace

int main(int argc, char** argv) {
    rt::chapter_program program;
    program.id = "ch06";
    program.title = "shading";
    program.accepts_scene_file = true;  // --scene FILE renders your own scene with your code
    program.render = [](const rt::program_options& opt, long& rays) {
        return opt.prec == rt::precision::single ? render_scene<float>(opt, rays) : render_scene<double>(opt, rays);
    };
    return rt::run_chapter_program(argc, argv, program);
}
