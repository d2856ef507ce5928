// fast_path.cpp — the specialised renderer.
//
// Layout. Objects are stored as structure-of-arrays: all sphere centres'
// x in one array, all y in the next, and so on. Rays go in packets of
// eight neighbouring pixels of one row, also as arrays. The hot loop takes
// one object and tests it against the eight rays: the same arithmetic on
// eight independent lanes, which the compiler turns into vector
// instructions (AVX2: one instruction for eight floats or four doubles).
// Each lane keeps its own closest t and object with a select instead of a
// branch, so there is nothing to stop the vectoriser.
//
// Specialisation. Every loop the scene does not need is removed at compile
// time: the kernels are templates on the scalar type, the sphere
// formulation (none, plain, robust), whether there are planes, triangles
// and lights, and whether all rays of a packet share their origin (a
// pinhole camera's primary rays do, so terms that depend only on the origin
// and the object move out of the lane loop). dispatch() picks the one
// instantiation the plan asks for.
//
// Misses. Each lane function returns the hit's t, or +infinity for a miss;
// "t < closest so far" is false for infinity and for NaN, so neither a miss
// nor a NaN can ever be taken as a hit.
//
// Conditions are combined with & rather than &&: && may skip the second
// comparison, which is a branch, and a loop with branches is not
// vectorised. With & every comparison is computed in every lane and the
// answer is one select.
#include "fast_path.hpp"

#include "bvh_build.hpp"
#include "look.hpp"

#include "common/timing.hpp"
#include "common/scene.hpp"   // material_at: the checker pattern
#include "06-shading/shading.hpp"   // chapter 06's shade(), for lit scenes

#include "common/render.hpp"
#include "fast_path_kernels.hpp"  // the plane and triangle kernels

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <functional>
#include <limits>
#include <string>
#include <type_traits>

// Run-time dispatch. This file is compiled three times (tools/render/
// CMakeLists.txt): plain x86-64, AVX2 + FMA, and AVX-512, each time in its
// own namespace (RT_FAST_ISA), and fast_path_dispatch.cpp picks one at
// start-up from what the CPU has. The instruction set is switched on here,
// *after* every header, with a pragma rather than with -mavx2 on the
// command line: the headers' inline functions (std::vector, glm, ...) are
// then compiled for plain x86-64 in every copy, so whichever copy the
// linker keeps is safe on any CPU; only this file's own kernels (templates
// in an anonymous namespace, private to each copy) use the wide units.
// Contraction is off for the whole project and FMA appears only where the
// code writes std::fma (exactly rounded on every path, in hardware or not),
// so all three copies give the same bits.
#ifndef RT_FAST_ISA
#define RT_FAST_ISA isa_baseline
#endif
#if defined(RT_FAST_AVX512)
#pragma GCC target("avx512f,avx512vl,avx512bw,avx512dq,avx2,fma,bmi,bmi2,lzcnt,popcnt")
#elif defined(RT_FAST_AVX2)
#pragma GCC target("avx2,fma,bmi,bmi2,lzcnt,popcnt")
#endif

namespace rt::render_tool::RT_FAST_ISA {

namespace {

constexpr int W = packet_width;
constexpr int tile_w = 8, tile_h = W / tile_w;  // the pixels of one packet
static_assert(tile_w * tile_h == W, "a packet is a whole tile");

enum class sphere_mode { none, plain, robust };

// A tree's leaf holds at most 8 objects (build_bvh's max_leaf); one ray
// tests them as one group of 8 lanes (a vector of 8 floats), like a shadow
// ray tests brute force's groups.
constexpr int leaf_lanes = 8;

// Object numbers in the same width as T, so a select on (t, object) pairs
// stays within one kind of vector lane.
template <class T>
using index_t = std::conditional_t<sizeof(T) == 4, std::int32_t, std::int64_t>;

template <class T>
struct packet {
    alignas(64) T ox[W], oy[W], oz[W], dx[W], dy[W], dz[W];
};

template <class T>
struct soa_scene {
    size_t sphere_count = 0, plane_count = 0, triangle_count = 0;
    // Each array is padded to a multiple of W with NaN entries, which never
    // hit, so the shadow-ray loop can run over whole groups of W objects.
    std::vector<T> cx, cy, cz, radius, radius2;
    std::vector<T> px, py, pz, nx, ny, nz;  // planes: a point and the unit normal
    std::vector<T> ax, ay, az, e1x, e1y, e1z, e2x, e2y, e2z;  // triangles: corner a, edges b-a, c-a
    std::vector<T> bx, by, bz, br2;  // a sphere around each triangle (radius squared), to skip it cheaply

    // With a tree, spheres and triangles are stored in the trees' leaf
    // order, so a leaf is a contiguous range of the arrays; original[i] is
    // then the scene's own number of object i.
    bool tree = false;
    //
    // Spheres and triangles get different trees, each the faster of the two
    // on rt-bench's scenes (tools/bench/README.md): spheres a binary tree
    // walked by a whole packet (traverse_packet: at a million random spheres
    // it is still faster than one ray at a time through the wide tree),
    // triangles the 4-wide tree walked one ray at a time (traverse_wide: on
    // the million-triangle tetrahedron most packets straddle a silhouette,
    // and single rays are three times faster there).
    bvh_tree sphere_tree;
    bvh_wide_tree triangle_tree;
    std::vector<std::int64_t> original;
    // The scene's triangles and planes, for the rare exact decisions
    // (corners and plane_normal below).
    const std::vector<triangle<double>>* source_triangles = nullptr;
    const std::vector<plane<double>>* source_planes = nullptr;

    // Plane i's normal as the scene gives it, rounded to T (nx, ny, nz are
    // the normalised one): plane_t_exact decides "parallel" on it.
    vec3<T> plane_normal(size_t i) const { return convert<T>((*source_planes)[i].normal); }

    // The corners of stored triangle j rounded to T, as corner a and the
    // edges were computed from them: triangle_t_exact decides "flat" on the
    // corners (rounded edges of an exactly flat case need not be flat).
    std::array<vec3<T>, 3> corners(size_t j) const {
        const triangle<double>& x = (*source_triangles)[tree ? triangle_tree.order[j] : j];
        return {convert<T>(x.a), convert<T>(x.b), convert<T>(x.c)};
    }

