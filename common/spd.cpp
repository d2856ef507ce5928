// spd.cpp — the three Standard Procedural Databases (see spd.hpp).
#include "spd.hpp"

#include "big_array.hpp"
#include "render.hpp"  // for_each_row: the project's thread pool

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

namespace rt {

const char* spd_name(spd_database db) {
    switch (db) {
        case spd_database::balls: return "balls";
        case spd_database::tetra: return "tetra";
        case spd_database::mount: return "mount";
    }
    return "?";
}

bool spd_from_name(const std::string& name, spd_database& db) {
    for (auto d : {spd_database::balls, spd_database::tetra, spd_database::mount})
        if (name == spd_name(d)) {
            db = d;
            return true;
        }
    return false;
}

int spd_max_size(spd_database db) {
    switch (db) {
        case spd_database::balls: return 8;   // 48 million spheres
        case spd_database::tetra: return 11;  // 4 million triangles
        case spd_database::mount: return 10;  // 2 million triangles
    }
    return 0;
}

int spd_material_count(spd_database db) { return db == spd_database::tetra ? 1 : 2; }

spd_counts spd_expected_counts(spd_database db, int size) {
    spd_counts c;
    std::uint64_t power = 1;  // 4^size or 9^size, built up below
    switch (db) {
        case spd_database::balls:
            // 1 + 9 + ... + 9^size, summed term by term (no rounding).
            for (int level = 0; level <= size; ++level, power *= 9) c.spheres += power;
            c.planes = 1;
            break;
        case spd_database::tetra:
            for (int i = 0; i < size; ++i) power *= 4;
            c.triangles = power;
            break;
        case spd_database::mount:
            for (int i = 0; i < size; ++i) power *= 4;
            c.triangles = 2 * power;
            c.spheres = 4;
            break;
    }
    return c;
}

namespace {

// Counts what passes through, for the return value of spd_generate.
class counting_sink : public spd_sink {
public:
    explicit counting_sink(spd_sink& out) : out_(out) {}
    void sphere(const vec3d& c, double r, int m) override { ++counts.spheres, out_.sphere(c, r, m); }
    void triangle(const vec3d& a, const vec3d& b, const vec3d& c, int m) override {
        ++counts.triangles, out_.triangle(a, b, c, m);
    }
    void plane(const vec3d& p, const vec3d& n, int m) override { ++counts.planes, out_.plane(p, n, m); }
    spd_counts counts;

private:
    spd_sink& out_;
};

// ---- balls -------------------------------------------------------------

// Two unit vectors across w, so (u, v, w) is a right-handed frame. Any
// choice works; this one avoids the cross product of nearly parallel vectors.
void frame_around(const vec3d& w, vec3d& u, vec3d& v) {
    vec3d helper = std::fabs(w.x) > 0.9 ? vec3d(0, 1, 0) : vec3d(1, 0, 0);
    u = normalize(cross(helper, w));
    v = cross(w, u);
}

// The frame as a matrix: columns u, v, w.
mat3d frame_matrix(const vec3d& w) {
    vec3d u, v;
    frame_around(w, u, v);
    return mat3d(u, v, w);
}

// The nine directions of a sphere's children in its own frame (w: away
// from its parent): six around the equator, 60 degrees apart, and three
// above, between them, at the elevation asin(sqrt(2/3)) = 54.7 degrees.
// Children a third of the parent's radius at these directions touch the
// parent and do not touch each other (the closest pair is 56 degrees
// apart, where 29 would be enough).
std::vector<vec3d> child_directions() {
    const double pi = std::acos(-1.0);
    std::vector<vec3d> dirs;
    for (int k = 0; k < 6; ++k) dirs.emplace_back(std::cos(k * pi / 3), std::sin(k * pi / 3), 0.0);
    double elevation = std::asin(std::sqrt(2.0 / 3.0));
    for (int k = 0; k < 3; ++k) {
        double azimuth = pi / 6 + k * 2 * pi / 3;
        dirs.emplace_back(std::cos(elevation) * std::cos(azimuth), std::cos(elevation) * std::sin(azimuth),
                          std::sin(elevation));
    }
    return dirs;
}

// The root's frame: the one frame_around gives the up direction z.
const mat3d root_frame = frame_matrix(vec3d(0, 0, 1));

// Child k of a sphere, relative to the sphere's own frame: its direction
// and its turn, the child's frame in the parent's frame coordinates. The
// turn is what frame_around gives the root's child, R^T F(R d) (R the
// root's frame, F(w) frame_around's frame for w), and every sphere gives
// its k-th child the same turn. That is what makes every sub-flake an exact
// copy of the whole: a sphere with frame M has children with frames M C_k,
// grandchildren with M C_k C_j, ..., so the sub-flake under it is the whole
// flake turned by M R^T (and scaled, and moved). (Picking each child's frame
// by frame_around from its direction in the world, as this generator did
// before, gives every sphere the same directions but turns the rings of
// grandchildren differently: a sphereflake, but not one made of copies.)
struct child_step {
    vec3d direction;  // in the parent's frame coordinates (a column of the turn: turn[2])
    mat3d turn;
};
std::vector<child_step> child_steps() {
    std::vector<child_step> steps;
    for (const vec3d& d : child_directions()) steps.push_back({d, glm::transpose(root_frame) * frame_matrix(root_frame * d)});
    return steps;
}

// A sphere of the flake and its frame (columns u, v, w; w away from its parent).
struct flake_sphere {
    vec3d center;
    mat3d frame;
    double radius;
};
// A sphere's child: a third of its radius, touching it in the direction
// step.direction of the parent's frame, turned by step.turn.
flake_sphere child_of(const flake_sphere& parent, const child_step& step) {
    const vec3d dir = parent.frame * step.direction;
    const double child_radius = parent.radius / 3;
    return {parent.center + (parent.radius + child_radius) * dir, parent.frame * step.turn, child_radius};
}

// Spheres in a flake `levels` deep: 1 + 9 + ... + 9^levels.
std::uint64_t flake_count(int levels) { return levels < 0 ? 0 : 1 + 9 * flake_count(levels - 1); }

// A sphere and, `levels` deep, its children, depth first: emit(i, sphere)
// with i its place in that order counted from `first` (the k-th child's
// subtree starts at first + 1 + k * flake_count(levels - 1)), so a
// subtree can be generated on its own, anywhere, into its own slots. The
// recursion is only `size` deep (at most 9 calls on the stack); the work is
// in the leaves.
template <class Emit>
void flake(const flake_sphere& s, int levels, std::uint64_t first, const std::vector<child_step>& steps, Emit& emit) {
    emit(first, s);
    if (levels == 0) return;
    const std::uint64_t below = flake_count(levels - 1);
    for (size_t k = 0; k < steps.size(); ++k)
        flake(child_of(s, steps[k]), levels - 1, first + 1 + k * below, steps, emit);
}

// A root sphere of radius 0.5 at the origin resting on the ground z = -0.5.
const flake_sphere flake_root{vec3d(0, 0, 0), root_frame, 0.5};
const vec3d ground_point(0, 0, -0.5), ground_normal(0, 0, 1);

void generate_balls(int size, spd_sink& out) {
    out.plane(ground_point, ground_normal, 0);
    auto emit = [&](std::uint64_t, const flake_sphere& s) { out.sphere(s.center, s.radius, 1); };
    flake(flake_root, size, 0, child_steps(), emit);
}

// The same spheres written straight into spheres[0 .. flake_count(size)),
// on every core: the 81 subtrees two levels down (9^7 spheres each at size
// 8) are one task each. Every sphere is computed by the same arithmetic
// from the same parent as in the serial walk, so the array is the same bit
// for bit whatever the number of threads.
void generate_balls_parallel(int size, sphere<double>* spheres, int material) {
    const std::vector<child_step> steps = child_steps();
    auto write = [&](std::uint64_t i, const flake_sphere& s) { spheres[i] = {s.center, s.radius, material}; };
    const int split = std::min(size, 2);  // levels generated here, above the tasks
    std::vector<std::pair<flake_sphere, std::uint64_t>> tasks;
    auto collect = [&](auto& self, const flake_sphere& s, int depth, std::uint64_t first) -> void {
        if (depth == split) {
            tasks.emplace_back(s, first);
            return;
        }
        write(first, s);
        const std::uint64_t below = flake_count(size - depth - 1);
        for (size_t k = 0; k < steps.size(); ++k) self(self, child_of(s, steps[k]), depth + 1, first + 1 + k * below);
    };
    collect(collect, flake_root, 0, 0);
    for_each_row(int(tasks.size()), [&](int t) {
        flake(tasks[size_t(t)].first, size - split, tasks[size_t(t)].second, steps, write);
    });
}

// ---- tetra -------------------------------------------------------------

// The four faces of the tetrahedron (p0..p3), each wound counter-clockwise
// seen from outside (its normal points away from the opposite corner).
void tetra_faces(const vec3d p[4], spd_sink& out) {
    for (int skip = 0; skip < 4; ++skip) {
        vec3d f[3];
        for (int i = 0, n = 0; i < 4; ++i)
            if (i != skip) f[n++] = p[i];
        if (dot(cross(f[1] - f[0], f[2] - f[0]), f[0] - p[skip]) < 0) std::swap(f[1], f[2]);
        out.triangle(f[0], f[1], f[2], 0);
    }
}

// Replaces a tetrahedron by its four corner tetrahedra of half the size
// (corner i and the midpoints of its three edges); at the last level the
// tetrahedron itself is drawn.
void sierpinski(const vec3d p[4], int levels, spd_sink& out) {
    if (levels == 0) return tetra_faces(p, out);
    for (int corner = 0; corner < 4; ++corner) {
        vec3d q[4];
        for (int i = 0; i < 4; ++i) q[i] = (p[corner] + p[i]) * 0.5;
        sierpinski(q, levels - 1, out);
    }
}

void generate_tetra(int size, spd_sink& out) {
    // A regular tetrahedron (alternate corners of a cube), edge 2*sqrt(2),
    // centred on the origin.
    const vec3d p[4] = {{1, 1, 1}, {-1, -1, 1}, {-1, 1, -1}, {1, -1, -1}};
    sierpinski(p, size - 1, out);
}

// ---- mount -------------------------------------------------------------

// A repeatable pseudo-random number in [-1, 1) for grid point (i, j): the
// same point gets the same displacement however the grid is traversed
// (a hash, not a sequence: SplitMix64's finaliser).
double hash_unit(std::uint64_t i, std::uint64_t j) {
    std::uint64_t z = (i << 32 | j) + 0x9e3779b97f4a7c15ull;
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    z ^= z >> 31;
    return double(z >> 11) * 0x1.0p-52 - 1.0;
}

// Heights on an (n+1) x (n+1) grid, n = 2^size, by midpoint displacement:
// each halving of the step sets the midpoints of the cells' edges and
// centres to the mean of their ends plus a random offset whose amplitude
// shrinks by 2^-H per halving (H = 3 - D for fractal dimension D = 2.2:
// rough, like a mountain).
std::vector<double> mountain_heights(int size) {
    const int n = 1 << size;
    const double H = 0.8;
    std::vector<double> h(size_t(n + 1) * size_t(n + 1), 0.0);
    auto at = [&](int i, int j) -> double& { return h[size_t(i) * size_t(n + 1) + size_t(j)]; };
    double amplitude = 0.6;
    for (int step = n; step > 1; step /= 2, amplitude *= std::pow(2.0, -H)) {
        int half = step / 2;
        auto offset = [&](int i, int j) { return amplitude * hash_unit(std::uint64_t(i), std::uint64_t(j)); };
        for (int i = 0; i < n; i += step)
            for (int j = 0; j < n; j += step) {
                // The first centre is lifted: one peak, not a rough plain.
                double lift = step == n ? 1.0 : 0.0;
                at(i + half, j + half) = (at(i, j) + at(i + step, j) + at(i, j + step) + at(i + step, j + step)) / 4 +
                                         offset(i + half, j + half) + lift;
                at(i + half, j) = (at(i, j) + at(i + step, j)) / 2 + offset(i + half, j);
                at(i, j + half) = (at(i, j) + at(i, j + step)) / 2 + offset(i, j + half);
                if (i + step == n) at(n, j + half) = (at(n, j) + at(n, j + step)) / 2 + offset(n, j + half);
                if (j + step == n) at(i + half, n) = (at(i, n) + at(i + step, n)) / 2 + offset(i + half, n);
            }
    }
    return h;
}

void generate_mount(int size, spd_sink& out) {
    const int n = 1 << size;
    std::vector<double> h = mountain_heights(size);
    // The grid spans [-1, 1] x [-1, 1]; heights are lifted so the corners,
    // which stay at 0, are the foot of the mountain.
    auto point = [&](int i, int j) {
        return vec3d(-1 + 2.0 * i / n, -1 + 2.0 * j / n, std::max(0.0, h[size_t(i) * size_t(n + 1) + size_t(j)]));
    };
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            vec3d a = point(i, j), b = point(i + 1, j), c = point(i + 1, j + 1), d = point(i, j + 1);
            out.triangle(a, b, c, 0);  // counter-clockwise seen from above
            out.triangle(a, c, d, 0);
        }
    // Four spheres floating in front of the mountain (the SPD's glass balls).
    const double spheres[4][4] = {
        {-0.8, -1.25, 0.35, 0.15}, {-0.3, -1.3, 0.45, 0.2}, {0.25, -1.25, 0.4, 0.17}, {0.75, -1.3, 0.3, 0.14}};
    for (const auto& s : spheres) out.sphere(vec3d(s[0], s[1], s[2]), s[3], 1);
}

// Appends to a scene<double>.
class scene_sink : public spd_sink {
public:
    scene_sink(scene<double>& s, const std::vector<int>& materials) : s_(s), m_(materials) {}
    void sphere(const vec3d& c, double r, int m) override { s_.spheres.push_back({c, r, m_.at(size_t(m))}); }
    void triangle(const vec3d& a, const vec3d& b, const vec3d& c, int m) override {
        s_.triangles.push_back({a, b, c, m_.at(size_t(m))});
    }
    void plane(const vec3d& p, const vec3d& n, int m) override { s_.planes.push_back({p, n, m_.at(size_t(m))}); }

private:
    scene<double>& s_;
    const std::vector<int>& m_;
};

// Appends to an object_definition.
class definition_sink : public spd_sink {
public:
    definition_sink(object_definition& d, const std::vector<int>& materials) : d_(d), m_(materials) {}
    void sphere(const vec3d& c, double r, int m) override { d_.spheres.push_back({c, r, m_.at(size_t(m))}); }
    void triangle(const vec3d& a, const vec3d& b, const vec3d& c, int m) override {
        d_.triangles.push_back({a, b, c, m_.at(size_t(m))});
    }
    void plane(const vec3d& p, const vec3d& n, int m) override { d_.planes.push_back({p, n, m_.at(size_t(m))}); }

private:
    object_definition& d_;
    const std::vector<int>& m_;
};

// ---- instanced ---------------------------------------------------------

instance_placement placement(int object, const affine_transform& to_parent, const std::string& field) {
    return {object, to_parent, inverted(to_parent), field};
}

// Level L of the flake: the root sphere (radius 0.5 at the origin, as
// generate_balls makes it) and nine copies of level L - 1. Child k is the
// whole turned so that the root's frame R becomes the k-th child's frame
// R C_k (child_steps: R C_k R^T, turning about the origin), scaled by 1/3
// and moved out to touch the root: centre at (0.5 + 0.5 / 3) R d_k. So
// placed, the copy's spheres are generate_balls' spheres under that child,
// to rounding (tests/scenes/instanced_render_test.cpp compares them).
void instanced_balls(int size, object_definition& into, std::vector<object_definition>& objects,
                     const std::vector<int>& materials) {
    int below = -1;
    for (int level = 0; level <= size; ++level) {
        object_definition d;
        d.name = "generate (balls, level " + std::to_string(level) + ")";
        d.spheres.push_back({vec3d(0), 0.5, materials.at(1)});
        if (below >= 0)
            for (const child_step& step : child_steps()) {
                const affine_transform child{root_frame * step.turn * glm::transpose(root_frame) * (1.0 / 3.0),
                                             (0.5 + 0.5 / 3.0) * (root_frame * step.direction)};
                d.instances.push_back(placement(below, child, d.name));
            }
        objects.push_back(std::move(d));
        below = int(objects.size()) - 1;
    }
    into.planes.push_back({vec3d(0, 0, -0.5), vec3d(0, 0, 1), materials.at(0)});
    into.instances.push_back(placement(below, affine_transform{}, "generate (balls)"));
}

// Level L of the tetrahedron: four copies of level L - 1 at half the size,
// each moved towards its corner (corner c's copy: p -> (p + p_c) / 2, the
// map sierpinski() applies to the corners); level 0 is its four faces.
void instanced_tetra(int size, object_definition& into, std::vector<object_definition>& objects,
                     const std::vector<int>& materials) {
    const vec3d p[4] = {{1, 1, 1}, {-1, -1, 1}, {-1, 1, -1}, {1, -1, -1}};  // as generate_tetra
    object_definition faces;
    faces.name = "generate (tetra, level 0)";
    definition_sink sink(faces, materials);
    tetra_faces(p, sink);
    objects.push_back(std::move(faces));
    int below = int(objects.size()) - 1;
    for (int level = 1; level < size; ++level) {
        object_definition d;
        d.name = "generate (tetra, level " + std::to_string(level) + ")";
        for (const vec3d& corner : p)
            d.instances.push_back(placement(below, affine_transform{mat3d(0.5), 0.5 * corner}, d.name));
        objects.push_back(std::move(d));
        below = int(objects.size()) - 1;
    }
    into.instances.push_back(placement(below, affine_transform{}, "generate (tetra)"));
}

}  // namespace

