// Hidden tests for chapter 08 (run by the autograder only).
//
// Families, each from a fixed seed, in both precisions:
//   slab test      random boxes and rays against the exact answer (long double
//                  from the very inputs): every crossed box is a hit, every
//                  clearly missed box a miss, the entry close to the exact one;
//                  parallel rays with +0 / -0 components on faces, edges and
//                  corners; flat and point boxes; grazing rays near the edge of
//                  a flat mesh, where an exit that is not widened misses
//   traversal      the tree's answer equals brute force's bit for bit: random
//                  spheres, triangles, mixed scenes with a planar mesh, rays
//                  along the axes, from inside boxes, with finite ranges;
//                  ties (equal t) go to the lowest index; empty scene, one
//                  object, leaves of many objects; nearer children first and
//                  pruning by the closest hit (counted object tests);
//                  any_hit agrees with closest_hit
//   SAH build      valid trees (every object once, exact boxes, leaf sizes),
//                  also for coincident centres and flat scenes; cheaper than
//                  the median split on clustered scenes
// Failure messages name the idea that went wrong, never inputs or expected
// values: every check is a plain bool computed beforehand.
#include "../public/ch08_scenes.hpp"
#include "08-acceleration/median_build.hpp"

#include "test_support.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

using namespace rt;
using namespace rt::ch08;
using namespace rt::ch08::test;

namespace {

using wide = long double;

// The exact slab test in long double on the T inputs: the entry and exit of
// the exact ray (parallel axes handled by inclusion of the origin).
template <class T>
struct exact_box {
    bool crosses = false;
    wide entry = 0, exit = 0;
};

template <class T>
exact_box<T> exact_slabs(const aabb<T>& box, const ray<T>& r, const interval<T>& range) {
    wide entry = range.min, exit = range.max;
    for (int k = 0; k < 3; ++k) {
        const wide o = r.origin[k], d = r.direction[k], lo = box.lo[k], hi = box.hi[k];
        if (d == 0) {
            if (o < lo || o > hi) return {};
            continue;
        }
        wide a = (lo - o) / d, b = (hi - o) / d;
        if (a > b) std::swap(a, b);
        entry = std::max(entry, a);
        exit = std::min(exit, b);
    }
    return {entry <= exit, entry, exit};
}

template <class T>
std::optional<T> box_test(const aabb<T>& box, const ray<T>& r, const interval<T>& range) {
    return intersect_box(box, r, reciprocal(r.direction), range);
}

template <class T>
aabb<T> random_box(std::mt19937_64& rng, double size) {
    aabb<T> b;
    b.grow(random_point<T>(rng, -size, size));
    b.grow(random_point<T>(rng, -size, size));
    return b;
}

template <class T>
T eps() {
    return std::numeric_limits<T>::epsilon();
}

// Compares the tree's closest hit with brute force on the given rays; true when all agree.
template <class T>
bool tree_equals_brute_force(const objects<T>& scene, const bvh<T>& tree, const std::vector<ray<T>>& rays,
                             const std::vector<interval<T>>& ranges) {
    const auto intersect = scene.intersector();
    bool all = true;
    for (size_t i = 0; i < rays.size(); ++i)
        all = same_answer(brute_force(scene, rays[i], ranges[i]), closest_hit(tree, intersect, rays[i], ranges[i])) &&
              all;
    return all;
}

// Random rays through a cube, some restricted to a finite range, some with a positive tmin.
template <class T>
void random_rays(std::mt19937_64& rng, int n, double size, std::vector<ray<T>>& rays, std::vector<interval<T>>& ranges) {
    std::uniform_real_distribution<double> u(0, 1);
    for (int i = 0; i < n; ++i) {
        rays.push_back(random_ray<T>(rng, size));
        interval<T> range{T(0), infinity<T>};
        if (i % 3 == 1) range.max = T(0.2 + u(rng));
        if (i % 5 == 2) range.min = T(0.3 * u(rng));
        ranges.push_back(range);
    }
}

template <class T>
objects<T> clustered(std::mt19937_64& rng, int clusters, int per_cluster) {
    objects<T> scene;
    std::normal_distribution<double> spread(0, 0.5);
    for (int c = 0; c < clusters; ++c) {
        const vec3d centre = convert<double>(random_point<T>(rng, -30, 30));
        for (int i = 0; i < per_cluster; ++i) {
            const vec3d p = centre + vec3d(spread(rng), spread(rng), spread(rng));
            if (i % 2)
                scene.spheres.push_back({convert<T>(p), T(0.08)});
            else
                scene.triangles.push_back({convert<T>(p), convert<T>(p + vec3d(0.2, 0, 0)), convert<T>(p + vec3d(0, 0.2, 0.1))});
        }
    }
    for (int i = 0; i < 3; ++i) scene.spheres.push_back({random_point<T>(rng, -30, 30), T(4)});
    return scene;
}

}  // namespace

