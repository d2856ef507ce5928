// fast_path_traversal.hpp — part of fast_path.cpp (see fast_path_arrays.hpp):
// the walks through the trees. The slab test's float arithmetic, a packet's
// walk of the binary tree, one shadow ray's walk of it, and one ray's walk
// of the 4-wide tree.
#pragma once
#ifndef RT_FAST_PATH_PARTS
#error "a part of fast_path.cpp: included by it, after its headers and its target pragma"
#endif

// The slab test's rule is chapter 08's (slab_axis, fast_path_kernels.hpp):
// an infinite reciprocal for a zero direction component, the near face by
// the reciprocal's sign, and NaN-safe updates of the entry and exit.
// A component that is not zero but whose reciprocal overflows float (below
// 2^-128) is treated as parallel. That cannot drop a hit in a box padded
// by box_pad (soa_scene::build_trees): the renderer's directions have a
// largest component of at least 2^-31 (closest_hits and any_hit scale
// shorter ones), so over any t that stays within the scene a ray moves by
// less than 2^-90 of the scene's magnitude along such an axis, far below
// the 1e-6 of it that every box is widened by beyond its object.
inline float slab_reciprocal(float d) { return 1.0f / d; }

// The far end of a slab interval is widened by a few units in the last
// place (Ize, "Robust BVH Ray Traversal", JCGT 2013), so a rounded exit
// never falls just short of a rounded entry for a ray that grazes a box.
constexpr float slab_widen = 1.0f + 4 * std::numeric_limits<float>::epsilon();

// The packet's rays in float, as the slab tests of traverse_packet use
// them, with the rule above: the near face and the NaN-safe updates are
// selects, so the loop over the 32 lanes is still vectorised (blends where
// the stand-in 1e30 had min and max: 3-5% slower in a quiet scratch timing
// of this walk, not the half an earlier rt-bench run under load read).
//
// In most packets (a camera's tile, a light's shadow rays) every ray's
// direction has the same sign along each axis. Then every lane takes its
// near face from the same side of the box, and one_sided says so: the walk
// picks each face once per box instead of once per lane, the same
// arithmetic on the same numbers, so the same answers.
struct packet_slabs {
    alignas(64) float ox[W], oy[W], oz[W], ix[W], iy[W], iz[W];
    bool one_sided = false;  // each axis's reciprocals all of one sign
    bool down[3] = {};       // and which: negative (near face hi)

    template <class T>
    [[gnu::always_inline]] explicit packet_slabs(const packet<T>& p) {
        int negative[3] = {0, 0, 0};
        for (int k = 0; k < W; ++k) {
            ox[k] = float(p.ox[k]), oy[k] = float(p.oy[k]), oz[k] = float(p.oz[k]);
            ix[k] = slab_reciprocal(float(p.dx[k])), iy[k] = slab_reciprocal(float(p.dy[k])),
            iz[k] = slab_reciprocal(float(p.dz[k]));
            negative[0] += int(ix[k] < 0), negative[1] += int(iy[k] < 0), negative[2] += int(iz[k] < 0);
        }
        one_sided = true;
        for (int a = 0; a < 3; ++a) {
            one_sided &= negative[a] == 0 || negative[a] == W;
            down[a] = negative[a] == W;
        }
    }
};

// A box that at most this many rays of a packet enter is walked by those
// rays one at a time (traverse_packet): deep in a big tree, where the
// boxes are small, the packet's 32 lanes would mostly work for rays that
// are not there.
constexpr int packet_hand_off = 2;

// Which rays k of the packet enter box b before best_t[k] (a bit each).
template <class T>
[[gnu::always_inline]] inline std::uint32_t rays_entering(const packet_slabs& slabs, const bvh_box& b, const T* best_t) {
    std::uint32_t mask = 0;
    if (slabs.one_sided) {
        // slab_axis's arithmetic with the near and far faces chosen once.
        float near[3], far[3];
        for (int a = 0; a < 3; ++a) near[a] = slabs.down[a] ? b.hi[a] : b.lo[a], far[a] = slabs.down[a] ? b.lo[a] : b.hi[a];
        for (int k = 0; k < W; ++k) {
            float enter = 0, leave = float(best_t[k]) * slab_widen;
            slab_faces(near[0], far[0], slabs.ox[k], slabs.ix[k], slab_widen, enter, leave);
            slab_faces(near[1], far[1], slabs.oy[k], slabs.iy[k], slab_widen, enter, leave);
            slab_faces(near[2], far[2], slabs.oz[k], slabs.iz[k], slab_widen, enter, leave);
            mask |= enter <= leave ? std::uint32_t(1) << k : 0;
        }
        return mask;
    }
    for (int k = 0; k < W; ++k) {
        float enter = 0, leave = float(best_t[k]) * slab_widen;
        slab_axis(b.lo[0], b.hi[0], slabs.ox[k], slabs.ix[k], slab_widen, enter, leave);
        slab_axis(b.lo[1], b.hi[1], slabs.oy[k], slabs.iy[k], slab_widen, enter, leave);
        slab_axis(b.lo[2], b.hi[2], slabs.oz[k], slabs.iz[k], slab_widen, enter, leave);
        mask |= enter <= leave ? std::uint32_t(1) << k : 0;
    }
    return mask;
}

