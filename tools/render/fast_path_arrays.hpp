// fast_path_arrays.hpp — part of fast_path.cpp: the packet of rays and the
// scene as structure-of-arrays, with its trees.
//
// The parts of fast_path.cpp (fast_path_arrays, _traversal, _spheres,
// _planes, _triangles, _queries) are not headers for anyone else: each is
// included once, by fast_path.cpp, after its instruction-set pragma and
// inside that copy's namespace, and includes nothing itself. (A library
// header first included after the pragma would have its inline functions
// compiled for AVX in one copy, and the linker could keep that one for all.)
// The lane loops are always_inline: in one function with the packet's
// arrays, the compiler sees that the closest hits written by a loop cannot
// be the packet or the scene it reads, and vectorises without run-time
// alias checks (out of line, the same loops measured slower).
#pragma once
#ifndef RT_FAST_PATH_PARTS
#error "a part of fast_path.cpp: included by it, after its headers and its target pragma"
#endif

constexpr int W = packet_width;
constexpr int tile_w = 8, tile_h = W / tile_w;  // the pixels of one packet
static_assert(tile_w * tile_h == W, "a packet is a whole tile");

// The sphere formulation a kernel is compiled for (chapter 07's plain or
// robust quadratic): the one choice about the objects made at compile time.
enum class sphere_mode { plain, robust };

// A tree's leaf holds at most 8 objects (build_bvh's max_leaf); one ray
// tests them as one group of 8 lanes (a vector of 8 floats), like a shadow
// ray tests brute force's groups.
constexpr int leaf_lanes = 8;

// Object numbers in the same width as T, so a select on (t, object) pairs
// stays within one kind of vector lane.
template <class T>
using index_t = std::conditional_t<sizeof(T) == 4, std::int32_t, std::int64_t>;

// The rays through one tile of 8 x 4 pixels: lane k is pixel (k % 8, k / 8).
template <class T>
struct packet {
    alignas(64) T ox[W], oy[W], oz[W], dx[W], dy[W], dz[W];
};

// What each ray of a packet has found so far, and the terms of its
// direction every kernel uses: a = |d|^2, 1/a, and d_max (direction_max:
// infinite for a direction the triangle lanes must leave to their exact
// path). A local object of closest_hits, so the compiler may keep it in
// registers for the whole object loop; copied out at the end.
template <class T>
struct packet_best {
    using I = index_t<T>;
    alignas(64) T a[W], inv_a[W], d_max[W], t[W];
    alignas(64) I object[W];  // -1: nothing hit yet

    explicit packet_best(const packet<T>& p) {
        for (int k = 0; k < W; ++k) {
            a[k] = p.dx[k] * p.dx[k] + p.dy[k] * p.dy[k] + p.dz[k] * p.dz[k];
            inv_a[k] = T(1) / a[k];
            d_max[k] = direction_max(p.dx[k], p.dy[k], p.dz[k]);
            t[k] = infinity<T>;
            object[k] = -1;
        }
    }

    // Only hits before tmax[k] count (a shadow ray's light): as if each ray
    // had already found something there, with no number (-1).
    void limit(const T* tmax) {
        for (int k = 0; k < W; ++k) t[k] = tmax[k];
    }

    // Ray k hits object id at t: kept if nearer than what it has, or, with
    // Ties, as near and of a lower number. Brute force meets the objects in
    // the order of their numbers, so the nearer rule alone keeps the lowest
    // number at a tie; a tree meets them in its own order and asks for Ties
    // (the numbers it passes are then the scene's own, soa_scene::sphere_number
    // and triangle_number),
    // so the tree and brute force return the same object (chapter 08's rule).
    template <bool Ties = false>
    [[gnu::always_inline]] void keep(int k, T t_new, I id) {
        const T old_t = t[k];
        const I old = object[k];
        const bool closer = Ties ? (t_new < old_t) | ((t_new == old_t) & (id < old)) : t_new < old_t;
        t[k] = closer ? t_new : old_t;
        // The object number is selected with a mask, not with ?: : gcc 12
        // turns "closer ? id : object[k]" into a conditional store, which it
        // vectorises with a test and a branch that mispredicts all the time.
        const I mask = -I(closer);
        object[k] = (old & ~mask) | (id & mask);
    }
};

// One shadow ray and its direction's terms, as the any-hit loops use them.
template <class T>
struct shadow_ray {
    T ox, oy, oz, dx, dy, dz, a, inv_a, d_max;
    T origin[3], direction[3];