// ---------------------------------------------------------------- slab test

TEST_CASE_TEMPLATE("hidden: slab: the slab test hits crossed boxes, misses the others, enters at the right t", T,
                   RT_SCALARS) {
    std::mt19937_64 rng(0x8a11);
    bool crossed_hit = true, clear_miss = true, entry_right = true, never_nan = true;
    std::uniform_real_distribution<double> u(0, 1);
    for (int i = 0; i < 3000; ++i) {
        const aabb<T> box = random_box<T>(rng, 4);
        const ray<T> r{random_point<T>(rng, -6, 6), random_direction<T>(rng) * T(0.5 + 2 * u(rng))};
        interval<T> range{T(0), infinity<T>};
        if (i % 4 == 1) range = {T(-3), T(2 + 4 * u(rng))};
        if (i % 7 == 3) range.min = T(1.5 * u(rng));
        const exact_box<T> want = exact_slabs(box, r, range);
        const auto got = box_test(box, r, range);
        if (got && std::isnan(*got)) never_nan = false;
        if (want.crosses && !got) crossed_hit = false;
        // A clear miss: the exact exit comes before the entry by more than rounding can explain.
        const wide margin = 64 * wide(eps<T>()) * (std::fabs(want.entry) + std::fabs(want.exit) + 1);
        if (!want.crosses && want.entry - want.exit > margin && got) clear_miss = false;
        if (want.crosses && got) {
            const wide tol = 16 * wide(eps<T>()) * (std::fabs(want.entry) + 1);
            if (!(std::fabs(wide(*got) - want.entry) <= tol)) entry_right = false;
        }
    }
    CHECK_MESSAGE(crossed_hit, "a box the ray crosses inside the range was reported as missed");
    CHECK_MESSAGE(clear_miss, "a box the ray clearly misses (or outside the range) was reported as hit");
    CHECK_MESSAGE(entry_right, "the entry is the largest slab entry clamped to range.min");
    CHECK_MESSAGE(never_nan, "the slab test returned a NaN entry");
}

TEST_CASE_TEMPLATE("hidden: slab: zero and negative-zero direction components never make a crossed box look missed", T,
                   RT_SCALARS) {
    const aabb<T> box{{T(-1.5), T(0.25), T(2)}, {T(0.75), T(3), T(2.5)}};
    const T zeros[] = {T(0), -T(0)};
    bool on_faces = true, inside = true, outside_missed = true, entry_ok = true;
    // Origins on every face plane, edge and corner (coordinates lo, hi or between),
    // rays travelling along one axis with the other two components +0 or -0.
    for (int axis = 0; axis < 3; ++axis)
        for (T z1 : zeros)
            for (T z2 : zeros)
                for (T sign : {T(1), T(-1)})
                    for (int a = 0; a < 3; ++a)
                        for (int b = 0; b < 3; ++b) {
                            const int k1 = (axis + 1) % 3, k2 = (axis + 2) % 3;
                            vec3<T> o{}, d{};
                            const T choices1[] = {box.lo[k1], box.hi[k1], (box.lo[k1] + box.hi[k1]) / 2};
                            const T choices2[] = {box.lo[k2], box.hi[k2], (box.lo[k2] + box.hi[k2]) / 2};
                            o[axis] = sign > 0 ? box.lo[axis] - T(2) : box.hi[axis] + T(2);
                            o[k1] = choices1[a];
                            o[k2] = choices2[b];
                            d[axis] = sign;
                            d[k1] = z1;
                            d[k2] = z2;
                            const ray<T> r{o, d};
                            const auto got = box_test(box, r, {T(0), infinity<T>});
                            if (!got) (a < 2 || b < 2 ? on_faces : inside) = false;
                            if (got && *got != T(2)) entry_ok = false;
                            // The same ray moved off the box along k1 misses.
                            vec3<T> off = o;
                            off[k1] = box.hi[k1] + T(0.5);
                            if (box_test(box, ray<T>{off, d}, {T(0), infinity<T>})) outside_missed = false;
                        }
    CHECK_MESSAGE(on_faces, "a ray lying in a face plane (direction component +0 or -0, origin on the face: 0 * inf "
                            "= NaN) is in the closed box and must be a hit");
    CHECK_MESSAGE(inside, "a ray parallel to two slabs and inside both crosses the box");
    CHECK_MESSAGE(outside_missed, "a ray parallel to a slab and outside it misses the box");
    CHECK_MESSAGE(entry_ok, "a parallel ray enters the box where it crosses the one slab it is not parallel to");
}