// The near child of inner node n first onto the stack last (so it is
// visited first), judged along direction d.
[[gnu::always_inline]] inline void push_children(const bvh_tree& tree, const bvh_node& n, const float (&d)[3],
                                                 std::uint32_t* stack, int& top) {
    const bvh_node &left = tree.nodes[n.first], &right = tree.nodes[n.first + 1];
    const bvh_box &l = left.box, &r = right.box;
    // Each inner child's own pair of children is one cache line away
    // (build_bvh keeps pairs in one line): asked for now, it is on its way
    // while the child's slab tests run. In a tree bigger than the caches
    // (the 48-million-sphere flake's is 1.3 GB) each level of the walk
    // would otherwise wait for memory.
    if (left.count == 0) __builtin_prefetch(&tree.nodes[left.first]);
    if (right.count == 0) __builtin_prefetch(&tree.nodes[right.first]);
    float towards = 0;  // > 0 when the left child lies further along d
    for (int a = 0; a < 3; ++a) towards += ((l.lo[a] + l.hi[a]) - (r.lo[a] + r.hi[a])) * d[a];
    stack[top++] = towards > 0 ? n.first : n.first + 1;
    stack[top++] = towards > 0 ? n.first + 1 : n.first;
}

// The subtree of node `start` for ray k of the packet alone: its own slab
// tests and near-first order; leaf_one(k, b, e) tests objects [b, e) for it.
template <class T, class LeafOne>
inline void traverse_one_lane(const bvh_tree& tree, std::uint32_t start, int k, const packet_slabs& slabs,
                              const packet<T>& p, const T* best_t, LeafOne&& leaf_one) {
    const float d[3] = {float(p.dx[k]), float(p.dy[k]), float(p.dz[k])};
    std::uint32_t stack[256];
    int top = 0;
    stack[top++] = start;
    while (top > 0) {
        const bvh_node& n = tree.nodes[stack[--top]];
        float enter = 0, leave = float(best_t[k]) * slab_widen;
        slab_axis(n.box.lo[0], n.box.hi[0], slabs.ox[k], slabs.ix[k], slab_widen, enter, leave);
        slab_axis(n.box.lo[1], n.box.hi[1], slabs.oy[k], slabs.iy[k], slab_widen, enter, leave);
        slab_axis(n.box.lo[2], n.box.hi[2], slabs.oz[k], slabs.iz[k], slab_widen, enter, leave);
        if (!(enter <= leave)) continue;
        if (n.count > 0) leaf_one(k, size_t(n.first), size_t(n.first) + n.count);
        else push_children(tree, n, d, stack, top);
    }
}

// Depth-first walk of a tree for the 32 rays of a packet. A node is
// opened when some ray of the packet enters its box before that ray's
// closest hit so far (best_t, updated by the leaves as they run); leaf(b, e)
// tests objects [b, e) for every ray. Children are visited near one first,
// judged along the first ray's direction, so the closest hits come early
// and the far child's box is then often passed by. A node that at most
// packet_hand_off rays enter is left to those rays one by one
// (traverse_one_lane, leaf_one). Either way each ray meets every object
// whose box it enters: the answers do not depend on which walk ran.
template <class T, class Leaf, class LeafOne>
[[gnu::always_inline]] inline void traverse_packet(const bvh_tree& tree, const packet<T>& p, const T* best_t, Leaf&& leaf,
                                                   LeafOne&& leaf_one) {
    if (tree.nodes.empty()) return;
    const packet_slabs slabs(p);
    const float d0[3] = {float(p.dx[0]), float(p.dy[0]), float(p.dz[0])};
    std::uint32_t stack[256];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
        const std::uint32_t index = stack[--top];
        const bvh_node& n = tree.nodes[index];
        std::uint32_t rays = rays_entering(slabs, n.box, best_t);
        if (rays == 0) continue;
        if (__builtin_popcount(rays) <= packet_hand_off) {
            for (; rays != 0; rays &= rays - 1) traverse_one_lane(tree, index, __builtin_ctz(rays), slabs, p, best_t, leaf_one);
            continue;
        }
        if (n.count > 0) leaf(size_t(n.first), size_t(n.first) + n.count);
        else push_children(tree, n, d0, stack, top);
    }
}