    explicit shadow_ray(const ray<T>& r)
        : ox(r.origin.x), oy(r.origin.y), oz(r.origin.z), dx(r.direction.x), dy(r.direction.y), dz(r.direction.z),
          a(dx * dx + dy * dy + dz * dz), inv_a(T(1) / a), d_max(direction_max(dx, dy, dz)), origin{ox, oy, oz},
          direction{dx, dy, dz} {}
};

// A shadow ray tests brute force's objects shadow_group at a time (here the
// lanes are objects), stopping at the first group with a blocker: one
// vector register of floats; larger groups would spend their lanes on the
// NaN padding in small scenes.
constexpr int shadow_group = 8;
static_assert(W % shadow_group == 0, "the arrays are padded to a multiple of W, so also of shadow_group");
inline size_t shadow_groups(size_t n) { return (n + shadow_group - 1) / shadow_group * shadow_group; }

template <class T>
struct soa_scene {
    size_t sphere_count = 0, plane_count = 0, triangle_count = 0;
    // Each array is padded to a multiple of W with NaN entries, which never
    // hit, so the shadow-ray loop can run over whole groups of W objects.
    // (big_vector: 48 million spheres are four arrays of 200-400 MB, each
    // sized once and written in place on every core, common/big_array.hpp.)
    big_vector<T> cx, cy, cz, radius;
    big_vector<T> px, py, pz, nx, ny, nz;  // planes: a point and the unit normal
    big_vector<T> ax, ay, az, e1x, e1y, e1z, e2x, e2y, e2z;  // triangles: corner a, edges b-a, c-a
    big_vector<T> bx, by, bz, br2;  // a sphere around each triangle (radius squared), to skip it cheaply
    // How much every box is widened (build_trees) and every cull sphere too:
    // 1e-6 of the scene's magnitude.
    double box_pad = 0;

    // With a tree, spheres and triangles are stored in the trees' leaf
    // order, so a leaf is a contiguous range of the arrays; sphere_number(i)
    // and triangle_number(j) are then the scene's own numbers of stored
    // sphere i and triangle j, and closest_hits answers with those numbers.
    bool tree = false;
    //
    // Spheres and triangles each get an 8-wide tree (bvh_build.hpp), walked
    // by a whole packet (traverse_packet), which hands the boxes that few of
    // its rays enter to those rays one at a time; shadow rays walk it one
    // at a time (traverse_wide).
    bvh_wide_tree sphere_tree;
    bvh_wide_tree triangle_tree;
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
    // sets how much the boxes are widened (see build_trees below).
    soa_scene(const scene<double>& s, bool use_tree, double magnitude) : box_pad(1e-6 * magnitude), tree(use_tree) {
        sphere_count = s.spheres.size();
        plane_count = s.planes.size();
        triangle_count = s.triangles.size();
        source_triangles = &s.triangles;
        source_planes = &s.planes;
        if (tree) build_trees(s);
        for (auto* v : {&cx, &cy, &cz, &radius}) v->reserve(padded(sphere_count));
        for (auto* v : {&px, &py, &pz, &nx, &ny, &nz}) v->reserve(padded(plane_count));
        for (auto* v : {&ax, &ay, &az, &e1x, &e1y, &e1z, &e2x, &e2y, &e2z, &bx, &by, &bz, &br2})
            v->reserve(padded(triangle_count));
        add_spheres(s.spheres);
        for (const auto& x : s.planes) add_plane(x);
        for (size_t j = 0; j < triangle_count; ++j) add_triangle(s.triangles[tree ? triangle_tree.order[j] : j]);
        for (auto* v : {&cx, &cy, &cz, &radius, &px, &py, &pz, &nx, &ny, &nz, &ax, &ay, &az, &e1x, &e1y,
                        &e1z, &e2x, &e2y, &e2z, &bx, &by, &bz, &br2})
            v->resize(padded(v->size()), std::numeric_limits<T>::quiet_NaN());
    }

    // The length of an array of n objects with its NaN padding: at least
    // leaf_lanes entries (a tree's leaf is tested leaf_lanes objects at a
    // time, past its end; those lanes are dropped), up to a multiple of W.
    static size_t padded(size_t n) { return (n + size_t(leaf_lanes) + W - 1) / W * W; }

    // The spheres in leaf order (or the scene's), on every core, each slot
    // written once, by one thread.
    void add_spheres(const std::vector<sphere<double>>& spheres) {
        for (auto* v : {&cx, &cy, &cz, &radius}) v->resize(sphere_count);
        for_each_chunk(sphere_count, [&](size_t j) {
            const sphere<double>& x = spheres[tree ? sphere_tree.order[j] : j];
            cx[j] = T(x.center.x), cy[j] = T(x.center.y), cz[j] = T(x.center.z);
            radius[j] = T(x.radius);
        });
    }