TEST_CASE_TEMPLATE("hidden: slab: edges, corners, flat boxes and point boxes are hit when touched", T, RT_SCALARS) {
    // Rays aimed at a corner, at the middle of a flat box, through a point
    // box. The origin is rounded, so the exact ray may pass a hair beside the
    // target: each case asks for a hit only when the exact ray (long double,
    // from the rounded inputs) touches the box; about half of the corner and
    // point rays do.
    std::mt19937_64 rng(0x8a12);
    bool corners = true, flats = true, points = true;
    int corner_cases = 0, point_cases = 0;
    const interval<T> ahead{T(0), infinity<T>};
    for (int i = 0; i < 600; ++i) {
        const aabb<T> box = random_box<T>(rng, 3);
        const vec3<T> corner{(i & 1) ? box.hi.x : box.lo.x, (i & 2) ? box.hi.y : box.lo.y,
                             (i & 4) ? box.hi.z : box.lo.z};
        const vec3<T> d{(i & 1) ? T(-1) : T(1), (i & 2) ? T(-0.5) : T(0.5), (i & 4) ? T(-0.25) : T(0.25)};
        const ray<T> at_corner{corner - T(4) * d, d};
        if (exact_slabs(box, at_corner, ahead).crosses) {
            ++corner_cases;
            if (!box_test(box, at_corner, ahead)) corners = false;
        }
        aabb<T> flat = box;
        const int k = i % 3;
        flat.hi[k] = flat.lo[k];
        const vec3<T> target = flat.centroid();
        const vec3<T> from = target + random_direction<T>(rng) * T(5);
        const ray<T> across{from, target - from};
        if (exact_slabs(flat, across, ahead).crosses && !box_test(flat, across, ahead)) flats = false;
        const aabb<T> point{corner, corner};
        const ray<T> through{corner - T(3) * random_direction<T>(rng), random_direction<T>(rng)};
        const ray<T> aimed{through.origin, corner - through.origin};
        if (exact_slabs(point, aimed, ahead).crosses) {
            ++point_cases;
            if (!box_test(point, aimed, ahead)) points = false;
        }
    }
    REQUIRE(corner_cases > 50);
    REQUIRE(point_cases > 10);
    CHECK_MESSAGE(corners, "a ray through a corner of the box touches it: a hit (compare entry <= exit, widened)");
    CHECK_MESSAGE(flats, "a flat box crossed through its inside is a hit (its slab is entered and left at one t)");
    CHECK_MESSAGE(points, "a ray through a point box is a hit");
}

TEST_CASE_TEMPLATE("hidden: slab: rays grazing the edge of a flat mesh find what brute force finds", T, RT_SCALARS) {
    // A flat mesh of two triangles at a height that is not exact in binary;
    // rays from far away aimed at its edge. Whenever the triangle test finds a
    // hit, the tree must too: an exit that is not widened loses some of them.
    const T height = T(-0.7), edge_x = T(-0.45);
    objects<T> mesh;
    mesh.triangles.push_back({{edge_x, height, T(-2)}, {edge_x, height, T(2)}, {T(1.55), height, T(2)}});
    mesh.triangles.push_back({{edge_x, height, T(-2)}, {T(1.55), height, T(2)}, {T(1.55), height, T(-2)}});
    const bvh<T> tree = build_median(mesh.boxes());
    const double spread = sizeof(T) == sizeof(float) ? 8e-5 : 3e-14;
    std::mt19937_64 rng(0x8a13);
    std::uniform_real_distribution<double> u(-1, 1);
    std::vector<ray<T>> rays;
    std::vector<interval<T>> ranges;
    for (int i = 0; i < 1500; ++i) {
        const vec3<T> from{T(-850.25 + 0.75 * i), T(410.5 - 0.125 * i), T(233.5 + 0.25 * i)};
        const vec3<T> target{T(edge_x + spread * u(rng)), height, T(1.8 * u(rng))};
        rays.push_back({from, target - from});
        ranges.push_back({T(0), infinity<T>});
    }
    CHECK_MESSAGE(tree_equals_brute_force(mesh, tree, rays, ranges),
                  "a ray that hits a triangle near the edge of a flat mesh was missed by the tree: rounding made "
                  "its flat box look missed (the exit must be widened)");
}

