// main.cpp — chapter 05's program: a closed triangle mesh among spheres.
//
// The icosahedron in the middle is twenty triangles, each tested with *your*
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
#include "plane.hpp"
#include "scene_loop.hpp"
#include "sphere.hpp"
#include "triangle.hpp"

#include "common/camera.hpp"
#include "common/program.hpp"
#include "common/render.hpp"
#include "common/scene.hpp"
#include "common/scene_file.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace {

using namespace rt;

// The twelve corners of an icosahedron are the cyclic permutations of
// (0, +-1, +-phi); two corners share an edge exactly when they are 2 apart.
// So the faces are the triples of corners that are pairwise 2 apart, and no
// face list needs to be typed in. Each face is turned so that its corners
// run counter-clockwise seen from outside (normal pointing away from the centre).
template <class T>
std::vector<triangle<T>> icosahedron(const vec3<T>& center, T size, T turn_radians, int material) {
    const T phi = (T(1) + std::sqrt(T(5))) / T(2);
    std::vector<vec3<T>> corners;
    for (T s1 : {T(-1), T(1)})
        for (T s2 : {-phi, phi}) {
            corners.push_back({0, s1, s2});
            corners.push_back({s1, s2, 0});
            corners.push_back({s2, 0, s1});
        }
    const auto neighbours = [&](size_t i, size_t j) {
        return std::fabs(length(corners[i] - corners[j]) - T(2)) < T(1e-3);
    };
    // Place the mesh: turn it about the vertical axis, scale it, move it.
    const T c = std::cos(turn_radians), s = std::sin(turn_radians);
    const auto place = [&](const vec3<T>& p) {
        return center + size * vec3<T>(c * p.x + s * p.z, p.y, -s * p.x + c * p.z);
    };
    std::vector<triangle<T>> faces;
    for (size_t i = 0; i < corners.size(); ++i)
        for (size_t j = i + 1; j < corners.size(); ++j)
            for (size_t k = j + 1; k < corners.size(); ++k) {
                if (!neighbours(i, j) || !neighbours(j, k) || !neighbours(i, k)) continue;
                vec3<T> a = corners[i], b = corners[j], d = corners[k];
                if (dot(cross(b - a, d - a), a + b + d) < T(0)) std::swap(b, d);
                faces.push_back({place(a), place(b), place(d), material});
            }
    return faces;  // 20 faces; every edge belongs to exactly two of them
}

template <class T>
scene<T> mesh_among_spheres() {
    scene<T> s;
    material ground;
    ground.diffuse = color(0.85f, 0.85f, 0.8f);
    ground.checker = true;
    ground.checker_color = color(0.15f, 0.2f, 0.3f);
    s.materials = {
        ground,
        {color(0.95f, 0.75f, 0.2f)},  // gold: the mesh
        {color(0.9f, 0.2f, 0.15f)},   // red
        {color(0.2f, 0.35f, 0.9f)},   // blue
    };
    s.spheres = {
        {{T(-2.1), T(0.7), T(-1.2)}, T(0.7), 2},
        {{T(1.9), T(0.55), T(0.1)}, T(0.55), 3},
    };
    s.planes = {{{0, 0, 0}, {0, 1, 0}, 0}};
    // Corners at distance sqrt(1 + phi^2) from the centre; the two lowest sit
    // at y = -phi before scaling, so lifting the centre by phi * size rests
    // the mesh on the ground.
    const T size = T(0.75);
    const T phi = (T(1) + std::sqrt(T(5))) / T(2);
    s.triangles = icosahedron<T>({T(0), phi * size, T(-1.5)}, size, T(0.45), 1);
    return s;
}

// Unit squares on the ground (x and z; see chapter 04's program).
template <class T>
color checker(const material& m, const vec3<T>& point) {
    const T squares = std::fmod(std::floor(point.x) + std::floor(point.z), T(2));  // 0 or +-1 (see chapter 04)
    return squares == T(0) ? m.diffuse : m.checker_color;
}

template <class T>
image render_scene(const program_options& opt) {
    scene<T> world = mesh_among_spheres<T>();
    camera_description view;
    view.eye = {0.5, 2.2, 5};
    view.look_at = {0, 0.9, -1.2};
    view.fov_degrees = 50;
    if (opt.scene_file) {  // --scene FILE: your own scene, drawn with your code
        world = convert_scene<T>(opt.scene_file->world);
        view = opt.scene_file->camera;
    }
    const int sphere_count = int(world.spheres.size());
    const int plane_count = int(world.planes.size());
    const scene_camera<T> camera(view, opt.width, opt.height);

    // Objects are numbered spheres, then planes, then triangles (common/scene.hpp).
    const ch03::object_intersector<T> intersect = [&](int i, const ray<T>& r, const interval<T>& range) {
        if (i < sphere_count) return ch02::intersect_sphere(world.spheres[size_t(i)], r, range);
        if (i < sphere_count + plane_count) return ch04::intersect_plane(world.planes[size_t(i - sphere_count)], r, range);
        return ch05::intersect_triangle(world.triangles[size_t(i - sphere_count - plane_count)], r, range);
    };
    const vec3<T> to_light = normalize(vec3<T>(T(-0.5), T(1.0), T(0.7)));

    return render(opt.width, opt.height, [&](int col, int row) {
        ray<T> r = camera.primary_ray(col, row);
        // t > 1: only what lies beyond the image plane is visible (chapter 01);
        // an orthographic camera from a scene file takes t > 0.
        auto hit = ch03::closest_hit(world.object_count(), intersect, r, camera.primary_range());
        if (!hit) return world.background;

        color albedo;
        if (hit->object < sphere_count) {
            albedo = world.materials[size_t(world.spheres[size_t(hit->object)].material)].diffuse;
        } else if (hit->object < sphere_count + plane_count) {
            const plane<T>& p = world.planes[size_t(hit->object - sphere_count)];
            albedo = checker(world.materials[size_t(p.material)], hit->point);
        } else {
            const triangle<T>& tri = world.triangles[size_t(hit->object - sphere_count - plane_count)];
            albedo = world.materials[size_t(tri.material)].diffuse;
            // Near an edge one barycentric coordinate is close to 0: draw an outline there.
            const vec3<T> w = ch05::barycentric(tri, hit->point);
            if (std::min({w.x, w.y, w.z}) < T(0.025)) albedo *= 0.35f;
        }
        const float lambert = float(std::max(T(0), dot(hit->normal, to_light)));
        return albedo * (0.2f + 0.8f * lambert);
    });
}

}  // namespace

int main(int argc, char** argv) {
    rt::chapter_program program;
    program.id = "ch05";
    program.title = "triangle";
    program.accepts_scene_file = true;  // --scene FILE renders your own scene with your code
    program.render = [](const rt::program_options& opt, long& rays) {
        rays = long(opt.width) * opt.height;
        return opt.prec == rt::precision::single ? render_scene<float>(opt) : render_scene<double>(opt);
    };
    return rt::run_chapter_program(argc, argv, program);
}