    // Sphere i's radius squared, in T. Formed where it is used rather than
    // stored: one multiplication against a fifth array to stream through
    // (400 MB in double for 48 million spheres).
    T radius_squared(size_t i) const { return radius[i] * radius[i]; }

    // f(i) for every i in [0, n), in a few contiguous chunks per thread.
    template <class F>
    static void for_each_chunk(size_t n, F&& f) {
        const int chunks = n < 65536 ? 1 : 8 * render_threads();
        for_each_row(chunks, [&](int c) {
            const size_t from = n * size_t(c) / size_t(chunks), to = n * size_t(c + 1) / size_t(chunks);
            for (size_t i = from; i < to; ++i) f(i);
        });
    }

    // Scaled by a power of two first (exact), so that normalize's squares
    // neither underflow nor overflow: a normal of any finite non-zero length
    // gives the unit normal to within rounding.
    static vec3d unit_normal(const plane<double>& x) {
        const int k = formulations::direction_scale(x.normal);
        return normalize(vec3d(std::ldexp(x.normal.x, k), std::ldexp(x.normal.y, k), std::ldexp(x.normal.z, k)));
    }

    void add_plane(const plane<double>& x) {
        const vec3d n = unit_normal(x);
        px.push_back(T(x.point.x)), py.push_back(T(x.point.y)), pz.push_back(T(x.point.z));
        nx.push_back(T(n.x)), ny.push_back(T(n.y)), nz.push_back(T(n.z));
    }

    void add_triangle(const triangle<double>& x) {
        // Edges from the corners rounded to T, as the general path sees them.
        vec3<T> a = convert<T>(x.a), e1 = convert<T>(x.b) - a, e2 = convert<T>(x.c) - a;
        ax.push_back(a.x), ay.push_back(a.y), az.push_back(a.z);
        e1x.push_back(e1.x), e1y.push_back(e1.y), e1z.push_back(e1.z);
        e2x.push_back(e2.x), e2y.push_back(e2.y), e2z.push_back(e2.z);
        // The cull sphere (triangle_near_packet): centred on the centroid,
        // through the farthest corner, made 1% larger and then widened by the
        // boxes' padding (build_trees), which covers the rounding of this
        // centre to T and lets through every ray the tree's padded boxes let
        // through. Stored squared and times 1.02: the slack the cull's own
        // rounding bound takes (cull_radius2).
        const vec3d centre = (x.a + x.b + x.c) / 3.0;
        const double r = 1.01 * std::max({length(x.a - centre), length(x.b - centre), length(x.c - centre)}) + box_pad;
        bx.push_back(T(centre.x)), by.push_back(T(centre.y)), bz.push_back(T(centre.z));
        br2.push_back(std::nextafter(T(1.02 * 1.01 * r * r), infinity<T>));
    }

    // The scene's number of stored sphere i and of stored triangle j (the
    // scene numbers spheres, then planes, then triangles; with a tree each
    // kind is stored in its tree's leaf order, which order[] undoes).
    std::int64_t sphere_number(size_t i) const { return std::int64_t(tree ? sphere_tree.order[i] : i); }
    std::int64_t triangle_number(size_t j) const {
        return std::int64_t(sphere_count + plane_count) + std::int64_t(tree ? triangle_tree.order[j] : j);
    }

    // Float boxes that hold each object as the kernels see it, whatever the
    // rounding: the exact box, rounded outwards to float, widened by
    // box_pad, 1e-6 of the scene's magnitude (float's own rounding of a coordinate
    // or of a ray's origin and direction is 6e-8 of it). A box test in
    // float can then only let through too much, never drop a hit, so the
    // tree gives the same closest object and t as brute force.
    void build_trees(const scene<double>& s) {
        sphere_tree = collapse_to_wide(build_bvh(s.spheres.size(), [&](size_t i) {
            const auto& x = s.spheres[i];
            return float_box_around(x.center - vec3d(x.radius), x.center + vec3d(x.radius), box_pad);
        }));
        triangle_tree = collapse_to_wide(build_bvh(s.triangles.size(), [&](size_t i) {
            const auto& x = s.triangles[i];
            return float_box_around(glm::min(x.a, glm::min(x.b, x.c)), glm::max(x.a, glm::max(x.b, x.c)), box_pad);
        }));
    }
};