TEST_CASE_TEMPLATE("hidden: slab: a ray from a face that leaves the box touches it at t = 0 (closed rule)", T,
                   RT_SCALARS) {
    // The origin lies on a face and the ray points out of the box: the box is
    // touched at t = 0 = range.min, where the exit is exactly +0 or -0 (the
    // widened exit is then still 0): entry <= exit counts it, entry < exit does not.
    const aabb<T> box{{T(-1.5), T(0.25), T(2)}, {T(0.75), T(3), T(2.5)}};
    bool touched = true, entry_zero = true;
    for (int axis = 0; axis < 3; ++axis)
        for (int side = 0; side < 2; ++side) {
            vec3<T> o = box.centroid();
            o[axis] = side ? box.hi[axis] : box.lo[axis];
            vec3<T> d{T(0.25), T(-0.5), T(0.125)};
            d[axis] = side ? T(1) : T(-1);  // away from the box
            const auto got = box_test(box, ray<T>{o, d}, {T(0), infinity<T>});
            if (!got) touched = false;
            else if (!(*got == T(0))) entry_zero = false;
        }
    const aabb<T> flat{{T(-1), T(0.5), T(-1)}, {T(1), T(0.5), T(1)}};
    const auto on_flat = box_test(flat, ray<T>{{T(0.25), T(0.5), T(0)}, {T(0.5), T(1), T(0.25)}}, {T(0), infinity<T>});
    if (!on_flat) touched = false;
    CHECK_MESSAGE(touched, "a box is closed and so is the slab test's comparison: a ray that starts on a face is in "
                           "the box at t = range.min even when it leaves at once (entry <= exit, not <)");
    CHECK_MESSAGE(entry_zero, "a ray that starts on a face enters the box at range.min");
}

// ---------------------------------------------------------------- traversal

TEST_CASE_TEMPLATE("hidden: traversal: random spheres give brute force's answer bit for bit", T, RT_SCALARS) {
    std::mt19937_64 rng(0x8b01);
    objects<T> scene;
    add_random_spheres(scene, rng, 400, 12, 0.02, 1.2);
    std::vector<ray<T>> rays;
    std::vector<interval<T>> ranges;
    random_rays(rng, 500, 14, rays, ranges);
    CHECK_MESSAGE(tree_equals_brute_force(scene, build_median(scene.boxes()), rays, ranges),
                  "closest hit through a median-split tree differs from brute force on random spheres");
    build_options two;
    two.max_leaf_size = 2;
    CHECK_MESSAGE(tree_equals_brute_force(scene, build_sah_bounded(scene.boxes(), two), rays, ranges),
                  "closest hit through an SAH tree differs from brute force on random spheres");
}

TEST_CASE_TEMPLATE("hidden: traversal: random triangles give brute force's answer bit for bit", T, RT_SCALARS) {
    std::mt19937_64 rng(0x8b02);
    objects<T> scene;
    add_random_triangles(scene, rng, 500, 8, 2.5);
    std::vector<ray<T>> rays;
    std::vector<interval<T>> ranges;
    random_rays(rng, 500, 9, rays, ranges);
    CHECK_MESSAGE(tree_equals_brute_force(scene, build_median(scene.boxes()), rays, ranges),
                  "closest hit through a median-split tree differs from brute force on random triangles");
    CHECK_MESSAGE(tree_equals_brute_force(scene, build_sah_bounded(scene.boxes()), rays, ranges),
                  "closest hit through an SAH tree differs from brute force on random triangles");
}

TEST_CASE_TEMPLATE("hidden: traversal: mixed scenes with a planar mesh, axis rays and rays from inside boxes", T, RT_SCALARS) {
    std::mt19937_64 rng(0x8b03);
    objects<T> scene;
    add_random_spheres(scene, rng, 80, 2, 0.05, 0.4);
    add_planar_grid(scene, 12, T(0.375));
    add_random_triangles(scene, rng, 120, 2, 0.6);
    std::vector<ray<T>> rays;
    std::vector<interval<T>> ranges;
    random_rays(rng, 300, 2.5, rays, ranges);
    // Along the axes, both ways, with +0 and -0 in the other components, through
    // grid lines (shared edges) and from inside the scene's boxes.
    std::uniform_int_distribution<int> cell(-12, 12);
    for (int i = 0; i < 240; ++i) {
        const int axis = i % 3;
        const T zero = (i / 3) % 2 ? -T(0) : T(0);
        vec3<T> d{zero, zero, zero};
        d[axis] = (i / 6) % 2 ? T(1) : T(-1);
        const vec3<T> o{T(cell(rng)) / T(12), T(cell(rng)) / T(12) + T(0.375) * T(i % 2), T(cell(rng)) / T(24)};
        rays.push_back({o, d});
        ranges.push_back({T(0), infinity<T>});
    }
    const auto boxes = scene.boxes();
    CHECK_MESSAGE(tree_equals_brute_force(scene, build_median(boxes), rays, ranges),
                  "closest hit through a median-split tree differs from brute force on a mixed scene with a flat mesh "
                  "(axis rays, zero direction components, flat boxes, rays from inside)");
    build_options one;
    one.max_leaf_size = 1;
    CHECK_MESSAGE(tree_equals_brute_force(scene, build_sah_bounded(boxes, one), rays, ranges),
                  "closest hit through an SAH tree differs from brute force on a mixed scene with a flat mesh");
}