    // magnitude: the largest coordinate of the scene, eye and lights, which
    // sets how much the boxes are widened (see boxes below).
    soa_scene(const scene<double>& s, bool use_tree, double magnitude) : tree(use_tree) {
        sphere_count = s.spheres.size();
        plane_count = s.planes.size();
        triangle_count = s.triangles.size();
        source_triangles = &s.triangles;
        source_planes = &s.planes;
        if (tree) build_trees(s, magnitude);
        auto sphere_at = [&](size_t j) -> const sphere<double>& {
            return s.spheres[tree ? sphere_tree.order[j] : j];
        };
        auto triangle_at = [&](size_t j) -> const triangle<double>& {
            return s.triangles[tree ? triangle_tree.order[j] : j];
        };
        for (size_t j = 0; j < sphere_count; ++j) {
            const auto& x = sphere_at(j);
            cx.push_back(T(x.center.x)), cy.push_back(T(x.center.y)), cz.push_back(T(x.center.z));
            radius.push_back(T(x.radius)), radius2.push_back(T(x.radius) * T(x.radius));
        }
        for (const auto& x : s.planes) {
            // Scaled by a power of two first (exact), so that normalize's
            // squares neither underflow nor overflow: a normal of any finite
            // non-zero length gives the unit normal to within rounding.
            const int k = formulations::direction_scale(x.normal);
            const vec3d n = normalize(vec3d(std::ldexp(x.normal.x, k), std::ldexp(x.normal.y, k), std::ldexp(x.normal.z, k)));
            px.push_back(T(x.point.x)), py.push_back(T(x.point.y)), pz.push_back(T(x.point.z));
            nx.push_back(T(n.x)), ny.push_back(T(n.y)), nz.push_back(T(n.z));
        }
        for (size_t j = 0; j < triangle_count; ++j) {
            const auto& x = triangle_at(j);
            // Edges from the corners rounded to T, as the general path sees them.
            vec3<T> a = convert<T>(x.a), e1 = convert<T>(x.b) - a, e2 = convert<T>(x.c) - a;
            ax.push_back(a.x), ay.push_back(a.y), az.push_back(a.z);
            e1x.push_back(e1.x), e1y.push_back(e1.y), e1z.push_back(e1.z);
            e2x.push_back(e2.x), e2y.push_back(e2.y), e2z.push_back(e2.z);
            // Centred on the centroid, through the farthest corner, made 1%
            // larger so rounding in the cull test can never drop a hit.
            const vec3d centre = (x.a + x.b + x.c) / 3.0;
            const double r = 1.01 * std::max({length(x.a - centre), length(x.b - centre), length(x.c - centre)});
            bx.push_back(T(centre.x)), by.push_back(T(centre.y)), bz.push_back(T(centre.z));
            br2.push_back(T(r * r));
        }
        for (auto* v : {&cx, &cy, &cz, &radius, &radius2, &px, &py, &pz, &nx, &ny, &nz, &ax, &ay, &az, &e1x, &e1y,
                        &e1z, &e2x, &e2y, &e2z, &bx, &by, &bz, &br2})
            // At least leaf_lanes of padding: a tree's leaf is tested leaf_lanes
            // objects at a time, past its end (those lanes are dropped).
            for (size_t k = 0; k < size_t(leaf_lanes) || v->size() % W; ++k)
                v->push_back(std::numeric_limits<T>::quiet_NaN());
        if (tree) {
            for (size_t j = 0; j < sphere_count; ++j) original.push_back(std::int64_t(sphere_tree.order[j]));
            for (size_t j = 0; j < plane_count; ++j) original.push_back(std::int64_t(sphere_count + j));
            for (size_t j = 0; j < triangle_count; ++j)
                original.push_back(std::int64_t(sphere_count + plane_count + triangle_tree.order[j]));
        }
    }

    // Float boxes that hold each object as the kernels see it, whatever the
    // rounding: the exact box, rounded outwards to float, widened by
    // 1e-6 of the scene's magnitude (float's own rounding of a coordinate
    // or of a ray's origin and direction is 6e-8 of it). A box test in
    // float can then only let through too much, never drop a hit, so the
    // tree gives the same closest object and t as brute force.
    void build_trees(const scene<double>& s, double magnitude) {
        const double pad = 1e-6 * magnitude;
        auto box_of = [&](vec3d lo, vec3d hi) {
            bvh_box b;
            for (int a = 0; a < 3; ++a) {
                b.lo[a] = std::nextafter(float(lo[a] - pad), -infinity<float>);
                b.hi[a] = std::nextafter(float(hi[a] + pad), infinity<float>);
            }
            return b;
        };
        std::vector<bvh_box> boxes(s.spheres.size());
        for (size_t i = 0; i < boxes.size(); ++i) {
            const auto& x = s.spheres[i];
            boxes[i] = box_of(x.center - vec3d(x.radius), x.center + vec3d(x.radius));
        }
        sphere_tree = build_bvh(boxes);
        boxes.assign(s.triangles.size(), bvh_box{});
        for (size_t i = 0; i < boxes.size(); ++i) {
            const auto& x = s.triangles[i];
            boxes[i] = box_of(glm::min(x.a, glm::min(x.b, x.c)), glm::max(x.a, glm::max(x.b, x.c)));
        }
        triangle_tree = collapse_to_wide(build_bvh(boxes));
    }
};

// A ray direction's reciprocal for the slab test. A zero component becomes
// 1e30 instead of infinity: (box side - origin) * 1e30 is then 0 or huge,
// never 0 * infinity = NaN, and the ray counts as between the planes of a
// slab it lies in (conservative: it is tested against the box's objects).
inline float slab_reciprocal(float d) {
    return d == 0.0f ? std::copysign(1e30f, d) : 1.0f / d;
}

// The far end of a slab interval is widened by a few units in the last
// place (Ize, "Robust BVH Ray Traversal", JCGT 2013), so a rounded exit
// never falls just short of a rounded entry for a ray that grazes a box.
constexpr float slab_widen = 1.0f + 4 * std::numeric_limits<float>::epsilon();

// Depth-first walk of a tree for the 32 rays of a packet. A node is
// opened when some ray of the packet enters its box before that ray's
// closest hit so far (best_t, updated by the leaves as they run); leaf(b, e)
// tests objects [b, e). Children are visited near one first, judged along
// the first ray's direction, so the closest hits come early and the far
// child's box is then often passed by.
template <class T, class Leaf>
void traverse_packet(const bvh_tree& tree, const packet<T>& p, const T* best_t, Leaf&& leaf) {
    if (tree.nodes.empty()) return;
    alignas(64) float ox[W], oy[W], oz[W], ix[W], iy[W], iz[W];
    for (int k = 0; k < W; ++k) {
        ox[k] = float(p.ox[k]), oy[k] = float(p.oy[k]), oz[k] = float(p.oz[k]);
        ix[k] = slab_reciprocal(float(p.dx[k])), iy[k] = slab_reciprocal(float(p.dy[k])),
        iz[k] = slab_reciprocal(float(p.dz[k]));
    }
    const float d0[3] = {float(p.dx[0]), float(p.dy[0]), float(p.dz[0])};
    auto opened = [&](const bvh_box& b) {
        int any = 0;
        for (int k = 0; k < W; ++k) {
            const float x0 = (b.lo[0] - ox[k]) * ix[k], x1 = (b.hi[0] - ox[k]) * ix[k];
            const float y0 = (b.lo[1] - oy[k]) * iy[k], y1 = (b.hi[1] - oy[k]) * iy[k];
            const float z0 = (b.lo[2] - oz[k]) * iz[k], z1 = (b.hi[2] - oz[k]) * iz[k];
            const float enter = std::max(std::max(std::min(x0, x1), std::min(y0, y1)), std::max(std::min(z0, z1), 0.0f));
            const float leave = std::min(std::min(std::max(x0, x1), std::max(y0, y1)), std::max(z0, z1)) * slab_widen;
            // best_t in float, rounded up a little: never below the true value.
            const float limit = float(best_t[k]) * slab_widen;
            any |= int((enter <= leave) & (enter <= limit));
        }
        return any != 0;
    };
    std::uint32_t stack[256];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
        const bvh_node& n = tree.nodes[stack[--top]];
        if (!opened(n.box)) continue;
        if (n.count > 0) {
            leaf(size_t(n.first), size_t(n.first) + n.count);
            continue;
        }
        const bvh_box &l = tree.nodes[n.first].box, &r = tree.nodes[n.first + 1].box;
        float towards = 0;  // > 0 when the left child lies further along d0
        for (int a = 0; a < 3; ++a) towards += ((l.lo[a] + l.hi[a]) - (r.lo[a] + r.hi[a])) * d0[a];
        // Pushed last is visited first: the near child.
        stack[top++] = towards > 0 ? n.first : n.first + 1;
        stack[top++] = towards > 0 ? n.first + 1 : n.first;
    }
}

// The same walk for one ray that only asks whether anything blocks it:
// blocked(b, e) tests objects [b, e) and the walk stops at the first yes.
template <class T, class Blocked>
bool traverse_any(const bvh_tree& tree, const ray<T>& r, T tmax, Blocked&& blocked) {
    if (tree.nodes.empty()) return false;
    const float o[3] = {float(r.origin.x), float(r.origin.y), float(r.origin.z)};
    const float d[3] = {float(r.direction.x), float(r.direction.y), float(r.direction.z)};
    const float inv[3] = {slab_reciprocal(d[0]), slab_reciprocal(d[1]), slab_reciprocal(d[2])};
    const float limit = float(tmax) * slab_widen;
    auto opened = [&](const bvh_box& b) {
        float enter = 0, leave = limit;
        for (int a = 0; a < 3; ++a) {
            const float t0 = (b.lo[a] - o[a]) * inv[a], t1 = (b.hi[a] - o[a]) * inv[a];
            enter = std::max(enter, std::min(t0, t1));
            leave = std::min(leave, std::max(t0, t1) * slab_widen);
        }
        return enter <= leave;
    };
    std::uint32_t stack[256];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
        const bvh_node& n = tree.nodes[stack[--top]];
        if (!opened(n.box)) continue;
        if (n.count > 0) {
            if (blocked(size_t(n.first), size_t(n.first) + n.count)) return true;
            continue;
        }
        stack[top++] = n.first;
        stack[top++] = n.first + 1;
    }
    return false;
}