int spd_max_instanced_size(spd_database db) {
    switch (db) {
        case spd_database::balls: return 12;  // 3.2e12 spheres; the smallest radius 0.5 / 3^12 = 9.4e-7
        case spd_database::tetra: return 16;  // 4.3e9 triangles
        case spd_database::mount: return 0;
    }
    return 0;
}

spd_counts spd_generate_instanced(spd_database db, int size, object_definition& into,
                                  std::vector<object_definition>& objects, const std::vector<int>& materials) {
    if (spd_max_instanced_size(db) == 0)
        throw std::invalid_argument(std::string("spd: ") + spd_name(db) + " is not self-similar: it has no instanced form");
    if (size < 1 || size > spd_max_instanced_size(db))
        throw std::invalid_argument(std::string("spd: instanced ") + spd_name(db) + " takes a size from 1 to " +
                                    std::to_string(spd_max_instanced_size(db)) + ", got " + std::to_string(size));
    if (db == spd_database::balls) instanced_balls(size, into, objects, materials);
    else instanced_tetra(size, into, objects, materials);
    return spd_expected_counts(db, size);
}

spd_counts spd_generate(spd_database db, int size, scene<double>& into, const std::vector<int>& materials) {
    if (db == spd_database::balls && size >= 1 && size <= spd_max_size(db)) {
        // 48 million spheres at size 8: generated on every core, in place.
        const size_t first = into.spheres.size();
        const int ground = materials.at(0), flake_material = materials.at(1);
        into.planes.push_back({ground_point, ground_normal, ground});
        // 1.9 GB at size 8: in 2 MB pages, mapped with 3,000 faults, not 500,000 (big_array.hpp).
        into.spheres.reserve(first + flake_count(size));
        advise_huge_pages(into.spheres.data() + first, flake_count(size) * sizeof(sphere<double>));
        into.spheres.resize(first + flake_count(size));
        generate_balls_parallel(size, into.spheres.data() + first, flake_material);
        return spd_expected_counts(db, size);
    }
    if (size >= 1 && size <= spd_max_size(db)) {  // else the call below throws
        spd_counts expected = spd_expected_counts(db, size);
        into.spheres.reserve(into.spheres.size() + expected.spheres);
        into.triangles.reserve(into.triangles.size() + expected.triangles);
    }
    scene_sink sink(into, materials);
    return spd_generate(db, size, sink);
}

spd_counts spd_generate(spd_database db, int size, spd_sink& out) {
    if (size < 1 || size > spd_max_size(db))
        throw std::invalid_argument(std::string("spd: ") + spd_name(db) + " takes a size from 1 to " +
                                    std::to_string(spd_max_size(db)) + ", got " + std::to_string(size));
    counting_sink counted(out);
    switch (db) {
        case spd_database::balls: generate_balls(size, counted); break;
        case spd_database::tetra: generate_tetra(size, counted); break;
        case spd_database::mount: generate_mount(size, counted); break;
    }
    return counted.counts;
}

}  // namespace rt