TEST_CASE_TEMPLATE("hidden: traversal: equal t goes to the lowest object index", T, RT_SCALARS) {
    std::mt19937_64 rng(0x8b04);
    objects<T> scene;
    // Copies of a few spheres scattered through the index range, and a flat
    // mesh whose shared edges are hit at equal t by two triangles.
    add_random_spheres(scene, rng, 30, 3, 0.2, 0.5);
    for (int i = 0; i < 30; ++i) scene.spheres.push_back(scene.spheres[size_t(i % 7)]);
    add_planar_grid(scene, 6, T(-2));
    std::vector<ray<T>> rays;
    std::vector<interval<T>> ranges;
    for (int i = 0; i < 7; ++i) {
        const sphere<T>& s = scene.spheres[size_t(i)];
        rays.push_back({s.center + vec3<T>(T(0.05), T(0.02), T(6)), {0, 0, -1}});
        rays.push_back({s.center + vec3<T>(T(-6), T(0.01), T(0)), {1, 0, 0}});
    }
    for (int i = -6; i <= 6; ++i)
        for (int j = -6; j <= 6; j += 3) rays.push_back({{T(i) / T(6), T(4), T(j) / T(6)}, {0, -1, 0}});
    ranges.assign(rays.size(), {T(0), infinity<T>});
    build_options one;
    one.max_leaf_size = 1;
    CHECK_MESSAGE(tree_equals_brute_force(scene, build_median(scene.boxes(), one), rays, ranges),
                  "when two objects are hit at exactly the same t, the lowest index must win (median-split tree)");
    CHECK_MESSAGE(tree_equals_brute_force(scene, build_sah_bounded(scene.boxes(), one), rays, ranges),
                  "when two objects are hit at exactly the same t, the lowest index must win (SAH tree)");
}

TEST_CASE_TEMPLATE("hidden: traversal: an empty scene and a single object", T, RT_SCALARS) {
    const objects<T> none;
    const ray<T> r{{0, 0, 0}, {0, 0, -1}};
    const bvh<T> empty_median = build_median(none.boxes());
    const bvh<T> empty_sah = build_sah_bounded(none.boxes());
    // A budget of no calls: the record of the calls says whether one was made.
    const auto everything = interval<T>{T(0), infinity<T>};
    const auto median_hit =
        rt::test::call_with_rules<T>([&] { return closest_hit(empty_median, none.intersector(0), r, everything); });
    const auto sah_hit =
        rt::test::call_with_rules<T>([&] { return closest_hit(empty_sah, none.intersector(0), r, everything); });
    const auto any = rt::test::call_with_rules<T>([&] { return any_hit(empty_sah, none.intersector(0), r, everything); });
    const bool empty_miss = !median_hit.answer && !sah_hit.answer && !any.answer;
    const bool none_asked = !median_hit.broken && !sah_hit.broken && !any.broken;
    CHECK_MESSAGE(empty_miss, "an empty tree is a miss");
    CHECK_MESSAGE(none_asked, "an empty tree never calls intersect");
    CHECK_MESSAGE((empty_sah.nodes.empty() && empty_sah.order.empty()), "the SAH build of no objects is an empty tree");

    objects<T> one;
    one.triangles.push_back({{-1, -1, -3}, {1, -1, -3}, {0, 1, -3}});
    std::vector<ray<T>> rays = {{{0, 0, 0}, {0, 0, -1}}, {{5, 0, 0}, {0, 0, -1}}, {{0, 0, -5}, {0, 0, 1}},
                                {{0, 0, 0}, {0, 0, 1}}};
    std::vector<interval<T>> ranges = {{T(0), infinity<T>}, {T(0), infinity<T>}, {T(0), infinity<T>},
                                       {T(0), infinity<T>}};
    rays.push_back({{0, 0, 0}, {0, 0, -1}});
    ranges.push_back({T(0), T(3)});  // the hit is exactly at tmax: not inside the open range
    CHECK_MESSAGE(tree_equals_brute_force(one, build_median(one.boxes()), rays, ranges),
                  "a tree of one object answers exactly as brute force, the open range included");
    CHECK_MESSAGE(tree_equals_brute_force(one, build_sah_bounded(one.boxes()), rays, ranges),
                  "an SAH tree of one object answers exactly as brute force");
}

