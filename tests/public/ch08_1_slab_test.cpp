// Public tests for chapter 08, exercise 1: the robust slab test (aabb.hpp).
//
// Most boxes here are the box [1, 2] x [1, 2] x [1, 2] or a flat or point
// box; every input is exactly representable, so each expected entry is exact.
#include "08-acceleration/aabb.hpp"

#include "test_support.hpp"

#include <cmath>
#include <limits>
#include <random>

using namespace rt;
using rt::ch08::aabb;
using rt::ch08::intersect_box;
using rt::ch08::reciprocal;
using rt::test::describe;

namespace {

template <class T>
aabb<T> unit_box_at_one() {
    return {{1, 1, 1}, {2, 2, 2}};
}

template <class T>
std::optional<T> box_test(const aabb<T>& box, const ray<T>& r, interval<T> range = {T(0), infinity<T>}) {
    return intersect_box(box, r, reciprocal(r.direction), range);
}

}  // namespace

TEST_CASE_TEMPLATE("slab: a ray through a box enters it at the largest of the three slab entries", T, RT_SCALARS) {
    // From the origin along (1, 1, 1): each slab is entered at t = 1.
    auto diagonal = box_test(unit_box_at_one<T>(), ray<T>{{0, 0, 0}, {1, 1, 1}});
    REQUIRE_MESSAGE(diagonal.has_value(), "the ray from the origin along (1, 1, 1) goes through the box [1, 2]^3");
    CHECK_MESSAGE(*diagonal == T(1), "it enters every slab at t = 1, so the box at t = 1; got " << describe(diagonal));

    // Along (2, 1, 1): the x slab is entered at t = 0.5, y and z at t = 1: the box at t = 1.
    auto slanted = box_test(unit_box_at_one<T>(), ray<T>{{0, 0, 0}, {2, T(1.5), T(1.5)}});
    REQUIRE_MESSAGE(slanted.has_value(), "the ray from the origin along (2, 1.5, 1.5) passes (1.33, 1, 1) and "
                                         "(2, 1.5, 1.5): it crosses the box");
    CHECK_MESSAGE(*slanted == T(2) / T(3),
                  "slab entries are x: 1/2, y: 2/3, z: 2/3; the box is entered when the ray is inside ALL three "
                  "slabs, at the LARGEST entry, t = 2/3; got "
                      << describe(slanted));
}

TEST_CASE_TEMPLATE("slab: a ray that passes beside a box misses it", T, RT_SCALARS) {
    // Along (1, 1, 0) from (0, -1.5, 1.5): in the x slab for t in [1, 2], in the y slab for t in [2.5, 3.5].
    auto beside = box_test(unit_box_at_one<T>(), ray<T>{{0, T(-1.5), T(1.5)}, {1, 1, 0}});
    CHECK_MESSAGE(!beside.has_value(),
                  "this ray is in the x slab for t in [1, 2] and in the y slab for t in [2.5, 3.5]: never in both "
                  "at once, so it passes beside the box. A hit means the test did not compare the largest entry "
                  "with the smallest exit; got "
                      << describe(beside));
    auto above = box_test(unit_box_at_one<T>(), ray<T>{{0, 3, T(1.5)}, {1, 0, 0}});
    CHECK_MESSAGE(!above.has_value(), "a ray along +x at height y = 3 passes above the box [1, 2]^3; got "
                                          << describe(above));
}

TEST_CASE_TEMPLATE("slab: a box behind the ray or beyond the range is missed, one the ray starts in is entered at tmin",
                   T, RT_SCALARS) {
    const aabb<T> box = unit_box_at_one<T>();
    auto behind = box_test(box, ray<T>{{3, T(1.5), T(1.5)}, {1, 0, 0}});
    CHECK_MESSAGE(!behind.has_value(), "the box lies behind this ray (t in [-2, -1]) and the range is (0, inf): a miss; got "
                                           << describe(behind));
    auto too_far = box_test(box, ray<T>{{0, T(1.5), T(1.5)}, {1, 0, 0}}, {T(0), T(0.5)});
    CHECK_MESSAGE(!too_far.has_value(),
                  "the box is entered at t = 1, beyond range.max = 0.5: a miss (the traversal uses this to skip "
                  "boxes beyond the closest hit so far); got "
                      << describe(too_far));
    auto inside = box_test(box, ray<T>{{T(1.5), T(1.5), T(1.5)}, {1, T(0.25), T(-0.5)}}, {T(0.125), infinity<T>});
    REQUIRE_MESSAGE(inside.has_value(), "a ray that starts inside a box is in it: a hit");
    CHECK_MESSAGE(*inside == T(0.125), "a ray that starts inside the box is in it from range.min = 0.125 on, so the "
                                       "entry is range.min, not a negative slab entry; got "
                                           << describe(inside));
}

