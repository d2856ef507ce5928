// fast_path_traversal.hpp — part of fast_path.cpp (see fast_path_arrays.hpp):
// the walks through the 8-wide trees. The slab test's float arithmetic, one
// ray's walk (closest or any hit), and a packet's walk, which hands a box
// that few of its rays enter to those rays one at a time.
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
// are not there. (rt-bench --trees-only, three runs each in turn, avx2
// copy, 4 December 2026: on a million random spheres 2 gave 273-284 ns per
// ray, 4 gave 259-277 and 6 gave 261-277; on the tetra 59-62, 56-64 and
// 54-57. The one-ray walk's leaves had just become cheaper, which moved
// the best threshold up from 2.)
constexpr int packet_hand_off = 4;

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

// Eight floats, one per child of a wide node: gcc's vector extension, which
// each copy of this file compiles for its own instruction set (two SSE
// registers in the baseline copy, one AVX register in the others).
// A row is loaded into a vector the caller holds, not returned: the
// baseline copy, without AVX, passes a returned 32-byte vector otherwise
// than the AVX copies do (gcc's -Wpsabi).
typedef float fw __attribute__((vector_size(4 * wide)));

[[gnu::always_inline]] inline void load_row(fw& v, const float (&r)[wide]) { std::memcpy(&v, r, sizeof v); }

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

    // Ray k of a packet, from the float origin and reciprocals its slabs
    // already hold (the same numbers: packet_slabs computes them alike).
    [[gnu::always_inline]] wide_ray(const packet_slabs& slabs, int k)
        : o{slabs.ox[k], slabs.oy[k], slabs.oz[k]}, inv{slabs.ix[k], slabs.iy[k], slabs.iz[k]} {
        for (int a = 0; a < 3; ++a) negative[a] = std::signbit(inv[a]);
    }

    // The children of n the ray enters before limit, into hit[], sorted
    // farthest first; returns how many. The ray's slab intervals with the
    // eight child boxes are computed together. The near side of a slab is
    // the box's low side when the direction component is positive
    // (reciprocal >= 0) and its high side otherwise, so no min/max is
    // needed; an empty slot's box (low +inf, high -inf) then gives entry
    // +inf and exit -inf and is never entered.
    [[gnu::always_inline]] int entered(const bvh_wide_node& n, float limit, wide_entry (&hit)[wide]) const {
        fw enter = fw{}, leave = fw{} + limit;
        for (int a = 0; a < 3; ++a) {
            fw lo, hi;
            load_row(lo, n.lo[a]), load_row(hi, n.hi[a]);
            const fw t0 = ((negative[a] ? hi : lo) - o[a]) * inv[a];
            const fw t1 = ((negative[a] ? lo : hi) - o[a]) * inv[a] * slab_widen;
            enter = t0 > enter ? t0 : enter;  // NaN (the origin on a face plane of a slab
            leave = t1 < leave ? t1 : leave;  // the ray is parallel to) keeps the old value
        }
        const auto in = enter <= leave;
        int h = 0;
        for (int i = 0; i < wide; ++i) {  // at most eight: insertion sort
            if (!in[i]) continue;
            const wide_entry c{enter[i], n.child[i], n.count[i]};
            int j = h++;
            for (; j > 0 && hit[j - 1].enter < c.enter; --j) hit[j] = hit[j - 1];
            hit[j] = c;
        }
        return h;
    }
};

// The walks' stacks: a node's children but the one walked next wait there,
// at most wide - 1 a level, over at most bvh_max_depth levels, plus the
// root (traverse_packet pushes it).
constexpr size_t wide_walk_stack = 1024;
static_assert((wide - 1) * bvh_max_depth + 1 <= wide_walk_stack, "a walk's stack holds the deepest tree's");