TEST_CASE_TEMPLATE("hidden: traversal: leaves holding many objects", T, RT_SCALARS) {
    std::mt19937_64 rng(0x8b05);
    objects<T> scene;
    add_random_spheres(scene, rng, 150, 5, 0.1, 0.9);
    add_random_triangles(scene, rng, 150, 5, 1.5);
    std::vector<ray<T>> rays;
    std::vector<interval<T>> ranges;
    random_rays(rng, 300, 6, rays, ranges);
    bool same = true, valid = true;
    for (int leaf : {16, 64, 1000}) {
        build_options big;
        big.max_leaf_size = leaf;
        const auto boxes = scene.boxes();
        const bvh<T> sah_tree = build_sah_bounded(boxes, big);
        valid = tree_problem(sah_tree, boxes, leaf).empty() && valid;
        same = tree_equals_brute_force(scene, build_median(boxes, big), rays, ranges) && same;
        same = tree_equals_brute_force(scene, sah_tree, rays, ranges) && same;
    }
    CHECK_MESSAGE(valid, "an SAH tree with a large max_leaf_size is not a valid tree");
    CHECK_MESSAGE(same, "a tree whose leaves hold many objects differs from brute force (every object of a leaf "
                        "must be asked, and the nearest kept)");
}

TEST_CASE_TEMPLATE("hidden: traversal: nearer children first, and boxes beyond the closest hit are skipped", T, RT_SCALARS) {
    // A row of 64 spheres, one per leaf, and rays along the row: nearest first
    // with pruning asks a handful of objects; visiting the far side first, or
    // never skipping boxes beyond the closest hit, asks all of them.
    objects<T> scene;
    for (int i = 0; i < 64; ++i) scene.spheres.push_back({{T(0.01 * i), 0, T(-2.5 * i - 3)}, T(1)});
    build_options one;
    one.max_leaf_size = 1;
    bool few = true, right = true;
    for (const bvh<T>& tree : {build_median(scene.boxes(), one), build_sah_bounded(scene.boxes(), one)})
        for (T dir : {T(-1), T(1)}) {
            const ray<T> r{{T(0.3), T(0.1), dir < 0 ? T(0) : T(-170)}, {0, 0, dir}};
            // A 7th ask breaks the test's budget: the record of the asks keeps it.
            const auto got = rt::test::call_with_rules<T>(
                [&] { return closest_hit(tree, scene.intersector(6), r, {T(0), infinity<T>}); });
            if (got.broken) few = false;
            else right = same_answer(got.answer, brute_force(scene, r, {T(0), infinity<T>})) && right;
        }
    CHECK_MESSAGE(right, "along a row of spheres the nearest one is the answer");
    CHECK_MESSAGE(few, "the traversal asked far more objects than needed: visit the nearer child first, and skip a "
                       "node whose entry lies beyond the closest hit found so far");
}

TEST_CASE_TEMPLATE("hidden: traversal: the nearer child is visited first", T, RT_SCALARS) {
    // A row of spheres along the ray, one per leaf, boxes apart: nearest
    // child first, the first object asked is the nearest one. Checked from
    // the record of the calls the test answered.
    objects<T> scene;
    for (int i = 0; i < 32; ++i) scene.spheres.push_back({{T(0.01 * i), 0, T(-2.5 * i - 3)}, T(1)});
    build_options one;
    one.max_leaf_size = 1;
    const bvh<T> tree = build_median(scene.boxes(), one);
    bool nearest_first = true;
    for (T dir : {T(-1), T(1)}) {
        const ray<T> r{{T(0.3), T(0.1), dir < 0 ? T(0) : T(-90)}, {0, 0, dir}};
        const call_record<T> record = std::make_shared<std::vector<asked<T>>>();
        (void)closest_hit(tree, recording_intersector(scene, record), r, {T(0), infinity<T>});
        const int nearest = dir < 0 ? 0 : 31;
        if (record->empty() || record->front().object != nearest) nearest_first = false;
    }
    CHECK_MESSAGE(nearest_first, "of two children, the one the ray enters first must be visited first (push the "
                                 "farther child first, so the nearer one is popped first)");
}