// Four floats, one per child of a wide node: gcc's vector extension, which
// each copy of this file compiles for its own instruction set (SSE, part
// of every x86-64, holds four).
typedef float f4 __attribute__((vector_size(16)));

inline f4 row(const float (&r)[wide]) {
    f4 v;
    std::memcpy(&v, r, sizeof v);
    return v;
}

// Depth-first walk of a wide tree for one ray, nearest child first.
// At each node the ray's slab intervals with the four child boxes are
// computed together. The near side of a slab is the box's low side when
// the direction component is positive (reciprocal >= 0) and its high side
// otherwise, so no min/max is needed; an empty slot's box (low +inf, high
// -inf) then gives entry +inf and exit -inf and is never entered. The
// children entered before the ray's current limit are pushed farthest first,
// each with its entry distance: when it is popped later and the ray has
// meanwhile found a hit nearer than that entry, it is skipped unopened.
// leaf(first, count) tests a leaf's objects; for closest hit (AnyHit false)
// it updates `best`, the limit; for any hit it returns true at a blocker.
template <bool AnyHit, class T, class Leaf>
bool traverse_wide(const bvh_wide_tree& tree, const T (&origin)[3], const T (&direction)[3], const T& best,
                   Leaf&& leaf) {
    if (tree.nodes.empty()) return false;
    float o[3], inv[3];
    bool negative[3];
    for (int a = 0; a < 3; ++a) {
        o[a] = float(origin[a]);
        inv[a] = slab_reciprocal(float(direction[a]));
        negative[a] = inv[a] < 0;
    }
    // best in float, rounded up a little: never below the true value.
    float limit = float(best) * slab_widen;
    struct entry {
        float enter;
        std::uint32_t child, count;
    };
    entry stack[512];  // at most wide - 1 per level and the tree is at most ~130 levels deep
    int top = 0;
    entry current{0.0f, 0, 0};  // the root
    for (;;) {
        if (current.count > 0) {
            if constexpr (AnyHit) {
                if (leaf(current.child, current.count)) return true;
            } else {
                leaf(current.child, current.count);
                limit = float(best) * slab_widen;
            }
        } else {
            const bvh_wide_node& n = tree.nodes[current.child];
            f4 enter = {0, 0, 0, 0}, leave = {limit, limit, limit, limit};
            for (int a = 0; a < 3; ++a) {
                const f4 lo = row(n.lo[a]), hi = row(n.hi[a]);
                const f4 t0 = ((negative[a] ? hi : lo) - o[a]) * inv[a];
                const f4 t1 = ((negative[a] ? lo : hi) - o[a]) * inv[a] * slab_widen;
                enter = enter > t0 ? enter : t0;
                leave = leave < t1 ? leave : t1;
            }
            const auto in = enter <= leave;
            // The children entered, sorted farthest first (at most four:
            // insertion); all but the nearest are pushed, and the walk goes
            // on at the nearest without a trip through the stack.
            entry hit[wide];
            int h = 0;
            for (int i = 0; i < wide; ++i) {
                if (!in[i]) continue;
                const entry c{enter[i], n.child[i], n.count[i]};
                int j = h++;
                for (; j > 0 && hit[j - 1].enter < c.enter; --j) hit[j] = hit[j - 1];
                hit[j] = c;
            }
            if (h > 0) {
                for (int i = 0; i < h - 1; ++i) stack[top++] = hit[i];
                current = hit[h - 1];
                continue;
            }
        }
        // Next from the stack, skipping what lies beyond a hit found since it was pushed.
        do {
            if (top == 0) return false;
            current = stack[--top];
        } while (current.enter > limit);
    }
}

