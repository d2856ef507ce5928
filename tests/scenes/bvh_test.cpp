// bvh_test.cpp — the renderer's tree (tools/render/bvh_build.hpp) gives the
// same answers as brute force, bit for bit: the same object and the same t
// for every primary ray. The leaves run the brute-force kernels unchanged,
// so the tree may only decide *which* objects are tested; a box that wrongly
// dropped an object (rounding in the slab test, a zero direction component,
// a flat box) would show here as a pixel on another object or at another t.
#include "bvh_build.hpp"
#include "fast_path.hpp"
#include "scene_plan.hpp"

#include "common/spd.hpp"

#include <doctest/doctest.h>

#include <functional>
#include <random>
#include <string>

using namespace rt;
using namespace rt::render_tool;

namespace {

const char* camera_of(const std::string& type) {
    if (type == "orthographic")  // looking straight down -z: rays with two zero direction components
        return R"("camera": {"type": "orthographic", "eye": [0, 0, 5], "look_at": [0, 0, 0], "view_height": 3.5})";
    return R"("camera": {"eye": [2.1, 1.3, 1.7], "look_at": [0, 0, 0], "up": [0, 0, 1], "fov": 50})";
}

scene_description generated(const std::string& name, int size, const std::string& camera) {
    return parse_scene(std::string("{") + camera_of(camera) + R"(, "materials": [{}, {}], "generate": {"name": ")" +
                           name + R"(", "size": )" + std::to_string(size) + "}}",
                       "bvh-test.json");
}

// Random spheres and triangles (some of them flat in z: a planar mesh has
// boxes of zero thickness), seeded.
scene_description random_scene(unsigned seed, const std::string& camera) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(-1.5, 1.5), r(0.01, 0.15);
    std::string text = std::string("{") + camera_of(camera) + R"(, "spheres": [)";
    auto point = [&](double z) { return "[" + std::to_string(u(rng)) + ", " + std::to_string(u(rng)) + ", " + std::to_string(z) + "]"; };
    for (int i = 0; i < 300; ++i)
        text += std::string(i ? ", " : "") + R"({"center": )" + point(u(rng)) + R"(, "radius": )" + std::to_string(r(rng)) + "}";
    text += R"(], "triangles": [)";
    for (int i = 0; i < 300; ++i) {
        const double z = i % 2 ? -0.25 : u(rng);  // every other triangle in the plane z = -0.25
        text += std::string(i ? ", " : "") + R"({"a": )" + point(z) + R"(, "b": )" + point(i % 2 ? z : u(rng)) +
                R"(, "c": )" + point(i % 2 ? z : u(rng)) + "}";
    }
    return parse_scene(text + "]}", "bvh-random.json");
}

// Primary hits with and without the tree, in the plan's precision and in
// the other one: the same t for every pixel, bit for bit, and the same
// object, at an exact tie too (two objects hit at the very same t: the
// shared edge of two triangles of a flat mesh, coplanar overlapping
// triangles, duplicates): the lowest number, as brute force and chapter 08.
void check_tree_equals_brute_force(const scene_description& d) {
    for (precision p : {precision::single, precision::double_}) {
        scene_plan plan = make_plan(d, 1e-3, p);
        plan.tree = true;
        const primary_hits with = trace_primary(d, plan, 64, 48);
        plan.tree = false;
        const primary_hits without = trace_primary(d, plan, 64, 48);
        int other_t = 0, ties = 0, hits = 0;
        for (size_t i = 0; i < with.object.size(); ++i) {
            const bool same_t = with.t[i] == without.t[i] && (with.object[i] < 0) == (without.object[i] < 0);
            if (!same_t && other_t < 3)
                MESSAGE("pixel " << i << ": tree " << with.object[i] << " t=" << double(with.t[i]) << ", brute force "
                                 << without.object[i] << " t=" << double(without.t[i]));
            other_t += !same_t;
            ties += same_t && with.object[i] != without.object[i];
            hits += without.object[i] >= 0;
        }
        CAPTURE(p == precision::single ? "float" : "double");
        CHECK(hits > 100);  // the view really shows the objects
        CHECK(other_t == 0);
        CHECK(ties == 0);  // the tree once kept the object its leaves reached first
    }
}

}  // namespace

TEST_CASE("tree = brute force: sphereflake, pinhole and orthographic") {
    check_tree_equals_brute_force(generated("balls", 3, "pinhole"));
    check_tree_equals_brute_force(generated("balls", 3, "orthographic"));
}

TEST_CASE("tree = brute force: Sierpinski tetrahedron and fractal mountain (triangles)") {
    check_tree_equals_brute_force(generated("tetra", 4, "pinhole"));
    check_tree_equals_brute_force(generated("mount", 4, "pinhole"));
    check_tree_equals_brute_force(generated("mount", 4, "orthographic"));  // looking down on the mountain
}