TEST_CASE_TEMPLATE("hidden: traversal: the range shrinks to the closest hit so far", T, RT_SCALARS) {
    // After a hit at t, every object is asked only up to t (the next number
    // above it): checked from the record of the calls, and on a scene where
    // a farther object of lower index, asked about the whole range, would
    // replace the nearer hit.
    objects<T> pair;
    pair.triangles.push_back({{-1, -1, T(-4.9)}, {1, -1, T(-4.9)}, {0, 1, T(-11.1)}});  // box entered at 4.9, hit near 8
    pair.triangles.push_back({{-1, -1, T(-4.8)}, {1, -1, T(-4.8)}, {0, 1, T(-5.2)}});   // box entered at 4.8, hit at 5
    std::mt19937_64 rng(0x8b07);
    objects<T> cloud;
    add_random_spheres(cloud, rng, 120, 4, 0.1, 0.8);
    add_random_triangles(cloud, rng, 80, 4, 1.5);
    build_options one;
    one.max_leaf_size = 1;
    bool shrunk = true, right = true;
    const auto check = [&](const objects<T>& scene, const bvh<T>& tree, const ray<T>& r) {
        const call_record<T> record = std::make_shared<std::vector<asked<T>>>();
        const auto got = closest_hit(tree, recording_intersector(scene, record), r, {T(0), infinity<T>});
        right = same_answer(got, brute_force(scene, r, {T(0), infinity<T>})) && right;
        std::optional<T> best;
        for (const asked<T>& a : *record) {
            if (best && a.range.max > std::nextafter(*best, infinity<T>)) shrunk = false;
            if (a.answer && (!best || a.answer->t < *best)) best = a.answer->t;
        }
    };
    check(pair, build_median(pair.boxes(), one), ray<T>{{0, 0, 0}, {0, 0, -1}});
    const bvh<T> cloud_tree = build_median(cloud.boxes());
    for (int i = 0; i < 200; ++i) check(cloud, cloud_tree, random_ray<T>(rng, 5));
    CHECK_MESSAGE(shrunk, "after a hit, objects must be asked only up to the closest t found so far (range.max "
                          "shrinks to it): a farther hit must never be able to replace a nearer one");
    CHECK_MESSAGE(right, "with the range shrunk to the closest hit, the answer is brute force's");
}

TEST_CASE_TEMPLATE("hidden: traversal: a waiting node is re-checked with the widened comparison", T, RT_SCALARS) {
    // A flat mesh, one triangle per leaf, hit straight down through its
    // shared edges and corners along directions that are not powers of two:
    // the slab test's entry (h - o) * (1 / d) and the triangle's own t round
    // differently, so a triangle's t can lie a rounding below the entry of
    // the box that holds it. Two triangles sharing an edge are hit at equal
    // t, and the lower index must win even when its leaf waits on the stack:
    // it may only be skipped when its entry lies beyond widen_exit(best t).
    bool same = true;
    for (const T height : {T(0.3), T(-0.7), T(0.1)})
        for (const bool reversed : {false, true}) {
            objects<T> mesh;
            add_planar_grid(mesh, 8, height);
            if (reversed) std::reverse(mesh.triangles.begin(), mesh.triangles.end());
            build_options one;
            one.max_leaf_size = 1;
            const bvh<T> tree = build_median(mesh.boxes(), one);
            std::vector<ray<T>> rays;
            for (int i = -8; i <= 8; ++i)
                for (int j = -8; j <= 8; ++j)
                    for (const T down : {T(3), T(0.7), T(1.3), T(5.5)})
                        rays.push_back({{T(i) / T(8), T(2), T(j) / T(8)}, {0, -down, 0}});
            const std::vector<interval<T>> ranges(rays.size(), {T(0), infinity<T>});
            same = tree_equals_brute_force(mesh, tree, rays, ranges) && same;
        }
    CHECK_MESSAGE(same, "a node waiting on the stack was skipped although it held the answer: compare its entry "
                        "with widen_exit(best t), the very comparison intersect_box makes, not with best t itself");
}

TEST_CASE_TEMPLATE("hidden: traversal: any_hit agrees with closest_hit on whether something is hit", T, RT_SCALARS) {
    std::mt19937_64 rng(0x8b06);
    objects<T> scene;
    add_random_spheres(scene, rng, 120, 8, 0.1, 1.0);
    add_random_triangles(scene, rng, 120, 8, 2.0);
    add_planar_grid(scene, 4, T(0.5));
    const auto intersect = scene.intersector();
    bool agree = true;
    std::uniform_real_distribution<double> u(0, 1);
    for (const bvh<T>& tree : {build_median(scene.boxes()), build_sah_bounded(scene.boxes())})
        for (int i = 0; i < 400; ++i) {
            const ray<T> r = random_ray<T>(rng, 9);
            const interval<T> range{T(0.1 * u(rng)), i % 2 ? infinity<T> : T(0.05 + u(rng))};
            agree = (any_hit(tree, intersect, r, range) == closest_hit(tree, intersect, r, range).has_value()) &&
                    agree;
        }
    CHECK_MESSAGE(agree, "any_hit must be true exactly when something is hit inside the open range");
}

