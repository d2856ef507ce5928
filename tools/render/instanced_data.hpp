// instanced_data.hpp — the two-level tree's data (instanced_path.cpp builds
// it) and the one-ray, one-shape tests both of its walks use: the one-ray
// walk (instanced_path.cpp: shadow rays, tests) and the packet walk
// (instanced_packets.cpp, compiled once per instruction set). Instructor
// side, private to tools/render: not a header for anyone else.
#pragma once

#include "bvh_build.hpp"
#include "fast_path_kernels.hpp"  // the plane and triangle tests, as the specialised path has them
#include "instanced_path.hpp"

#include <cmath>
#include <cstdint>
#include <vector>

namespace rt::render_tool {

struct sphere_item {
    vec3d center;
    double radius, radius2;
    int material;
};

struct triangle_item {
    vec3d a, e1, e2, b, c;  // corner a and the edges b - a, c - a; b and c for the exact decision
    double flat_scale;       // fast_path_kernels.hpp's bound on the determinant's rounding, over d_max
    int material;
};

// An instance inside an object: where a ray goes to meet it.
struct child_item {
    int object;
    mat3d from_linear;    // parent space -> the placed object's space (the inverse transform)
    vec3d from_offset;
    mat3d normal_matrix;  // the placed object's normals -> parent space: the inverse's transpose
    mat3d to_linear;      // the placed object's points -> parent space (the transform itself)
    vec3d to_offset;
};

struct plane_item {
    vec3d point, unit_normal, normal;  // normal as given, for the exact "parallel" decision
    int material;
};

// A box in double, as the walk tests it (the tree stores float boxes,
// rounded outwards: they still hold everything).
struct box3 {
    vec3d lo{infinity<double>}, hi{-infinity<double>};
    void add(const vec3d& p) { lo = glm::min(lo, p), hi = glm::max(hi, p); }
    void add(const box3& b) { lo = glm::min(lo, b.lo), hi = glm::max(hi, b.hi); }
    bool empty() const { return !(lo.x <= hi.x); }
};

// One object's items and its tree over them: spheres are items
// [0, spheres), triangles follow, then the instances it places.
struct level_object {
    std::vector<sphere_item> spheres;
    std::vector<triangle_item> triangles;
    std::vector<child_item> children;
    std::vector<bvh_box> child_boxes;  // in this object's space, as the tree holds them
    bvh_tree tree;
    box3 bounds;  // of everything in it, in its own space (empty: nothing to hit)
    bool expanded = false;  // its instances expanded into its own shapes (expand_at_most)
    size_t bytes() const {
        return tree.bytes() + spheres.size() * sizeof(sphere_item) + triangles.size() * sizeof(triangle_item) +
               children.size() * sizeof(child_item);
    }
};

struct instanced_scene_data {
    std::vector<level_object> objects;  // the scene's objects, then the top level
    int top = 0;
    std::vector<plane_item> planes;  // in world space: the top level's and those moved out of placed objects
    double build_seconds = 0;
    expanded_counts expanded;
    size_t stored_spheres = 0, stored_triangles = 0, placements = 0;
    size_t expanded_objects = 0;  // placed objects stored expanded in their own space
    std::uint64_t expand_at_most = 0;
};

// ---- the kernels: one ray, one shape ------------------------------------

// The robust sphere test: the perpendicular foot formed before squaring,
// then the stable root pair (as the specialised path's robust kernel). On
// numbers, not vectors, and without a branch (a miss is a select at the
// end), so that the packet walk's loop over its rays (instanced_packets.cpp)
// is vectorised; the one-ray walk calls the same function, so both get the
// same t to the bit. f = o - centre, d the direction, a = d.d, r2 the
// squared radius.
[[gnu::always_inline]] inline double sphere_t(double fx, double fy, double fz, double dx, double dy, double dz,
                                              double a, double r2, double tmin) {
    const double half_b = (fx * dx + fy * dy) + fz * dz;
    const double foot = half_b / a;
    const double gx = fx - foot * dx, gy = fy - foot * dy, gz = fz - foot * dz;
    const double disc = a * (r2 - ((gx * gx + gy * gy) + gz * gz));
    const double q = -(half_b + std::copysign(std::sqrt(disc), half_b));
    const double c = ((fx * fx + fy * fy) + fz * fz) - r2;
    const double root1 = c / q, root2 = q / a;
    const double near = root2 < root1 ? root2 : root1, far = root1 < root2 ? root2 : root1;
    const double t = near > tmin ? near : far;
    return (disc >= 0) & (t > tmin) ? t : infinity<double>;  // NaN from a negative disc: a miss
}

inline double sphere_t(const sphere_item& s, const vec3d& o, const vec3d& d, double a, double tmin) {
    return sphere_t(o.x - s.center.x, o.y - s.center.y, o.z - s.center.z, d.x, d.y, d.z, a, s.radius2, tmin);
}

inline double triangle_hit_t(const triangle_item& x, const vec3d& o, const vec3d& d, double d_max, double tmin) {
    const vec3d s = o - x.a, q = cross(s, x.e1);
    int unsure = 0;
    const double t = triangle_t(s.x, s.y, s.z, q.x, q.y, q.z, x.e1.x, x.e1.y, x.e1.z, x.e2.x, x.e2.y, x.e2.z, d.x, d.y,
                                d.z, tmin, x.flat_scale * d_max + flat_tiny<double>(), unsure);
    if (!unsure) return t;
    return triangle_t_exact(s.x, s.y, s.z, q.x, q.y, q.z, x.e1.x, x.e1.y, x.e1.z, x.e2.x, x.e2.y, x.e2.z, d.x, d.y, d.z,
                            tmin, x.a, x.b, x.c);
}

struct local_hit {
    double t;
    int material = -1;
    vec3d normal{0};  // not normalised: in the space of the object the walk is in
    // The hit point put back on the shape's surface (chapter 09's given
    // on_sphere, on_triangle) in the shape's own space, then carried out
    // through each transform: origin + t d in world space is off the
    // surface by the rounding of t, about eps times the eye's distance,
    // more than chapter 06's shadow offset for a far eye (fast_path.cpp,
    // surface_point). In the space of the object the walk is in.
    vec3d point{0};
};

// The one-ray walk (instanced_path.cpp, walker::closest): the closest hit
// in object o of the ray o + t d with tmin < t < best.t, the ray in o's
// space; true when best was improved (it is then in o's space).
bool closest_one_ray(const instanced_scene_data& d, int o, const vec3d& origin, const vec3d& direction, double tmin,
                     local_hit& best);

// The packet walk (instanced_packets.cpp, the copy for this CPU): the
// closest hit in the scene's trees (planes left out) of each of the 32 rays,
// with tmin < t < out[k].t on entry, as walker::closest finds it for one.
void closest_in_trees_packet(const instanced_scene_data& d, const ray<double>* rays, double tmin, local_hit* out);

}  // namespace rt::render_tool