// c = |f|^2 - r^2 with the rounding error of each square added back (fma
// gives a product's exact low half), so a large sphere seen from near its
// surface, where |f|^2 and r^2 agree in most digits, keeps an accurate c.
template <class T>
inline T compensated_c(T fx, T fy, T fz, T r) {
    const T xx = fx * fx, yy = fy * fy, zz = fz * fz, rr = r * r;
    const T low = (std::fma(fx, fx, -xx) + std::fma(fy, fy, -yy) + std::fma(fz, fz, -zz)) - std::fma(r, r, -rr);
    return ((xx - rr) + (yy + zz)) + low;
}

// Just the discriminant of sphere_t (the same formula, so the same sign):
// negative means the ray passes the sphere by. Used to skip a sphere that
// no ray of a packet comes near, which at large N is almost every sphere.
template <class T, sphere_mode SM>
inline T sphere_discriminant(T fx, T fy, T fz, T c, T rr, T dx, T dy, T dz, T a, T inv_a) {
    const T half_b = fx * dx + fy * dy + fz * dz;
    if constexpr (SM == sphere_mode::plain) {
        return half_b * half_b - a * c;
    } else {
        const T m = half_b * inv_a;
        const T gx = fx - m * dx, gy = fy - m * dy, gz = fz - m * dz;
        return a * (rr - (gx * gx + gy * gy + gz * gz));
    }
}

// One sphere against one ray, with f = origin - centre, c = |f|^2 - r^2,
// a = |d|^2. Returns the nearest t > tmin, or infinity. The radius is > 0
// and at most 1e15 (the scene reader refuses anything else, and one that
// rounds to 0 in float); r only enters squared, so this test itself would
// answer a negative radius as if it were positive and a zero radius as a
// point.
template <class T, sphere_mode SM>
inline T sphere_t(T fx, T fy, T fz, T c, T rr, T dx, T dy, T dz, T a, T inv_a, T tmin) {
    const T half_b = fx * dx + fy * dy + fz * dz;
    T disc, near, far;
    if constexpr (SM == sphere_mode::plain) {
        // The plain quadratic: cheapest, loses digits as (distance / radius)^2.
        disc = half_b * half_b - a * c;
        const T root = std::sqrt(disc);  // NaN when disc < 0: that lane's answer is dropped below
        near = (-half_b - root) * inv_a;
        far = (-half_b + root) * inv_a;
    } else {
        // The perpendicular foot g = f - (half_b / a) d is formed before
        // squaring, then the stable root pair c / q and q / a.
        const T m = half_b * inv_a;
        const T gx = fx - m * dx, gy = fy - m * dy, gz = fz - m * dz;
        disc = a * (rr - (gx * gx + gy * gy + gz * gz));
        const T root = std::sqrt(disc);
        const T q = -(half_b + std::copysign(root, half_b));
        const T r1 = c / q, r2 = q * inv_a;
        near = r1 < r2 ? r1 : r2;
        far = r1 < r2 ? r2 : r1;
    }
    const T t = near > tmin ? near : far;
    return ((disc >= T(0)) & (t > tmin)) ? t : infinity<T>;
}


// One ray against the scene's triangle j, by the brute-force kernel: the
// per-lane work of every triangle loop below (brute force, the tree's leaves
// and the shadow test), written once so they stay the same to the bit.
template <class T>
[[gnu::always_inline]] inline T triangle_lane_t(const soa_scene<T>& s, size_t j, T ox, T oy, T oz, T dx, T dy, T dz,
                                                T d_max, T tmin, int& unsure) {
    const T sx = ox - s.ax[j], sy = oy - s.ay[j], sz = oz - s.az[j];
    const T qx = sy * s.e1z[j] - sz * s.e1y[j], qy = sz * s.e1x[j] - sx * s.e1z[j], qz = sx * s.e1y[j] - sy * s.e1x[j];
    const T flat_bound = flat_scale(s.e1x[j], s.e1y[j], s.e1z[j], s.e2x[j], s.e2y[j], s.e2z[j]) * d_max + flat_tiny<T>();
    return triangle_t(sx, sy, sz, qx, qy, qz, s.e1x[j], s.e1y[j], s.e1z[j], s.e2x[j], s.e2y[j], s.e2z[j], dx, dy, dz,
                      tmin, flat_bound, unsure);
}

// triangle_t_exact for the scene's triangle j (j < triangle_count): the
// scalar path for the rare lanes triangle_t was unsure of.
template <class T>
T triangle_exact_t(const soa_scene<T>& s, size_t j, T ox, T oy, T oz, T dx, T dy, T dz, T tmin) {
    const T sx = ox - s.ax[j], sy = oy - s.ay[j], sz = oz - s.az[j];
    const T qx = sy * s.e1z[j] - sz * s.e1y[j], qy = sz * s.e1x[j] - sx * s.e1z[j], qz = sx * s.e1y[j] - sy * s.e1x[j];
    const std::array<vec3<T>, 3> c = s.corners(j);
    return triangle_t_exact(sx, sy, sz, qx, qy, qz, s.e1x[j], s.e1y[j], s.e1z[j], s.e2x[j], s.e2y[j], s.e2z[j], dx, dy,
                            dz, tmin, c[0], c[1], c[2]);
}

// One ray against the triangles [g, g + leaf_lanes) of a tree's leaf that
// ends at e (lanes from e on, other leaves' triangles or padding, give
// infinity): t[i] for triangle g + i, by the brute-force kernel in
// leaf_lanes lanes, then triangle_t_exact for the whole group when a lane
// was unsure (as the brute-force loops do), so t is the same to the bit.
template <class T>
struct triangle_group {
    alignas(64) T t[leaf_lanes];

    triangle_group(const soa_scene<T>& s, size_t g, size_t e, T ox, T oy, T oz, T dx, T dy, T dz, T d_max, T tmin) {
        int unsure = 0;
        for (int i = 0; i < leaf_lanes; ++i) {
            const size_t j = g + size_t(i);
            const T x = triangle_lane_t(s, j, ox, oy, oz, dx, dy, dz, d_max, tmin, unsure);
            t[i] = j < e ? x : infinity<T>;
        }
        if (!unsure) return;
        for (int i = 0; i < leaf_lanes; ++i) {  // nearly parallel or degenerate: decide exactly
            const size_t j = g + size_t(i);
            if (j >= e) break;
            t[i] = triangle_exact_t(s, j, ox, oy, oz, dx, dy, dz, tmin);
        }
    }

    bool blocked_before(T tmax) const {
        int blocked = 0;
        for (int i = 0; i < leaf_lanes; ++i) blocked |= int(t[i] < tmax);
        return blocked != 0;
    }
};