TEST_CASE_TEMPLATE("slab: zero and negative zero direction components: parallel rays, and no NaN", T, RT_SCALARS) {
    const aabb<T> box = unit_box_at_one<T>();
    const T zero = T(0), minus_zero = -T(0);
    for (T z : {zero, minus_zero}) {
        // Parallel to the y and z slabs, inside them: only the x slab decides.
        auto through = box_test(box, ray<T>{{0, T(1.5), T(1.5)}, {1, z, z}});
        REQUIRE_MESSAGE(through.has_value(), "a ray along +x at y = z = 1.5 (direction y and z components "
                                                 << (std::signbit(z) ? "-0" : "+0")
                                                 << ") crosses the box. 1 / 0 is infinite; that is fine here");
        CHECK_MESSAGE(*through == T(1), "it enters at the x = 1 face, t = 1; got " << describe(through));
        auto outside = box_test(box, ray<T>{{0, 3, T(1.5)}, {1, z, z}});
        CHECK_MESSAGE(!outside.has_value(), "a ray parallel to the y slab but at y = 3, outside it, misses");
    }

    // On a face plane: (1 - 1) * (1 / 0) = 0 * inf = NaN. The ray travels
    // along one axis (entering at that axis' face, t = 1) and lies in a face
    // plane of another slab; the NaN comes from the first, the middle or the
    // last axis the loop looks at, so it cannot be washed out by a later one.
    const char* axis_name = "xyz";
    for (int travel = 0; travel < 3; ++travel)
        for (int lying = 0; lying < 3; ++lying) {
            if (lying == travel) continue;
            for (T z : {zero, minus_zero})
                for (T face : {T(1), T(2)}) {
                    vec3<T> o{T(1.5), T(1.5), T(1.5)}, d{z, z, z};
                    o[travel] = 0;
                    d[travel] = 1;
                    o[lying] = face;
                    const auto on_face = box_test(box, ray<T>{o, d});
                    const std::string where = std::string("the ray from ") + rt::test::describe(o) + " along " +
                                              rt::test::describe(d) + " lies in the plane " + axis_name[lying] +
                                              " = " + std::to_string(int(face)) + " of a face of the box (its " +
                                              axis_name[lying] + " direction component is " +
                                              (std::signbit(z) ? "-0" : "+0") + ")";
                    REQUIRE_MESSAGE(on_face.has_value(),
                                    where << ": the box is closed, so it is a hit. Here (face - origin) * (1 / d) = "
                                             "0 * inf = NaN, and a NaN must change nothing: write entry = (t > "
                                             "entry ? t : entry) and exit = (t < exit ? t : exit), whose "
                                             "comparisons are false for NaN and keep the old value, and pick the "
                                             "near plane with std::signbit so -0 counts as negative. std::min and "
                                             "std::max let the NaN through when it is their first argument. Got "
                                                 << describe(on_face));
                    CHECK_MESSAGE(*on_face == T(1),
                                  where << ": it enters the box at the " << std::string(1, axis_name[travel])
                                        << " = 1 face, t = 1; got " << describe(on_face)
                                        << ". A NaN entry or exit (0 * inf) was let into the comparisons: std::max "
                                           "and std::min pass a NaN through when it is their first argument, and "
                                           "a later axis then replaces it with its own value. Keep the old value "
                                           "on a NaN: entry = (t > entry ? t : entry)");
                }
        }
}

TEST_CASE_TEMPLATE("slab: rays that touch an edge or a corner of a box hit it", T, RT_SCALARS) {
    const aabb<T> box = unit_box_at_one<T>();
    // Through the corner (2, 2, 2) only: from (3, 3, 1) along (-1, -1, 1).
    auto corner = box_test(box, ray<T>{{3, 3, 1}, {-1, -1, 1}});
    REQUIRE_MESSAGE(corner.has_value(), "the ray from (3, 3, 1) along (-1, -1, 1) touches the box in its corner "
                                        "(2, 2, 2) at t = 1 and nowhere else: a touch is a hit (the box is closed, "
                                        "entry <= exit, not <)");
    CHECK_MESSAGE(*corner == T(1), "the corner is reached at t = 1; got " << describe(corner));
    // Along the edge y = 2, z = 1, x in [1, 2].
    auto edge = box_test(box, ray<T>{{0, 2, 1}, {1, 0, 0}});
    REQUIRE_MESSAGE(edge.has_value(), "a ray running along an edge of the box (y = 2, z = 1) is in the box");
    CHECK_MESSAGE(*edge == T(1), "it reaches the edge at x = 1, t = 1; got " << describe(edge));
}