TEST_CASE_TEMPLATE("hidden: traversal: any_hit stops at the first hit it finds", T, RT_SCALARS) {
    // 40 big spheres around the ray's origin, one per leaf: every one is hit,
    // and every box contains the origin. "Is anything hit?" is answered by the
    // first object asked that is hit; a search that goes on for the nearest
    // asks all of them. Counted from the record of the calls the test answered.
    objects<T> scene;
    std::mt19937_64 rng(0x8b09);
    for (int i = 0; i < 40; ++i) scene.spheres.push_back({random_point<T>(rng, -0.5, 0.5), T(2 + 0.05 * i)});
    build_options one;
    one.max_leaf_size = 1;
    bool stops = true, says_hit = true;
    for (const bvh<T>& tree : {build_median(scene.boxes(), one), build_median(scene.boxes())})
        for (int i = 0; i < 20; ++i) {
            const ray<T> r{vec3<T>(0), random_direction<T>(rng)};
            const call_record<T> record = std::make_shared<std::vector<asked<T>>>();
            if (!any_hit(tree, recording_intersector(scene, record), r, {T(0), infinity<T>})) says_hit = false;
            int hits = 0;
            for (const asked<T>& a : *record) hits += a.answer.has_value();
            if (hits > 1) stops = false;
        }
    CHECK_MESSAGE(says_hit, "a ray from inside spheres hits them: any_hit is true");
    CHECK_MESSAGE(stops, "any_hit went on asking objects after one was hit: a shadow ray only asks whether "
                         "something blocks the light, so return true at the first hit");
}

// ---------------------------------------------------------------- SAH build

TEST_CASE_TEMPLATE("hidden: sah: the SAH tree holds every object exactly once with exact boxes", T, RT_SCALARS) {
    std::mt19937_64 rng(0x8c01);
    bool valid = true;
    for (int round = 0; round < 6; ++round) {
        objects<T> scene;
        add_random_spheres(scene, rng, 50 + 97 * round, 10, 0.01, 2.0);
        add_random_triangles(scene, rng, 30 * round, 10, 3.0);
        if (round == 2) add_planar_grid(scene, 9, T(0));  // flat boxes, centres in one plane
        if (round == 3)
            for (int i = 0; i < 25; ++i) scene.spheres.push_back({{1, 1, 1}, T(0.5)});  // coincident centres
        const auto boxes = scene.boxes();
        for (int leaf : {1, 3, 8}) {
            build_options options;
            options.max_leaf_size = leaf;
            options.bins = 4 + 5 * round;
            valid = tree_problem(build_sah_bounded(boxes, options), boxes, leaf).empty() && valid;
        }
    }
    objects<T> flat;
    add_planar_grid(flat, 10, T(2));
    valid = tree_problem(build_sah_bounded(flat.boxes()), flat.boxes(), build_options{}.max_leaf_size).empty() && valid;
    CHECK_MESSAGE(valid, "an SAH tree must hold every object exactly once, each node's box exactly the union of "
                         "the boxes below it, and no leaf larger than max_leaf_size");
}

TEST_CASE_TEMPLATE("hidden: sah: the SAH tree is cheaper than the median tree on clustered scenes", T, RT_SCALARS) {
    std::mt19937_64 rng(0x8c02);
    bool cheaper = true;
    for (int round = 0; round < 3; ++round) {
        const objects<T> scene = clustered<T>(rng, 3 + round, 40);
        const auto boxes = scene.boxes();
        const T median = sah_cost(build_median(boxes));
        const T sah = sah_cost(build_sah_bounded(boxes));
        if (!(sah < T(0.8) * median)) cheaper = false;
    }
    CHECK_MESSAGE(cheaper, "on clustered scenes the SAH tree's expected cost must be clearly below the median "
                           "split's: choose each split by the surface area heuristic over all axes and bins");
}

TEST_CASE_TEMPLATE("hidden: sah: splits are scored by surface area, flat scenes included", T, RT_SCALARS) {
    // A planar mesh: every box is flat (volume 0) but has an area, and the
    // surface area heuristic still tells good splits from bad ones there.
    bool cheaper = true;
    for (int round = 0; round < 3; ++round) {
        objects<T> grid;
        add_planar_grid(grid, 10 + 4 * round, T(0.5));
        const auto boxes = grid.boxes();
        const T median = sah_cost(build_median(boxes));
        const T sah = sah_cost(build_sah_bounded(boxes));
        if (!(sah < T(0.8) * median)) cheaper = false;
    }
    CHECK_MESSAGE(cheaper, "on a flat mesh the SAH tree's expected cost must be clearly below the median split's: a "
                           "split's cost uses the boxes' surface areas (aabb::half_area), which a flat box has");
}