// The closest hit of each ray of a packet: tbest[k] and object[k] (-1 for
// a miss). Objects are numbered spheres, then planes, then triangles.
template <class T, sphere_mode SM, bool Planes, bool Tris, bool CommonOrigin>
void closest_hits(const soa_scene<T>& s, const packet<T>& p, T tmin, T* tbest, index_t<T>* object) {
    using I = index_t<T>;
    // Local arrays, copied out at the end: the compiler may then keep them
    // in registers for the whole object loop.
    alignas(64) T a[W], inv_a[W], best_t[W], d_max[W];
    alignas(64) I best[W];
    for (int k = 0; k < W; ++k) {
        a[k] = p.dx[k] * p.dx[k] + p.dy[k] * p.dy[k] + p.dz[k] * p.dz[k];
        inv_a[k] = T(1) / a[k];
        d_max[k] = direction_max(p.dx[k], p.dy[k], p.dz[k]);
        best_t[k] = infinity<T>;
        best[k] = -1;
    }
    auto keep = [&](int k, T t, I id) {
        const T old_t = best_t[k];
        const I old = best[k];
        const bool closer = t < old_t;
        best_t[k] = closer ? t : old_t;
        // The object number is selected with a mask, not with ?: : gcc 12
        // turns "closer ? id : best[k]" into a conditional store, which it
        // vectorises with a test and a branch that mispredicts all the time.
        const I mask = -I(closer);
        best[k] = (old & ~mask) | (id & mask);
    };
    if constexpr (SM != sphere_mode::none) {
      auto spheres = [&](size_t begin, size_t end) {
        for (size_t i = begin; i < end; ++i) {
            const T cx = s.cx[i], cy = s.cy[i], cz = s.cz[i], r = s.radius[i], rr = s.radius2[i];
            if constexpr (CommonOrigin) {
                const T fx = p.ox[0] - cx, fy = p.oy[0] - cy, fz = p.oz[0] - cz;
                const T c = SM == sphere_mode::plain ? fx * fx + fy * fy + fz * fz - rr : compensated_c(fx, fy, fz, r);
                // Cull first: the full test (square root, division, the
                // update of the closest hit) only when some ray of the
                // packet passes within the sphere's radius.
                int near_any = 0;
                for (int k = 0; k < W; ++k)
                    near_any |= int(sphere_discriminant<T, SM>(fx, fy, fz, c, rr, p.dx[k], p.dy[k], p.dz[k], a[k],
                                                               inv_a[k]) >= T(0));
                if (!near_any) continue;
                for (int k = 0; k < W; ++k)
                    keep(k, sphere_t<T, SM>(fx, fy, fz, c, rr, p.dx[k], p.dy[k], p.dz[k], a[k], inv_a[k], tmin), I(i));
            } else {
                int near_any = 0;
                for (int k = 0; k < W; ++k) {
                    const T fx = p.ox[k] - cx, fy = p.oy[k] - cy, fz = p.oz[k] - cz;
                    const T c = fx * fx + fy * fy + fz * fz - rr;  // only the plain form's sign test uses it
                    near_any |= int(sphere_discriminant<T, SM>(fx, fy, fz, c, rr, p.dx[k], p.dy[k], p.dz[k], a[k],
                                                               inv_a[k]) >= T(0));
                }
                if (!near_any) continue;
                for (int k = 0; k < W; ++k) {
                    const T fx = p.ox[k] - cx, fy = p.oy[k] - cy, fz = p.oz[k] - cz;
                    const T c =
                        SM == sphere_mode::plain ? fx * fx + fy * fy + fz * fz - rr : compensated_c(fx, fy, fz, r);
                    keep(k, sphere_t<T, SM>(fx, fy, fz, c, rr, p.dx[k], p.dy[k], p.dz[k], a[k], inv_a[k], tmin), I(i));
                }
            }
        }
      };
      if (s.tree)
          traverse_packet(s.sphere_tree, p, best_t, spheres);
      else
          spheres(0, s.sphere_count);
    }
    if constexpr (Planes) {
        const I base = I(s.sphere_count);
        for (size_t i = 0; i < s.plane_count; ++i) {
            const T nx = s.nx[i], ny = s.ny[i], nz = s.nz[i];
            int unsure = 0;
            for (int k = 0; k < W; ++k) {
                const int o = CommonOrigin ? 0 : k;
                const T num = nx * (s.px[i] - p.ox[o]) + ny * (s.py[i] - p.oy[o]) + nz * (s.pz[i] - p.oz[o]);
                keep(k, plane_t(num, nx, ny, nz, p.dx[k], p.dy[k], p.dz[k], tmin, unsure), base + I(i));
            }
            if (unsure)  // a ray nearly or exactly parallel: decide exactly (keep takes a t once)
                for (int k = 0; k < W; ++k) {
                    const int o = CommonOrigin ? 0 : k;
                    const T num = nx * (s.px[i] - p.ox[o]) + ny * (s.py[i] - p.oy[o]) + nz * (s.pz[i] - p.oz[o]);
                    keep(k, plane_t_exact(num, nx, ny, nz, p.dx[k], p.dy[k], p.dz[k], tmin, s.plane_normal(i)),
                         base + I(i));
                }
        }
    }
    if constexpr (Tris) {
        const I base = I(s.sphere_count + s.plane_count);
      auto triangles = [&](size_t begin, size_t end) {
        for (size_t i = begin; i < end; ++i) {
            const T e1x = s.e1x[i], e1y = s.e1y[i], e1z = s.e1z[i], e2x = s.e2x[i], e2y = s.e2y[i], e2z = s.e2z[i];
            // Cull: skip the triangle when no ray of the packet comes near
            // its bounding sphere (the robust discriminant: accurate even
            // when the triangle is small and far away).
            int near_any = 0;
            for (int k = 0; k < W; ++k) {
                const int o = CommonOrigin ? 0 : k;
                const T fx = p.ox[o] - s.bx[i], fy = p.oy[o] - s.by[i], fz = p.oz[o] - s.bz[i];
                near_any |= int(sphere_discriminant<T, sphere_mode::robust>(fx, fy, fz, T(0), s.br2[i], p.dx[k], p.dy[k],
                                                                           p.dz[k], a[k], inv_a[k]) >= T(0));
            }
            if (!near_any) continue;
            const T scale = flat_scale(e1x, e1y, e1z, e2x, e2y, e2z), tiny = flat_tiny<T>();
            int unsure = 0;
            if constexpr (CommonOrigin) {
                const T sx = p.ox[0] - s.ax[i], sy = p.oy[0] - s.ay[i], sz = p.oz[0] - s.az[i];
                const T qx = sy * e1z - sz * e1y, qy = sz * e1x - sx * e1z, qz = sx * e1y - sy * e1x;
                for (int k = 0; k < W; ++k)
                    keep(k,
                         triangle_t(sx, sy, sz, qx, qy, qz, e1x, e1y, e1z, e2x, e2y, e2z, p.dx[k], p.dy[k], p.dz[k],
                                    tmin, scale * d_max[k] + tiny, unsure),
                         base + I(i));
            } else {
                for (int k = 0; k < W; ++k) {
                    const T sx = p.ox[k] - s.ax[i], sy = p.oy[k] - s.ay[i], sz = p.oz[k] - s.az[i];
                    const T qx = sy * e1z - sz * e1y, qy = sz * e1x - sx * e1z, qz = sx * e1y - sy * e1x;
                    keep(k,
                         triangle_t(sx, sy, sz, qx, qy, qz, e1x, e1y, e1z, e2x, e2y, e2z, p.dx[k], p.dy[k], p.dz[k],
                                    tmin, scale * d_max[k] + tiny, unsure),
                         base + I(i));
                }
            }
            if (unsure)  // nearly parallel or degenerate: decide exactly (keep takes a t once)
                for (int k = 0; k < W; ++k) {
                    const int o = CommonOrigin ? 0 : k;
                    keep(k, triangle_exact_t(s, i, p.ox[o], p.oy[o], p.oz[o], p.dx[k], p.dy[k], p.dz[k], tmin),
                         base + I(i));
                }
        }
      };
      if (s.tree) {
          // One ray at a time through the wide tree (see soa_scene). A
          // leaf's triangles are tested as one group of leaf_lanes lanes
          // with the brute-force arithmetic, so t is the same to the bit.
          for (int k = 0; k < W; ++k) {
              const int o = CommonOrigin ? 0 : k;
              const T ox = p.ox[o], oy = p.oy[o], oz = p.oz[o], dx = p.dx[k], dy = p.dy[k], dz = p.dz[k];
              const T origin[3] = {ox, oy, oz}, direction[3] = {dx, dy, dz};
              T bt = best_t[k];
              I bo = best[k];
              traverse_wide<false>(s.triangle_tree, origin, direction, bt, [&](std::uint32_t b, std::uint32_t n) {
                  for (size_t g = b; g < size_t(b) + n; g += leaf_lanes) {
                      const triangle_group<T> group(s, g, size_t(b) + n, ox, oy, oz, dx, dy, dz, d_max[k], tmin);
                      for (int i = 0; i < leaf_lanes; ++i)
                          if (group.t[i] < bt) bt = group.t[i], bo = base + I(g) + I(i);
                  }
                  return false;
              });
              best_t[k] = bt, best[k] = bo;
          }
      } else
          triangles(0, s.triangle_count);
    }
    for (int k = 0; k < W; ++k) {
        tbest[k] = best_t[k];
        object[k] = best[k];
    }
}