TEST_CASE_TEMPLATE("slab: flat boxes and point boxes are hit", T, RT_SCALARS) {
    // The box of a planar mesh at height y = 0.5.
    const aabb<T> flat{{-1, T(0.5), -1}, {1, T(0.5), 1}};
    auto across = box_test(flat, ray<T>{{T(0.25), 2, T(-0.25)}, {T(0.125), -1, T(0.25)}});
    REQUIRE_MESSAGE(across.has_value(), "a ray crossing the flat box y = 0.5 inside its square must hit it: its "
                                        "y slab is entered and left at the same t, which must count (<=, not <)");
    CHECK_MESSAGE(*across == T(1.5), "it crosses y = 0.5 at t = 1.5; got " << describe(across));
    auto in_plane = box_test(flat, ray<T>{{-2, T(0.5), 0}, {1, 0, 0}});
    CHECK_MESSAGE(in_plane.has_value(), "a ray lying in the plane of a flat box and crossing it is in the box");

    const aabb<T> point{{1, 2, 3}, {1, 2, 3}};
    auto at_point = box_test(point, ray<T>{{0, 0, 0}, {1, 2, 3}});
    REQUIRE_MESSAGE(at_point.has_value(), "the ray from the origin along (1, 2, 3) passes the point box (1, 2, 3)");
    CHECK_MESSAGE(*at_point == T(1), "it reaches the point at t = 1; got " << describe(at_point));
    auto past_point = box_test(point, ray<T>{{0, 0, 0}, {1, 2, T(3.25)}});
    CHECK_MESSAGE(!past_point.has_value(), "a ray that passes a point box at a distance misses it");
}

TEST_CASE_TEMPLATE("slab: the exit is widened: a box the ray crosses is never missed through rounding", T, RT_SCALARS) {
    // The flat box of a triangle at height y = 0.1 (not exact in binary: it is
    // rounded to T), and rays from about 700 units away aimed at its x = 0.3
    // edge, crossing the plane a hair inside or outside the edge. The box is
    // flat, so the y slab is entered and left at the same t; the x slab's
    // entry, rounded up, can come out after it, and the box looks missed
    // although the exact ray crosses it. Only rays whose exact crossing point
    // (computed in long double from the very rounded inputs) lies in the box
    // are kept; each must be a hit.
    const T height = T(0.1), edge = T(0.3);
    const aabb<T> flat{{edge, height, -1}, {1, height, 1}};
    const double aim_spread = sizeof(T) == sizeof(float) ? 5e-5 : 2e-14;  // about the rounding of the direction
    std::mt19937_64 rng(8008);
    std::uniform_real_distribution<double> offset(-1, 1);
    int missed = 0, crossing = 0;
    for (int i = 0; i < 1000; ++i) {
        const vec3<T> from{T(-699.5 + i), T(123.25), T(340.5 - i)};
        const vec3<T> target{T(edge + aim_spread * offset(rng)), height, T(-0.9 + (i % 200) * 0.009)};
        const ray<T> r{from, target - from};
        using wide = long double;
        const wide t = (wide(height) - wide(from.y)) / wide(r.direction.y);
        const wide x = wide(from.x) + t * wide(r.direction.x), z = wide(from.z) + t * wide(r.direction.z);
        if (!(x >= wide(edge) && x <= 1 && z >= -1 && z <= 1)) continue;
        ++crossing;
        if (!box_test(flat, r)) ++missed;
    }
    REQUIRE(crossing > 300);
    CHECK_MESSAGE(missed == 0, missed << " of " << crossing
                                      << " rays that cross this flat box (exactly, from their rounded inputs) were "
                                         "reported as misses. Each slab parameter (p - o) * (1/d) is rounded three "
                                         "times: widen the exit outwards by 4 epsilons of its magnitude "
                                         "(widen_exit) before comparing it with the entry");
}
