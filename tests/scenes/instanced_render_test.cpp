// instanced_render_test.cpp — rt-render's two-level tree
// (tools/render/instanced_path.hpp): a scene built from instances gives the
// same hits as the same scene built flat; an instance's box holds its
// object; normals under a non-uniform scale stay perpendicular to the surface.
#include "fast_path.hpp"
#include "common/image_compare.hpp"
#include "instanced_path.hpp"
#include "scene_plan.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <string>

using namespace rt;
using namespace rt::render_tool;

namespace {

const std::string camera = R"("camera": {"eye": [2.1, 1.3, 1.7], "look_at": [0, 0, 0], "up": [0, 0, 1], "fov": 50, "width": 48, "height": 40})";

// The packet walk (instanced_packets.cpp) against the one-ray walk, ray by
// ray: the same t, material, normal and point, to the bit. First the
// primary rays of each 8 x 4 tile (coherent, as rt-render sends them), then
// packets of rays with random origins and directions (every ray of a packet
// going its own way through the trees).
void check_packets_agree(const scene_description& d, const instanced_scene& built) {
    const scene_camera<double> cam(d.camera);
    const double tmin = cam.primary_range().min;
    long compared = 0, different = 0, hits = 0;
    auto compare = [&](const ray<double> (&rays)[packet_width]) {
        instanced_scene::hit together[packet_width];
        built.closest(rays, tmin, infinity<double>, together);
        for (int k = 0; k < packet_width; ++k) {
            const instanced_scene::hit one = built.closest(rays[k], tmin, infinity<double>);
            const instanced_scene::hit& h = together[k];
            const bool same = one.material == h.material &&
                              (one.material < 0 || (one.t == h.t && one.normal == h.normal && one.point == h.point &&
                                                    one.plane_normal == h.plane_normal));
            if (!same && different++ < 3)
                MESSAGE("ray " << compared << ": one-ray walk t " << one.t << " material " << one.material
                               << ", packet walk t " << h.t << " material " << h.material);
            ++compared;
            hits += one.material >= 0;
        }
    };
    ray<double> rays[packet_width];
    for (int row0 = 0; row0 < d.camera.height; row0 += 4)
        for (int col0 = 0; col0 < d.camera.width; col0 += 8) {
            for (int k = 0; k < packet_width; ++k)
                rays[k] = cam.primary_ray(std::min(col0 + k % 8, d.camera.width - 1),
                                          std::min(row0 + k / 8, d.camera.height - 1));
            compare(rays);
        }
    std::mt19937_64 random(20261202);
    std::uniform_real_distribution<double> u(-1.5, 1.5);
    for (int packet = 0; packet < 64; ++packet) {
        for (int k = 0; k < packet_width; ++k) {
            const vec3d from(u(random), u(random), u(random)), towards(0.3 * u(random), 0.3 * u(random), 0.3 * u(random));
            rays[k] = {from, towards - from};  // not normalised: t is in units of |d|
        }
        compare(rays);
    }
    CHECK(different == 0);
    CHECK(hits > compared / 10);  // the rays meet the scene
}

// Every pixel's primary hit through the two-level tree against the flat
// scene's (instances expanded, the specialised path in double): hit or miss
// alike, t to 1e-9 relative (each level's transform rounds the ray).
void check_same_hits(const scene_description& d) {
  // Every instance walked (0, the default), and placed objects of up to 8192 shapes stored expanded.
  for (const std::uint64_t expand : {std::uint64_t(0), std::uint64_t(8192)}) {
    CAPTURE(expand);
    const instanced_scene built(d, expand);
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
}

// Two clusters of balls and triangles, each cluster three instances of the
// ball (turned, scaled, mirrored), over a plane.
scene_description instances_of_instances() {
    return parse_scene("{" + camera + R"(, "materials": [{}, {"diffuse": [1, 0, 0]}],
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
}

}  // namespace

TEST_CASE("a scene built from instances of instances hits where the same scene built flat does") {
    check_same_hits(instances_of_instances());
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

TEST_CASE("the flat sphereflake's sub-flakes are copies of the whole: flat and instanced give the same spheres and t") {
    // common/spd.hpp: the flat generator turns every sphere's k-th child by
    // the same turn relative to its parent, so the flat flake is the
    // instanced one expanded, to rounding. Both compose the same turns and
    // scales, in another order: each level adds a 3x3 product and a centre
    // step of a few roundings each, on coordinates of the flake's size (1),
    // so a sphere of level L may move by a few epsilons per level. The bound
    // the spheres are held to: 4 (L + 1) epsilon, absolute (the flake's
    // size is 1); the largest difference measured is printed.
    constexpr int level = 5;  // 66,430 spheres: level 3 is the first whose sub-flakes can be turned wrongly
    const std::string view = R"("camera": {"eye": [2.1, 1.3, 1.7], "look_at": [0, 0, 0.05], "up": [0, 0, 1], "fov": 42, "width": 160, "height": 160},
        "materials": [{}, {"diffuse": [0.8, 0.55, 0.45]}], "generate": {"name": "balls", "size": )" + std::to_string(level);
    const scene_description flat = parse_scene("{" + view + "}}", "flat-flake.json");
    const scene_description instanced = parse_scene("{" + view + R"(, "instanced": true}})", "instanced-flake.json");
    const scene_description expanded = flattened(instanced);
    REQUIRE(flat.world.spheres.size() == 66430);
    REQUIRE(expanded.world.spheres.size() == flat.world.spheres.size());
    const double eps = std::numeric_limits<double>::epsilon(), sphere_bound = 4 * (level + 1) * eps;
    double worst = 0;
    long outside = 0;
    for (size_t i = 0; i < flat.world.spheres.size(); ++i) {  // the same order: depth first, children in turn
        const auto &a = flat.world.spheres[i], &b = expanded.world.spheres[i];
        double d = std::fabs(a.radius - b.radius);
        for (int k = 0; k < 3; ++k) d = std::max(d, std::fabs(a.center[k] - b.center[k]));
        worst = std::max(worst, d);
        outside += !(d <= sphere_bound);
    }
    MESSAGE("largest centre or radius difference: " << worst / eps << " epsilon (bound " << sphere_bound / eps << ")");
    CHECK(outside == 0);

    // Every pixel: the flat flake through the specialised path (double,
    // robust sphere test, its tree) against the two-level tree. Where the
    // ray meets the surface at |cos| >= 0.2, t within chapter 10's bound
    // 16 epsilon t c (chapters/10-transforms/instancing.hpp: c the largest
    // of 1, the ray's distance from the sphere over its radius, and the
    // sphere's coordinates over the ray's length to the hit); grazing hits
    // may differ in hit or miss and are counted apart.
    scene_plan plan = make_plan(flat, 1e-3, precision::double_);
    plan.form = sphere_formulation::robust;
    const primary_hits ref = trace_primary(flat, plan, flat.camera.width, flat.camera.height);
  // Every instance walked (0, the default), and the sub-flakes of up to 8,192 spheres stored expanded.
  for (const std::uint64_t expand : {std::uint64_t(0), std::uint64_t(8192)}) {
    CAPTURE(expand);
    const instanced_scene built(instanced, expand);
    const scene_camera<double> cam(instanced.camera);
    long compared = 0, grazing = 0, wrong = 0, sphere_hits = 0;
    double worst_ratio = 0;
    for (int row = 0; row < flat.camera.height; ++row)
        for (int col = 0; col < flat.camera.width; ++col) {
            const size_t i = size_t(row) * size_t(flat.camera.width) + size_t(col);
            const ray<double> r = cam.primary_ray(col, row);
            const instanced_scene::hit h = built.closest(r, cam.primary_range().min, infinity<double>);
            const bool hit = h.material >= 0, ref_hit = ref.object[i] >= 0;
            const double cosine = hit ? std::fabs(dot(h.normal, r.direction)) / length(r.direction) : 1;
            double ref_cosine = 1;  // the flat hit's, from its sphere (or the ground's normal z)
            if (ref_hit) {
                const vec3d n = size_t(ref.object[i]) < flat.world.spheres.size()
                                    ? normalize(r.origin + double(ref.t[i]) * r.direction -
                                                flat.world.spheres[size_t(ref.object[i])].center)
                                    : vec3d(0, 0, 1);
                ref_cosine = std::fabs(dot(n, r.direction)) / length(r.direction);
            }
            if (hit != ref_hit) {
                // A miss on one side and a hit on the other: only at a grazing hit.
                (hit ? cosine : ref_cosine) < 0.2 ? ++grazing : ++wrong;
                continue;
            }
            if (!hit) continue;
            if (cosine < 0.2) {
                ++grazing;
                continue;
            }
            const double t_flat = double(ref.t[i]);
            double c = 1;
            if (size_t(ref.object[i]) < flat.world.spheres.size()) {
                const sphere<double>& s = flat.world.spheres[size_t(ref.object[i])];
                const double reach = t_flat * length(r.direction);
                c = std::max({1.0, length(r.origin - s.center) / s.radius,
                              (std::max({std::fabs(s.center.x), std::fabs(s.center.y), std::fabs(s.center.z)}) + s.radius) / reach});
                ++sphere_hits;
            }
            const double ratio = std::fabs(h.t - t_flat) / (eps * t_flat * c);
            worst_ratio = std::max(worst_ratio, ratio);
            wrong += !(ratio <= 16);
            ++compared;
        }
    MESSAGE("largest |t - t_flat| / (epsilon t c): " << worst_ratio << " over " << compared << " hits (" << sphere_hits
                                                     << " on spheres), " << grazing << " grazing");
    CHECK(wrong == 0);
    CHECK(sphere_hits > 5000);                 // the flake fills much of the view
    CHECK(grazing < compared / 50);            // grazing hits are the silhouettes' few
  }
}

TEST_CASE("a checkered ground under instances is drawn as on the flat path (the plane's own checker axes)") {
    // z up, as the SPD scenes (the flake's ground, material 0, at z = -0.5):
    // the checker's squares lie in x and y. With the
    // default axes (x and z) the ground would show stripes.
    const scene_description d = parse_scene(R"({"camera": {"eye": [2.1, 1.3, 1.7], "look_at": [0, 0, 0], "up": [0, 0, 1], "width": 64, "height": 48},
        "materials": [{"diffuse": [0.75, 0.75, 0.7], "checker": [0.35, 0.35, 0.4]}, {"diffuse": [0.8, 0.55, 0.45]}],
        "lights": [{"position": [4, 3, 2], "intensity": [30, 30, 28]}],
        "generate": {"name": "balls", "size": 2, "instanced": true}})", "checker-ground.json");
    const instanced_scene built(d);
    render_stats stats;
    const image by_instances = render_instanced(d, built, 64, 48, stats);
    const scene_description flat = flattened(d);
    const image flat_picture = render_fast(flat, make_plan(flat, 1e-3, precision::double_), 64, 48, stats);
    // The usual tolerance (8/255 in 0.5% of the pixels): a silhouette pixel
    // may go either way (the flat plan's plain sphere test against the
    // robust one here); stripes instead of squares move a third of the ground.
    const compare_result same = compare_images(by_instances, flat_picture, compare_tolerance{});
    MESSAGE(same.summary(compare_tolerance{}));
    CHECK(same.within(compare_tolerance{}));
}

TEST_CASE("the packet walk gives every ray the one-ray walk's answer, to the bit") {
    // Instances of instances with a plane; the sphereflake and the tetrahedron
    // (triangles) by instancing, every instance walked and the small ones stored
    // expanded; an ellipsoid (a sphere under a non-uniform scale).
    check_packets_agree(instances_of_instances(), instanced_scene(instances_of_instances()));
    for (const char* g : {R"("name": "balls", "size": 3)", R"("name": "tetra", "size": 4)"})
        for (const std::uint64_t expand : {std::uint64_t(0), std::uint64_t(8192)}) {
            CAPTURE(g);
            CAPTURE(expand);
            const scene_description d = parse_scene(
                "{" + camera + R"(, "materials": [{}, {}], "generate": {)" + g + R"(, "instanced": true}})", "flake.json");
            check_packets_agree(d, instanced_scene(d, expand));
        }
    const scene_description ellipsoid = parse_scene(
        R"({"camera": {"eye": [4, 3, 5], "look_at": [0, 0, 0], "width": 40, "height": 40},
            "spheres": [{"center": [0, 0, 0], "radius": 1, "transform": {"scale": [3, 0.5, 1]}}]})", "ellipsoid.json");
    check_packets_agree(ellipsoid, instanced_scene(ellipsoid));
}
