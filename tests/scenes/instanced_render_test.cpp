// instanced_render_test.cpp — rt-render's two-level tree
// (tools/render/instanced_path.hpp): a scene built from instances gives the
// same hits as the same scene built flat; an instance's box holds its
// object; normals under a non-uniform scale stay perpendicular to the surface.
#include "fast_path.hpp"
#include "instanced_path.hpp"
#include "scene_plan.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <random>
#include <string>

using namespace rt;
using namespace rt::render_tool;

namespace {

const std::string camera = R"("camera": {"eye": [2.1, 1.3, 1.7], "look_at": [0, 0, 0], "up": [0, 0, 1], "fov": 50, "width": 48, "height": 40})";

// Every pixel's primary hit through the two-level tree against the flat
// scene's (instances expanded, the specialised path in double): hit or miss
// alike, t to 1e-9 relative (each level's transform rounds the ray).
void check_same_hits(const scene_description& d) {
    const instanced_scene built(d);
    const scene_description flat = flattened(d);
    scene_plan plan = make_plan(flat, 1e-3, precision::double_);
    const primary_hits ref = trace_primary(flat, plan, d.camera.width, d.camera.height);
    const scene_camera<double> cam(d.camera);
    long hits = 0, different = 0;
    for (int row = 0; row < d.camera.height; ++row)
        for (int col = 0; col < d.camera.width; ++col) {
            const size_t i = size_t(row) * size_t(d.camera.width) + size_t(col);
            const instanced_scene::hit h = built.closest(cam.primary_ray(col, row), cam.primary_range().min, infinity<double>);
            const bool hit = h.material >= 0, ref_hit = ref.object[i] >= 0;
            if (hit != ref_hit || (hit && !(std::fabs(h.t - double(ref.t[i])) <= 1e-9 * double(ref.t[i])))) ++different;
            hits += hit;
        }
    CHECK(different == 0);
    CHECK(hits > 100);  // the view sees the scene
}

}  // namespace

TEST_CASE("a scene built from instances of instances hits where the same scene built flat does") {
    const scene_description d = parse_scene("{" + camera + R"(, "materials": [{}, {"diffuse": [1, 0, 0]}],
      "objects": {
        "ball": {"spheres": [{"center": [0, 0, 0], "radius": 0.3, "material": 1}],
                 "triangles": [{"a": [0.3, 0, 0], "b": [0, 0.5, 0], "c": [0, 0, 0.6]}]},
        "cluster": {"instances": [
          {"object": "ball"},
          {"object": "ball", "transform": {"translate": [0.7, 0, 0], "rotate": {"axis": [1, 2, 3], "degrees": 40}, "scale": 0.6}},
          {"object": "ball", "transform": [{"scale": -0.5}, {"translate": [0, 0.7, 0.2]}]}]}
      },
      "instances": [{"object": "cluster"},
                    {"object": "cluster", "transform": {"translate": [-0.6, -0.6, 0], "rotate": {"axis": [0, 0, 1], "degrees": 120}, "scale": 0.7}}],
      "planes": [{"point": [0, 0, -0.5], "normal": [0, 0, 1]}]})", "instanced-test.json");
    check_same_hits(d);
}

TEST_CASE("the instanced sphereflake and tetrahedron hit where the flat ones do") {
    for (const char* g : {R"("name": "balls", "size": 3)", R"("name": "tetra", "size": 4)"}) {
        const scene_description d = parse_scene(
            "{" + camera + R"(, "materials": [{}, {}], "generate": {)" + g + R"(, "instanced": true}})", "flake.json");
        check_same_hits(d);
    }
}

TEST_CASE("an instance's box holds every point of its object, turned and squashed") {
    const scene_description d = parse_scene("{" + camera + R"(,
      "spheres": [{"center": [0.2, -0.1, 0.3], "radius": 0.5,
                   "transform": [{"scale": [3, 0.02, 1]}, {"rotate": {"axis": [1, 1, 0], "degrees": 37}}, {"translate": [1e3, -2e3, 5]}]}]})",
                                            "box.json");
    const instanced_scene built(d);
    const std::vector<instanced_scene::placed_box> boxes = built.top_instance_boxes();
    REQUIRE(boxes.size() == 1);
    const affine_transform& to_world = d.instances[0].to_parent;
    const sphere<double>& s = d.objects[0].spheres[0];
    std::mt19937 rng(7);
    std::normal_distribution<double> n;
    long outside = 0;
    for (int i = 0; i < 100000; ++i) {
        const vec3d u = normalize(vec3d(n(rng), n(rng), n(rng)));
        const vec3d p = to_world.linear * (s.center + s.radius * u) + to_world.offset;
        for (int a = 0; a < 3; ++a) outside += !(p[a] >= boxes[0].lo[a] && p[a] <= boxes[0].hi[a]);
    }
    CHECK(outside == 0);
    // And the box is not the world: within 1% of the ellipsoid's own extent
    // (the corners of its object box, turned, make it a little larger).
    CHECK(boxes[0].hi.x - boxes[0].lo.x < 2 * 0.5 * 3 * 1.5);
}

TEST_CASE("normals under a non-uniform scale stay perpendicular to the surface (inverse transpose)") {
    // An ellipsoid x^2/9 + y^2/0.25 + z^2 = 1 (a unit sphere scaled by [3, 0.5, 1]) seen from outside:
    // its normal at p is along (x/9, y/0.25, z), which the matrix itself would not give.
    const scene_description d = parse_scene(
        R"({"camera": {"eye": [4, 3, 5], "look_at": [0, 0, 0], "width": 40, "height": 40},
            "spheres": [{"center": [0, 0, 0], "radius": 1, "transform": {"scale": [3, 0.5, 1]}}]})", "ellipsoid.json");
    const instanced_scene built(d);
    const scene_camera<double> cam(d.camera);
    int hits = 0;
    double worst = 0;
    for (int row = 0; row < 40; ++row)
        for (int col = 0; col < 40; ++col) {
            const ray<double> r = cam.primary_ray(col, row);
            const instanced_scene::hit h = built.closest(r, 1, infinity<double>);
            if (h.material < 0) continue;
            ++hits;
            const vec3d p = r.origin + h.t * r.direction;
            CHECK(std::fabs(p.x * p.x / 9 + p.y * p.y / 0.25 + p.z * p.z - 1) < 1e-9);
            const vec3d gradient = normalize(vec3d(p.x / 9, p.y / 0.25, p.z));
            worst = std::max(worst, length(h.normal - gradient));
        }
    CHECK(hits > 50);
    CHECK(worst < 1e-9);
}