// The same walk for one ray that only asks whether anything blocks it:
// blocked(b, e) tests objects [b, e) and the walk stops at the first yes.
template <class T, class Blocked>
[[gnu::always_inline]] inline bool traverse_any(const bvh_tree& tree, const T (&origin)[3], const T (&direction)[3], T tmax, Blocked&& blocked) {
    if (tree.nodes.empty()) return false;
    const float o[3] = {float(origin[0]), float(origin[1]), float(origin[2])};
    const float d[3] = {float(direction[0]), float(direction[1]), float(direction[2])};
    const float inv[3] = {slab_reciprocal(d[0]), slab_reciprocal(d[1]), slab_reciprocal(d[2])};
    const float limit = float(tmax) * slab_widen;
    auto opened = [&](const bvh_box& b) {
        float enter = 0, leave = limit;
        for (int a = 0; a < 3; ++a) slab_axis(b.lo[a], b.hi[a], o[a], inv[a], slab_widen, enter, leave);
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

// A wide node's child on traverse_wide's stack: where the ray enters its box.
struct wide_entry {
    float enter;
    std::uint32_t child, count;
};

// One ray in float, as traverse_wide's slab tests use it.
struct wide_ray {
    float o[3], inv[3];
    bool negative[3];

    template <class T>
    [[gnu::always_inline]] wide_ray(const T (&origin)[3], const T (&direction)[3]) {
        for (int a = 0; a < 3; ++a) {
            o[a] = float(origin[a]);
            inv[a] = slab_reciprocal(float(direction[a]));
            negative[a] = std::signbit(inv[a]);  // -0 too: its reciprocal is -inf
        }
    }

    // The children of n the ray enters before limit, into hit[], sorted
    // farthest first; returns how many. The ray's slab intervals with the
    // four child boxes are computed together. The near side of a slab is
    // the box's low side when the direction component is positive
    // (reciprocal >= 0) and its high side otherwise, so no min/max is
    // needed; an empty slot's box (low +inf, high -inf) then gives entry
    // +inf and exit -inf and is never entered.
    [[gnu::always_inline]] int entered(const bvh_wide_node& n, float limit, wide_entry (&hit)[wide]) const {
        f4 enter = {0, 0, 0, 0}, leave = {limit, limit, limit, limit};
        for (int a = 0; a < 3; ++a) {
            const f4 lo = row(n.lo[a]), hi = row(n.hi[a]);
            const f4 t0 = ((negative[a] ? hi : lo) - o[a]) * inv[a];
            const f4 t1 = ((negative[a] ? lo : hi) - o[a]) * inv[a] * slab_widen;
            enter = t0 > enter ? t0 : enter;  // NaN (the origin on a face plane of a slab
            leave = t1 < leave ? t1 : leave;  // the ray is parallel to) keeps the old value
        }
        const auto in = enter <= leave;
        int h = 0;
        for (int i = 0; i < wide; ++i) {  // at most four: insertion sort
            if (!in[i]) continue;
            const wide_entry c{enter[i], n.child[i], n.count[i]};
            int j = h++;
            for (; j > 0 && hit[j - 1].enter < c.enter; --j) hit[j] = hit[j - 1];
            hit[j] = c;
        }
        return h;
    }
};

// Depth-first walk of a wide tree for one ray, nearest child first. Of the
// children a node's ray enters before its current limit, all but the
// nearest are pushed, farthest first, each with its entry distance, and the
// walk goes on at the nearest without a trip through the stack; a child
// popped later is skipped unopened when the ray has meanwhile found a hit
// nearer than its entry. leaf(first, count) tests a leaf's objects; for
// closest hit (AnyHit false) it updates `best`, the limit; for any hit it
// returns true at a blocker.
template <bool AnyHit, class T, class Leaf>
[[gnu::always_inline]] inline bool traverse_wide(const bvh_wide_tree& tree, const T (&origin)[3], const T (&direction)[3], const T& best,
                   Leaf&& leaf) {
    if (tree.nodes.empty()) return false;
    const wide_ray r(origin, direction);
    // best in float, rounded up a little: never below the true value.
    float limit = float(best) * slab_widen;
    wide_entry stack[512];  // at most wide - 1 per level and the tree is at most ~130 levels deep
    int top = 0;
    wide_entry current{0.0f, 0, 0};  // the root
    for (;;) {
        if (current.count > 0) {
            if constexpr (AnyHit) {
                if (leaf(current.child, current.count)) return true;
            } else {
                leaf(current.child, current.count);
                limit = float(best) * slab_widen;
            }
        } else {
            wide_entry hit[wide];
            const int h = r.entered(tree.nodes[current.child], limit, hit);
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