// Depth-first walk of a wide tree for one ray, nearest child first. Of the
// children a node's ray enters before its current limit, all but the
// nearest are pushed, farthest first, each with its entry distance, and the
// walk goes on at the nearest without a trip through the stack; a child
// popped later is skipped unopened when the ray has meanwhile found a hit
// nearer than its entry. leaf(first, count) tests a leaf's objects; for
// closest hit (AnyHit false) it updates `best`, the limit; for any hit it
// returns true at a blocker. `start` is where the walk begins: the root,
// or a child of a node that a packet's walk hands to this ray alone.
template <bool AnyHit, class T, class Leaf>
[[gnu::always_inline]] inline bool traverse_wide(const bvh_wide_tree& tree, const wide_ray& r, const T& best, Leaf&& leaf,
                                                 wide_entry start = wide_entry{0.0f, 0, 0}) {
    if (tree.nodes.empty()) return false;
    // best in float, rounded up a little: never below the true value.
    float limit = float(best) * slab_widen;
    wide_entry stack[wide_walk_stack];
    int top = 0;
    wide_entry current = start;
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

// The same for a ray given by its origin and direction.
template <bool AnyHit, class T, class Leaf>
[[gnu::always_inline]] inline bool traverse_wide(const bvh_wide_tree& tree, const T (&origin)[3], const T (&direction)[3],
                                                 const T& best, Leaf&& leaf) {
    return traverse_wide<AnyHit>(tree, wide_ray(origin, direction), best, leaf);
}

// A child of a wide node on traverse_packet's stack, with the rays of the
// packet that enter its box (a bit each).
struct packet_entry {
    std::uint32_t child, count, rays;
};

// The children of wide node n that some of `rays` enter (rays_entering),
// onto the stack farthest first, so the nearest is walked next: the order
// of their boxes' centres along d. An inner child's node is asked for now
// (all four of its cache lines), so it is on its way while the rest is tested.
template <class T>
[[gnu::always_inline]] inline void push_entered_children(const bvh_wide_tree& tree, const bvh_wide_node& n,
                                                         const packet_slabs& slabs, const T* best_t, std::uint32_t rays,
                                                         const float (&d)[3], packet_entry* stack, int& top) {
    packet_entry entered[wide];
    float along[wide];  // the box centre's distance along d, doubled
    int h = 0;
    for (int i = 0; i < wide; ++i) {
        if (n.count[i] == bvh_wide_node::empty_slot) continue;
        const bvh_box b{{n.lo[0][i], n.lo[1][i], n.lo[2][i]}, {n.hi[0][i], n.hi[1][i], n.hi[2][i]}};
        const std::uint32_t in = rays_entering(slabs, b, best_t) & rays;
        if (in == 0) continue;
        if (n.count[i] == 0) {
            const char* node = reinterpret_cast<const char*>(&tree.nodes[n.child[i]]);
            for (size_t line = 0; line < sizeof(bvh_wide_node); line += 64) __builtin_prefetch(node + line);
        }
        float x = 0;
        for (int a = 0; a < 3; ++a) x += (b.lo[a] + b.hi[a]) * d[a];
        int j = h++;  // at most eight: insertion sort, farthest first
        for (; j > 0 && along[j - 1] < x; --j) entered[j] = entered[j - 1], along[j] = along[j - 1];
        entered[j] = packet_entry{n.child[i], n.count[i], in}, along[j] = x;
    }
    for (int i = 0; i < h; ++i) stack[top++] = entered[i];
}

// Depth-first walk of a wide tree for the 32 rays of a packet. A node's
// eight child boxes are tested for every ray (rays_entering, against each
// ray's closest hit so far, best_t, which the leaves update as they run);
// the children some ray enters are pushed, the nearest last so that it is
// walked first, judged by the boxes' centres along the first ray's
// direction. leaf(b, e) tests objects [b, e) for every ray. A child that
// at most packet_hand_off rays enter is left to those rays one by one
// (traverse_wide from that child, leaf_one(k, b, e) for ray k). Either way
// each ray meets every object whose box it enters: the answers do not
// depend on which walk ran.
//
// Why eight children, not two: in a tree bigger than the caches each level
// is a trip to memory, and eight children per node take a third of the
// levels. On the level-8 sphereflake (48 million spheres, a tree of depth
// 35 and 1.2-1.4 GB) the binary walk's primary rays took 305 ns each and
// the walk of four children 233 (3 Dec 2026); eight gave 11.96-12.45
// Mrays/s against four's 10.23-10.26 (6 Dec 2026; rt-bench --flake-only,
// the binaries run in turn; tools/bench/README.md).
template <class T, class Leaf, class LeafOne>
[[gnu::always_inline]] inline void traverse_packet(const bvh_wide_tree& tree, const packet<T>& p, const T* best_t, Leaf&& leaf,
                                                   LeafOne&& leaf_one) {
    if (tree.nodes.empty()) return;
    const packet_slabs slabs(p);
    const float d0[3] = {float(p.dx[0]), float(p.dy[0]), float(p.dz[0])};
    packet_entry stack[wide_walk_stack];
    int top = 0;
    stack[top++] = packet_entry{0, 0, ~std::uint32_t(0)};  // the root, for every ray
    while (top > 0) {
        const packet_entry e = stack[--top];
        if (__builtin_popcount(e.rays) <= packet_hand_off) {
            for (std::uint32_t rays = e.rays; rays != 0; rays &= rays - 1) {
                const int k = __builtin_ctz(rays);
                traverse_wide<false>(
                    tree, wide_ray(slabs, k), best_t[k],
                    [&](std::uint32_t b, std::uint32_t n) { leaf_one(k, size_t(b), size_t(b) + n); },
                    wide_entry{0.0f, e.child, e.count});
            }
            continue;
        }
        if (e.count > 0) {
            leaf(size_t(e.child), size_t(e.child) + e.count);
            continue;
        }
        push_entered_children(tree, tree.nodes[e.child], slabs, best_t, e.rays, d0, stack, top);
    }
}