// Every sphere and triangle twice, the copies far apart in the numbering:
// every hit is a tie, which the tree must settle as brute force does.
TEST_CASE("tree = brute force at exact ties: the lowest object number (duplicated spheres and triangles)") {
    scene_description d = random_scene(4, "pinhole");
    const auto spheres = d.world.spheres;
    const auto triangles = d.world.triangles;
    d.world.spheres.insert(d.world.spheres.begin(), spheres.rbegin(), spheres.rend());
    d.world.triangles.insert(d.world.triangles.end(), triangles.rbegin(), triangles.rend());
    check_tree_equals_brute_force(d);
}

TEST_CASE("tree = brute force: random spheres and triangles, some flat") {
    for (unsigned seed : {1u, 2u, 3u}) {
        CAPTURE(seed);
        check_tree_equals_brute_force(random_scene(seed, "pinhole"));
        check_tree_equals_brute_force(random_scene(seed, "orthographic"));
    }
}

TEST_CASE("build_bvh puts every pair of children in one cache line: an even slot of an array that starts on a line") {
    // The instanced packet walk reads both children's boxes (push_children
    // in tools/render/instanced_packets.cpp), and collapse_to_wide too: 2 x 32
    // bytes, one line when the pair starts at an even slot of an aligned
    // array, two lines otherwise. 300,000 boxes: more than one build task
    // (2^17 objects each), whose blocks of slots must keep pairs even too.
    for (size_t count : {size_t(9), size_t(37), size_t(300000)}) {
        CAPTURE(count);
        std::mt19937 rng{unsigned(count)};
        std::uniform_real_distribution<float> u(-100, 100);
        std::vector<bvh_box> boxes(count);
        for (bvh_box& b : boxes)
            for (int a = 0; a < 3; ++a) b.lo[a] = u(rng), b.hi[a] = b.lo[a] + 0.5f;
        const bvh_tree tree = build_bvh(boxes);
        CHECK(reinterpret_cast<std::uintptr_t>(tree.nodes.data()) % 64 == 0);
        size_t inner = 0, odd = 0, reached = 0;
        std::vector<std::uint32_t> stack{0};
        while (!stack.empty()) {
            const bvh_node& n = tree.nodes[stack.back()];
            stack.pop_back();
            ++reached;
            if (n.count > 0) continue;
            ++inner;
            odd += n.first % 2;
            stack.push_back(n.first), stack.push_back(n.first + 1);
        }
        CHECK(inner > 0);
        CHECK(reached == 2 * inner + 1);
        CHECK(odd == 0);
    }
}

TEST_CASE("the plan uses a tree from tree_threshold objects on and says so") {
    const scene_plan small = make_plan(generated("balls", 1, "pinhole"), 1e-3, std::nullopt);  // 10 spheres
    CHECK_FALSE(small.tree);
    CHECK(small.describe().find("brute force (10 spheres and triangles") != std::string::npos);
    const scene_plan big = make_plan(generated("balls", 3, "pinhole"), 1e-3, std::nullopt);  // 820 spheres
    CHECK(big.tree);
    CHECK(big.describe().find("BVH over 820 spheres and triangles") != std::string::npos);
}

namespace {

// A lit render's shadow rays, traced 32 at a time as render_fast traces
// them (fast_path_shadows.hpp), find exactly the blockers any_hit finds one
// ray at a time, with and without the tree, in both precisions; and
// chapter 06's shade() asks no ray that was not asked ahead. The lights sit
// among the objects (rays that end between them), far away, and on an
// object (a ray of length 0, or one that starts where it ends).
void check_shadow_packets_agree(scene_description d) {
    d.world.lights.clear();
    d.world.lights.push_back({vec3d(0.1, 0.2, 0.05), color(1)});
    d.world.lights.push_back({vec3d(4, 3, 6), color(1)});
    if (!d.world.spheres.empty()) {
        const sphere<double>& s = d.world.spheres.back();
        d.world.lights.push_back({s.center + vec3d(s.radius, 0, 0), color(1)});
    }
    const pass_timer once = [](const std::function<void()>& pass) {
        pass();
        return 0.0;
    };
    for (precision p : {precision::single, precision::double_})
        for (bool tree : {false, true}) {
            scene_plan plan = make_plan(d, 1e-3, p);
            plan.tree = tree;
            const shadow_figures f = time_shadow_rays(d, plan, 64, 48, once);
            CAPTURE(p == precision::single ? "float" : "double");
            CAPTURE(tree);
            CHECK(f.shadow_rays > 2000);
            CHECK(f.occluded_one_at_a_time > 100);                          // the lights really are hidden at times
            CHECK(f.occluded_one_at_a_time < f.shadow_rays - 100);         // and seen at times
            CHECK(f.occluded == f.occluded_one_at_a_time);
            CHECK(f.asked_but_not_ahead == 0);
        }
}

}  // namespace

TEST_CASE("shadow rays in packets of 32 are blocked exactly when any_hit says so: sphereflake, mountain, random scenes") {
    check_shadow_packets_agree(generated("balls", 3, "pinhole"));
    check_shadow_packets_agree(generated("mount", 4, "pinhole"));
    for (unsigned seed : {1u, 2u}) {
        CAPTURE(seed);
        check_shadow_packets_agree(random_scene(seed, "pinhole"));
        check_shadow_packets_agree(random_scene(seed, "orthographic"));
    }
}
