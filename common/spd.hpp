// spd.hpp — Eric Haines' Standard Procedural Databases, generated.
//
// The SPD (IEEE CG&A, November 1987) are scenes defined by a program and a
// size, so that ray tracers can be compared on the same data at any scale.
// Three of them are generated here, written from their published
// descriptions (not from the SPD's code):
//
//   balls  the "sphereflake": a sphere with nine spheres a third its size
//          touching it (six around its equator, three above), each of them
//          with nine of its own, `size` levels deep, on a ground plane.
//          Spheres: 1 + 9 + 81 + ... + 9^size = (9^(size+1) - 1) / 8
//          (size 4: 7,381, the SPD's default; size 8: 48,427,561).
//   tetra  a Sierpinski tetrahedron: a tetrahedron replaced by its four
//          corner tetrahedra of half the size, recursively; the last level
//          is drawn as four triangles each. Triangles: 4^size (size 6: 4,096).
//   mount  a fractal mountain: a square of two triangles subdivided `size`
//          times by midpoint displacement, with four spheres floating in
//          front of it. Triangles: 2 * 4^size (size 6: 8,192), spheres: 4.
//
// The SPD's own figures at the default sizes (balls 7,382 primitives =
// 7,381 spheres + 1 ground polygon; tetra 4,096; mount 8,196) are what
// tests/scenes/spd_test.cpp checks the generators against.
//
// Scenes this large are generated, never stored, and may not fit twice in
// memory (48 million spheres are 1.9 GB in double): so the generator hands
// every shape to a `spd_sink` as it makes it, and the caller stores it in
// whatever form it renders from (a float structure-of-arrays, say).
// Data only: nothing here intersects anything. Coordinates are z-up, as in
// the SPD.
#pragma once

#include "instances.hpp"
#include "math.hpp"
#include "scene.hpp"

#include <cstdint>
#include <string>

namespace rt {

enum class spd_database { balls, tetra, mount };

// How many shapes of each kind a database has at a size.
struct spd_counts {
    std::uint64_t spheres = 0, triangles = 0, planes = 0;
    std::uint64_t total() const { return spheres + triangles + planes; }
};

// Receives the shapes, in the order they are generated. `material` is the
// database's own numbering (0 .. spd_material_count - 1): balls 0 ground,
// 1 spheres; tetra 0; mount 0 mountain, 1 spheres.
class spd_sink {
public:
    virtual ~spd_sink() = default;
    virtual void sphere(const vec3d& center, double radius, int material) = 0;
    virtual void triangle(const vec3d& a, const vec3d& b, const vec3d& c, int material) = 0;
    virtual void plane(const vec3d& point, const vec3d& normal, int material) = 0;
};

// The database's name ("balls", "tetra", "mount") and back; false for an
// unknown name.
const char* spd_name(spd_database db);
bool spd_from_name(const std::string& name, spd_database& db);

// Sizes accepted: 1 .. spd_max_size (balls 8, tetra 11, mount 10; larger
// would not fit in memory on a 24 GB machine, or in a float's precision).
int spd_max_size(spd_database db);
int spd_material_count(spd_database db);

// The counts by the formulas above (no generation).
spd_counts spd_expected_counts(spd_database db, int size);

// Generates the database at `size` into `out`; returns what it generated.
// Throws std::invalid_argument for a size out of range.
spd_counts spd_generate(spd_database db, int size, spd_sink& out);

// The same, appended to a scene's shapes (memory reserved up front), with
// material m of the database mapped to materials[m] of the scene.
spd_counts spd_generate(spd_database db, int size, scene<double>& into, const std::vector<int>& materials);

// ---- the self-similar databases as instances of instances ----------------
//
// A sphereflake of level L is a sphere and nine copies of the flake of level
// L - 1, each a third of the size; a Sierpinski tetrahedron of level L is
// four copies of level L - 1 at half the size. Stored that way (one object
// per level: a sphere and nine instances, or four instances), the level-10
// sphereflake's 3,922,632,451 spheres take eleven spheres and 90 instances.
//
// Both are the flat ones', to rounding: the flat flake gives every
// sphere's k-th child the same turn relative to its parent's frame, so each
// of its sub-flakes is an exact copy of the whole, as instances are. The two
// generators compose the same turns in another order, so a sphere's centre
// and radius differ by rounding only; the bound, and the test that checks it
// sphere by sphere and hit by hit: tests/scenes/instanced_render_test.cpp.
int spd_max_instanced_size(spd_database db);  // balls 12, tetra 16, mount 0 (not self-similar)

// Appends the levels' objects to `objects` and, to `into`, what the flat
// database has at its top besides the fractal (the ground plane of balls)
// and one instance (identity) of the whole; returns the counts of the
// expanded database. Throws std::invalid_argument for a size out of range
// or a database that is not self-similar.
spd_counts spd_generate_instanced(spd_database db, int size, object_definition& into,
                                  std::vector<object_definition>& objects, const std::vector<int>& materials);

}  // namespace rt