// Is anything hit with tmin < t < tmax? One ray (a shadow ray) against G
// objects at a time: here the lanes are objects, and the loop stops at the
// first group with a blocker.
template <class T, sphere_mode SM, bool Planes, bool Tris>
bool any_hit(const soa_scene<T>& s, const ray<T>& r, T tmin, T tmax) {
    // Groups of G objects, one vector register of floats: larger groups
    // would spend their lanes on the NaN padding in small scenes.
    constexpr int G = 8;
    static_assert(W % G == 0, "the arrays are padded to a multiple of W, so also of G");
    auto round_up = [](size_t n) { return (n + G - 1) / G * G; };
    const T ox = r.origin.x, oy = r.origin.y, oz = r.origin.z;
    const T dx = r.direction.x, dy = r.direction.y, dz = r.direction.z;
    const T a = dx * dx + dy * dy + dz * dz, inv_a = T(1) / a;
    const T d_max = direction_max(dx, dy, dz);
    [[maybe_unused]] const T origin[3] = {ox, oy, oz}, direction[3] = {dx, dy, dz};
    if constexpr (SM != sphere_mode::none) {
        // With a tree: only the leaves whose boxes the ray crosses, one object at a time.
        if (s.tree) {
            if (traverse_any(s.sphere_tree, r, tmax, [&](size_t b, size_t e) {
                    for (size_t j = b; j < e; ++j) {
                        const T fx = ox - s.cx[j], fy = oy - s.cy[j], fz = oz - s.cz[j];
                        const T c = SM == sphere_mode::plain ? fx * fx + fy * fy + fz * fz - s.radius2[j]
                                                             : compensated_c(fx, fy, fz, s.radius[j]);
                        if (sphere_t<T, SM>(fx, fy, fz, c, s.radius2[j], dx, dy, dz, a, inv_a, tmin) < tmax) return true;
                    }
                    return false;
                }))
                return true;
        } else
        for (size_t i = 0; i < round_up(s.sphere_count); i += G) {
            int blocked = 0;
            for (int k = 0; k < G; ++k) {
                const size_t j = i + size_t(k);
                const T fx = ox - s.cx[j], fy = oy - s.cy[j], fz = oz - s.cz[j];
                const T c = SM == sphere_mode::plain ? fx * fx + fy * fy + fz * fz - s.radius2[j]
                                                     : compensated_c(fx, fy, fz, s.radius[j]);
                blocked |= int(sphere_t<T, SM>(fx, fy, fz, c, s.radius2[j], dx, dy, dz, a, inv_a, tmin) < tmax);
            }
            if (blocked) return true;
        }
    }
    if constexpr (Planes) {
        for (size_t i = 0; i < round_up(s.plane_count); i += G) {
            int blocked = 0, unsure = 0;
            for (int k = 0; k < G; ++k) {
                const size_t j = i + size_t(k);
                const T num = s.nx[j] * (s.px[j] - ox) + s.ny[j] * (s.py[j] - oy) + s.nz[j] * (s.pz[j] - oz);
                blocked |= int(plane_t(num, s.nx[j], s.ny[j], s.nz[j], dx, dy, dz, tmin, unsure) < tmax);
            }
            if (unsure && !blocked)  // nearly parallel: decide exactly
                for (size_t j = i; j < i + G && j < s.plane_count; ++j) {  // past the count: padding
                    const T num = s.nx[j] * (s.px[j] - ox) + s.ny[j] * (s.py[j] - oy) + s.nz[j] * (s.pz[j] - oz);
                    blocked |=
                        int(plane_t_exact(num, s.nx[j], s.ny[j], s.nz[j], dx, dy, dz, tmin, s.plane_normal(j)) < tmax);
                }
            if (blocked) return true;
        }
    }
    if constexpr (Tris) {
        if (s.tree) {
            if (traverse_wide<true>(s.triangle_tree, origin, direction, tmax, [&](std::uint32_t b, std::uint32_t n) {
                    const size_t e = size_t(b) + n;
                    for (size_t g = b; g < e; g += leaf_lanes)
                        if (triangle_group<T>(s, g, e, ox, oy, oz, dx, dy, dz, d_max, tmin).blocked_before(tmax))
                            return true;
                    return false;
                }))
                return true;
        } else
        for (size_t i = 0; i < round_up(s.triangle_count); i += G) {
            int blocked = 0, unsure = 0;
            for (int k = 0; k < G; ++k) {
                const size_t j = i + size_t(k);
                blocked |= int(triangle_lane_t(s, j, ox, oy, oz, dx, dy, dz, d_max, tmin, unsure) < tmax);
            }
            if (unsure && !blocked)  // nearly parallel or degenerate: decide exactly
                for (size_t j = i; j < i + G && j < s.triangle_count; ++j)  // past the count: padding, never a hit
                    blocked |= int(triangle_exact_t(s, j, ox, oy, oz, dx, dy, dz, tmin) < tmax);
            if (blocked) return true;
        }
    }
    return false;
}

// Everything the pixel loop needs, in precision T.
template <class T>
struct context {
    soa_scene<T> soa;
    scene_camera<T> camera;
    const scene<double>& world;
    std::vector<int> material_of;  // by object number
    T tmin;

    context(const scene_description& d, int width, int height, bool tree)
        : soa(d.world, tree, magnitude(d)), camera(d.camera, width, height), world(d.world),
          tmin(camera.primary_range().min) {
        const size_t spheres = d.world.spheres.size(), planes = d.world.planes.size();
        for (size_t i = 0; i < size_t(d.world.object_count()); ++i) {
            const size_t o = original(i);
            material_of.push_back(o < spheres            ? d.world.spheres[o].material
                                  : o < spheres + planes ? d.world.planes[o - spheres].material
                                                         : d.world.triangles[o - spheres - planes].material);
        }
    }

    // The scene's own number of the object stored as number i.
    size_t original(size_t i) const { return soa.tree ? size_t(soa.original[i]) : i; }

    // The largest coordinate in the scene, the eye and the lights.
    static double magnitude(const scene_description& d) {
        double m = 0;
        auto see = [&](const vec3d& p) { m = std::max({m, std::fabs(p.x), std::fabs(p.y), std::fabs(p.z)}); };
        see(d.camera.eye);
        for (const auto& l : d.world.lights) see(l.position);
        for (const auto& x : d.world.spheres) see(glm::abs(x.center) + vec3d(x.radius));
        for (const auto& x : d.world.triangles) see(x.a), see(x.b), see(x.c);
        return m;
    }

    // One line about the trees, for the render's report.
    std::string describe_trees() const {
        char line[200];
        const bvh_tree& a = soa.sphere_tree;
        const bvh_wide_tree& b = soa.triangle_tree;
        std::snprintf(line, sizeof line, "tree: built in %.0f ms on %d threads, %.1f MB, %zu leaves, depth %zu",
                      1e3 * (a.build_seconds + b.build_seconds), render_threads(), double(a.bytes() + b.bytes()) / 1e6,
                      a.leaves + b.leaves, std::max(a.depth, b.depth));
        return line;
    }

    // The packet of rays through a tile of tile_w x tile_h pixels with its
    // top-left corner at (col0, row0): lane k is pixel (col0 + k % tile_w,
    // row0 + k / tile_w). A square-ish tile keeps the rays close together,
    // so more spheres miss all of them and are skipped. Pixels past the
    // image's edge repeat the edge pixel; their results are dropped.
    void fill(packet<T>& p, int col0, int row0) const {
        for (int k = 0; k < W; ++k) {
            const int col = std::min(col0 + k % tile_w, camera.width() - 1);
            const int row = std::min(row0 + k / tile_w, camera.height() - 1);
            const ray<T> r = camera.primary_ray(col, row);
            p.ox[k] = r.origin.x, p.oy[k] = r.origin.y, p.oz[k] = r.origin.z;
            p.dx[k] = r.direction.x, p.dy[k] = r.direction.y, p.dz[k] = r.direction.z;
        }
    }

    template <sphere_mode SM, bool Planes, bool Tris>
    void trace(const packet<T>& p, T* t, index_t<T>* object) const {
        if (camera.type == camera_description::kind::pinhole)
            closest_hits<T, SM, Planes, Tris, true>(soa, p, tmin, t, object);
        else
            closest_hits<T, SM, Planes, Tris, false>(soa, p, tmin, t, object);
    }

    // Unit normal at a hit point of object o, facing the ray for planes and triangles.
    vec3<T> normal(size_t o, const vec3<T>& point, const vec3<T>& direction) const {
        if (o < soa.sphere_count) return (point - vec3<T>(soa.cx[o], soa.cy[o], soa.cz[o])) / soa.radius[o];
        vec3<T> n;
        if (o < soa.sphere_count + soa.plane_count) {
            o -= soa.sphere_count;
            n = vec3<T>(soa.nx[o], soa.ny[o], soa.nz[o]);
        } else {
            o -= soa.sphere_count + soa.plane_count;
            n = normalize(cross(vec3<T>(soa.e1x[o], soa.e1y[o], soa.e1z[o]), vec3<T>(soa.e2x[o], soa.e2y[o], soa.e2z[o])));
        }
        return dot(n, direction) > T(0) ? -n : n;
    }
};

template <class T, sphere_mode SM, bool Planes, bool Tris, bool Lights>
image render_with(const scene_description& d, int width, int height, bool tree, render_stats& stats) {
    const stopwatch setup;
    const double setup_cpu = process_cpu_seconds();
    const context<T> ctx(d, width, height, tree);
    stats.setup_seconds = setup.seconds();
    stats.setup_cpu_seconds = process_cpu_seconds() - setup_cpu;
    if (tree) std::fprintf(stderr, "%s\n", ctx.describe_trees().c_str());  // stderr: outside rt-bench's tables
    image img(width, height);
    std::atomic<long> shadow_rays{0};
    for_each_row((height + tile_h - 1) / tile_h, [&](int tile_row) {
        const int row0 = tile_row * tile_h;
        long shadows = 0;
        ch06::occlusion_test<T> occluded;
        if constexpr (Lights)
            occluded = [&](const ray<T>& r, const interval<T>& range) {
                ++shadows;
                return any_hit<T, SM, Planes, Tris>(ctx.soa, r, range.min, range.max);
            };
        packet<T> p;
        alignas(64) T t[W];
        alignas(64) index_t<T> object[W];
        for (int col0 = 0; col0 < width; col0 += tile_w) {
            ctx.fill(p, col0, row0);
            ctx.template trace<SM, Planes, Tris>(p, t, object);
            for (int k = 0; k < W; ++k) {
                const int col = col0 + k % tile_w, row = row0 + k / tile_w;
                if (col >= width || row >= height) continue;
                color& out = img.at(col, row);
                if (object[k] < 0) {
                    out = d.world.background;
                    continue;
                }
                const vec3<T> origin(p.ox[k], p.oy[k], p.oz[k]), direction(p.dx[k], p.dy[k], p.dz[k]);
                const vec3<T> point = origin + t[k] * direction;
                const vec3<T> n = ctx.normal(size_t(object[k]), point, direction);
                const material m = material_at(d.world.materials[size_t(ctx.material_of[size_t(object[k])])], point);
                if constexpr (Lights)
                    out = ch06::shade(point, n, -direction, m, d.world.lights, d.world.ambient, occluded);
                else
                    out = unlit_colour(m, n, direction);
            }
        }
        shadow_rays += shadows;
    });
    stats.rays = long(width) * long(height) + shadow_rays.load();
    return img;
}

template <class T, sphere_mode SM, bool Planes, bool Tris>
primary_hits trace_with(const scene_description& d, int width, int height, bool tree) {
    const context<T> ctx(d, width, height, tree);
    primary_hits hits;
    hits.object.assign(size_t(width) * size_t(height), -1);
    hits.t.assign(size_t(width) * size_t(height), 0);
    for_each_row((height + tile_h - 1) / tile_h, [&](int tile_row) {
        const int row0 = tile_row * tile_h;
        packet<T> p;
        alignas(64) T t[W];
        alignas(64) index_t<T> object[W];
        for (int col0 = 0; col0 < width; col0 += tile_w) {
            ctx.fill(p, col0, row0);
            ctx.template trace<SM, Planes, Tris>(p, t, object);
            for (int k = 0; k < W; ++k) {
                const int col = col0 + k % tile_w, row = row0 + k / tile_w;
                if (col >= width || row >= height) continue;
                size_t i = size_t(row) * size_t(width) + size_t(col);
                hits.object[i] = object[k] < 0 ? -1 : int(ctx.original(size_t(object[k])));
                hits.t[i] = (long double)t[k];
            }
        }
    });
    return hits;
}

template <class T, sphere_mode SM, bool Planes, bool Tris>
long count_with(const scene_description& d, int width, int height, bool tree, int repeat, render_stats* stats) {
    const stopwatch setup;
    const double setup_cpu = process_cpu_seconds();
    const context<T> ctx(d, width, height, tree);
    if (stats) {
        stats->setup_seconds = setup.seconds();
        stats->setup_cpu_seconds = process_cpu_seconds() - setup_cpu;
    }
    std::atomic<long> hits{0};
    for (int r = 0; r < repeat; ++r) {
    hits = 0;
    for_each_row((height + tile_h - 1) / tile_h, [&](int tile_row) {
        const int row0 = tile_row * tile_h;
        packet<T> p;
        alignas(64) T t[W];
        alignas(64) index_t<T> object[W];
        long row_hits = 0;
        for (int col0 = 0; col0 < width; col0 += tile_w) {
            ctx.fill(p, col0, row0);
            ctx.template trace<SM, Planes, Tris>(p, t, object);
            for (int k = 0; k < W; ++k)
                row_hits += object[k] >= 0 && col0 + k % tile_w < width && row0 + k / tile_w < height;
        }
        hits += row_hits;
    });
    }
    return hits.load();
}

// Calls f(SM, Planes, Tris, Lights) with each choice as a compile-time
// constant (std::integral_constant), so f can instantiate exactly one kernel.
template <class F>
decltype(auto) dispatch(sphere_mode sm, bool planes, bool tris, bool lights, F&& f) {
    auto pick = [](bool v, auto&& g) { return v ? g(std::true_type{}) : g(std::false_type{}); };
    auto go = [&](auto SM) {
        return pick(planes, [&](auto P) {
            return pick(tris, [&](auto Tr) { return pick(lights, [&](auto L) { return f(SM, P, Tr, L); }); });
        });
    };
    switch (sm) {
        case sphere_mode::none: return go(std::integral_constant<sphere_mode, sphere_mode::none>{});
        case sphere_mode::plain: return go(std::integral_constant<sphere_mode, sphere_mode::plain>{});
        default: return go(std::integral_constant<sphere_mode, sphere_mode::robust>{});
    }
}

sphere_mode mode_of(const scene_plan& plan) {
    if (plan.spheres == 0) return sphere_mode::none;
    return plan.form == sphere_formulation::plain ? sphere_mode::plain : sphere_mode::robust;
}

}  // namespace

image render_fast(const scene_description& d, const scene_plan& plan, int width, int height, render_stats& stats) {
    auto run = [&](auto type) {
        using T = decltype(type);
        return dispatch(mode_of(plan), plan.planes > 0, plan.triangles > 0, plan.lights > 0,
                        [&](auto SM, auto P, auto Tr, auto L) {
                            return render_with<T, decltype(SM)::value, decltype(P)::value, decltype(Tr)::value,
                                               decltype(L)::value>(d, width, height, plan.tree, stats);
                        });
    };
    return plan.prec == precision::single ? run(float{}) : run(double{});
}

primary_hits trace_primary(const scene_description& d, const scene_plan& plan, int width, int height) {
    auto run = [&](auto type) {
        using T = decltype(type);
        return dispatch(mode_of(plan), plan.planes > 0, plan.triangles > 0, false, [&](auto SM, auto P, auto Tr, auto) {
            return trace_with<T, decltype(SM)::value, decltype(P)::value, decltype(Tr)::value>(d, width, height, plan.tree);
        });
    };
    return plan.prec == precision::single ? run(float{}) : run(double{});
}

long count_primary_hits(const scene_description& d, const scene_plan& plan, int width, int height, int repeat,
                        render_stats* stats) {
    auto run = [&](auto type) {
        using T = decltype(type);
        return dispatch(mode_of(plan), plan.planes > 0, plan.triangles > 0, false, [&](auto SM, auto P, auto Tr, auto) {
            return count_with<T, decltype(SM)::value, decltype(P)::value, decltype(Tr)::value>(d, width, height, plan.tree,
                                                                                                repeat, stats);
        });
    };
    return plan.prec == precision::single ? run(float{}) : run(double{});
}

tree_figures build_trees_only(const scene_description& d) {
    const soa_scene<float> soa(d.world, true, context<float>::magnitude(d));
    tree_figures f;
    f.build_seconds = soa.sphere_tree.build_seconds + soa.triangle_tree.build_seconds;
    f.bytes = soa.sphere_tree.bytes() + soa.triangle_tree.bytes();
    f.leaves = soa.sphere_tree.leaves + soa.triangle_tree.leaves;
    f.depth = std::max(soa.sphere_tree.depth, soa.triangle_tree.depth);
    return f;
}

primary_hits trace_primary_reference(const scene_description& d, int width, int height) {
    const bool spheres = !d.world.spheres.empty();
    return dispatch(spheres ? sphere_mode::robust : sphere_mode::none, !d.world.planes.empty(),
                    !d.world.triangles.empty(), false, [&](auto SM, auto P, auto Tr, auto) {
                        return trace_with<long double, decltype(SM)::value, decltype(P)::value, decltype(Tr)::value>(
                            d, width, height, false);
                    });
}

}  // namespace rt::render_tool::RT_FAST_ISA
