// instanced_packets.cpp — the two-level tree walked by a packet of 32 rays
// (the primary rays of a tile of 8 x 4 pixels) at once, for the closest hit.
//
// The one-ray walk (instanced_path.cpp, walker::closest) spends most of
// its time on box tests and sphere tests, one ray at a time, in double.
// Here the same tests run on the 32 rays of a packet in one loop over the
// lanes, which the compiler turns into vector instructions (this file is
// compiled once per instruction set, as fast_path.cpp is; isa_target.hpp).
// The walk is the specialised path's packet walk (fast_path_traversal.hpp,
// traverse_packet) with one step added: a leaf's instance moves all 32
// rays into the placed object's space, by the inverse transform, and the
// walk goes on there with the same closest t per ray. The direction is not
// normalised, so t means the same point in both spaces (chapter 10): the
// packet's closest t carries over, in and out, unchanged.
//
// Every ray gets the same answer as from the one-ray walk, to the bit: each
// lane does the one-ray walk's arithmetic in the same order (a sphere's t,
// a ray moved by a transform, a hit point put back on its surface, a normal
// brought back out), and contraction is off. Only the order in which boxes
// are visited differs, and that decides nothing but speed: a box is a
// cull, and the closest t wins whatever the order. (At an exact tie of t
// between two shapes the one met first is kept, on both walks, so there the
// material may differ.) tests/scenes (instanced packets) compares the two.
//
// Which rays are worth 32 lanes: a box is opened when any ray of the packet
// enters it before its closest hit so far, and then its contents are
// tested against all 32 rays. A ray that does not enter the box cannot hit
// what is inside it, so testing it too costs time but never changes its
// answer. Coherent rays (a tile of primary rays) mostly open the same
// boxes; shadow rays go one at a time, on the one-ray walk.
#include "instanced_data.hpp"

#include "09-reflection/surface_error.hpp"  // hit points put back on their surfaces

#include <cstdint>
#include <limits>

#include "isa_target.hpp"  // last: no header may follow it

namespace rt::render_tool::RT_FAST_ISA {

namespace {

constexpr int W = packet_width;

// An instance whose box at most this many rays of the packet enter is
// walked by those rays one at a time (walk_one_by_one) instead of by the
// whole packet: deep in a tree of instances, where the boxes are small, a
// packet's 32 lanes would mostly work for rays that are not there.
constexpr int one_by_one = 4;

// The rays of a packet in the space of the object the walk is in.
struct ray_packet {
    alignas(64) double ox[W], oy[W], oz[W], dx[W], dy[W], dz[W];
};

// What each ray has found so far. t is shared by every level of the walk
// (it means the same in every space); the rest (material, normal, point)
// is in the space of the object whose walk last wrote it, and is brought
// out one level each time an instance's walk returns (object_walk::visit_instances).
struct packet_hits {
    alignas(64) double t[W];
    int material[W];
    vec3d normal[W], point[W];
};

// Lane k's bit.
constexpr std::uint32_t bit(int k) { return std::uint32_t(1) << k; }

// The packet's slab tests, in double, with chapter 08's rule (slab_axis in
// fast_path_kernels.hpp), the exit widened as the one-ray walk's.
struct packet_slabs {
    alignas(64) double ox[W], oy[W], oz[W], ix[W], iy[W], iz[W];

    explicit packet_slabs(const ray_packet& p) {
        for (int k = 0; k < W; ++k) {
            ox[k] = p.ox[k], oy[k] = p.oy[k], oz[k] = p.oz[k];
            ix[k] = 1 / p.dx[k], iy[k] = 1 / p.dy[k], iz[k] = 1 / p.dz[k];
        }
    }

    static constexpr double widen = 1 + 8 * std::numeric_limits<double>::epsilon();

    // Which rays k enter box b between 0 and their closest hit so far (a bit each).
    [[gnu::always_inline]] std::uint32_t entering(const bvh_box& b, const double* best_t) const {
        std::uint32_t mask = 0;
        for (int k = 0; k < W; ++k) {
            double enter = 0, leave = best_t[k];
            slab_axis(double(b.lo[0]), double(b.hi[0]), ox[k], ix[k], widen, enter, leave);
            slab_axis(double(b.lo[1]), double(b.hi[1]), oy[k], iy[k], widen, enter, leave);
            slab_axis(double(b.lo[2]), double(b.hi[2]), oz[k], iz[k], widen, enter, leave);
            mask |= enter <= leave ? bit(k) : 0;
        }
        return mask;
    }
};

// The walk of one object's tree. Items are numbered as level_object holds
// them: spheres, then triangles, then the instances it places. The items of
// this object that give a ray its closest hit are remembered by number
// (own[k], -1 for none, or for a hit found inside an instance), and their
// hit points and normals are worked out once, when the walk of the object
// ends, for the rays they are still the closest hit of.
class object_walk {
public:
    object_walk(const instanced_scene_data& d, int o, const ray_packet& p, double tmin, packet_hits& hits)
        : d_(d), level_(d.objects[size_t(o)]), p_(p), slabs_(p), tmin_(tmin), hits_(hits) {
        for (int k = 0; k < W; ++k) {
            a_[k] = (p.dx[k] * p.dx[k] + p.dy[k] * p.dy[k]) + p.dz[k] * p.dz[k];  // dot(d, d), in its order
            own_[k] = -1;
            t_on_entry_[k] = hits.t[k];
        }
    }

    // Walks the tree (the root's box tested first when test_root: an
    // instance's box was already tested in its parent's space) and returns
    // the rays whose closest hit is now in this object, with their hits
    // written in this object's space.
    std::uint32_t run(bool test_root) {
        const bvh_tree& tree = level_.tree;
        if (tree.nodes.empty()) return 0;
        if (test_root && slabs_.entering(tree.nodes[0].box, hits_.t) == 0) return 0;
        walk_tree();
        return finish();
    }

private:
    void walk_tree() {
        const bvh_tree& tree = level_.tree;
        const double d0[3] = {p_.dx[0], p_.dy[0], p_.dz[0]};  // the packet's first ray judges near and far
        std::uint32_t stack[bvh_binary_walk_stack];
        int top = 0;
        const bvh_node& root = tree.nodes[0];
        if (root.count > 0) leaf(root);
        else push_children(root, d0, stack, top);
        while (top > 0) {
            const bvh_node& n = tree.nodes[stack[--top]];
            if (slabs_.entering(n.box, hits_.t) == 0) continue;
            if (n.count > 0) leaf(n);
            else push_children(n, d0, stack, top);
        }
    }

    // The far child first onto the stack, so the near one is visited first.
    void push_children(const bvh_node& n, const double (&d0)[3], std::uint32_t* stack, int& top) const {
        const bvh_box &l = level_.tree.nodes[n.first].box, &r = level_.tree.nodes[n.first + 1].box;
        double towards = 0;  // > 0 when the left child lies further along d0
        for (int a = 0; a < 3; ++a) towards += ((double(l.lo[a]) + l.hi[a]) - (double(r.lo[a]) + r.hi[a])) * d0[a];
        stack[top++] = towards > 0 ? n.first : n.first + 1;
        stack[top++] = towards > 0 ? n.first + 1 : n.first;
    }

    void leaf(const bvh_node& n) {
        const size_t spheres = level_.spheres.size(), triangles = level_.triangles.size();
        std::uint32_t placed[16];  // the leaf's instances (a leaf holds at most 8 items)
        int placed_count = 0;
        std::uint32_t entering = 0;
        bool entering_known = false;
        for (std::uint32_t k = n.first; k < n.first + n.count; ++k) {
            const size_t item = level_.tree.order[k];
            if (item < spheres) {
                sphere_lanes(item);
            } else if (item < spheres + triangles) {
                if (!entering_known) entering = slabs_.entering(n.box, hits_.t), entering_known = true;
                triangle_lanes(item, entering);
            } else {
                placed[placed_count++] = std::uint32_t(item - spheres - triangles);
            }
        }
        if (placed_count > 0) visit_instances(placed, placed_count);
    }

    // One sphere against the 32 rays: the one-ray walk's sphere_t
    // (instanced_data.hpp) in every lane.
    [[gnu::always_inline]] void sphere_lanes(size_t item) {
        sphere_lanes(level_.spheres[item], std::int64_t(item), p_, a_, tmin_, hits_.t, own_);
    }
    // The lane loop on its own, its arrays marked as not overlapping: the
    // compiler must otherwise assume that writing a t could change the rays.
    [[gnu::always_inline]] static void sphere_lanes(const sphere_item& s, std::int64_t id, const ray_packet& __restrict p,
                                                    const double* __restrict a, double tmin, double* __restrict best_t,
                                                    std::int64_t* __restrict own) {
        const double cx = s.center.x, cy = s.center.y, cz = s.center.z, r2 = s.radius2;
        for (int k = 0; k < W; ++k) {
            const double t = sphere_t(p.ox[k] - cx, p.oy[k] - cy, p.oz[k] - cz, p.dx[k], p.dy[k], p.dz[k], a[k], r2, tmin);
            const bool closer = t < best_t[k];
            best_t[k] = closer ? t : best_t[k];
            const std::int64_t mask = -std::int64_t(closer);  // a select, not a branch (fast_path_arrays.hpp, keep)
            own[k] = (own[k] & ~mask) | (id & mask);
        }
    }

    // One triangle against the rays that entered its leaf's box, one at a time.
    void triangle_lanes(size_t item, std::uint32_t rays) {
        const triangle_item& x = level_.triangles[item - level_.spheres.size()];
        for (; rays != 0; rays &= rays - 1) {
            const int k = __builtin_ctz(rays);
            const vec3d o(p_.ox[k], p_.oy[k], p_.oz[k]), d(p_.dx[k], p_.dy[k], p_.dz[k]);
            const double t = triangle_hit_t(x, o, d, direction_max(d.x, d.y, d.z), tmin_);
            if (t < hits_.t[k]) hits_.t[k] = t, own_[k] = std::int64_t(item);
        }
    }

    // A leaf's instances, nearest first along the first ray (so the closest
    // t shrinks early and the farther ones are often passed by unopened):
    // each whose box some ray enters is walked with the rays moved into its
    // space, and the hits found there are brought back out.
    void visit_instances(std::uint32_t* placed, int count) {
        const double d0[3] = {p_.dx[0], p_.dy[0], p_.dz[0]};
        double key[16];
        for (int i = 0; i < count; ++i) {
            const bvh_box& b = level_.child_boxes[placed[i]];
            key[i] = 0;
            for (int a = 0; a < 3; ++a) key[i] += (double(b.lo[a]) + b.hi[a]) * d0[a];
        }
        for (int i = 1; i < count; ++i)  // insertion sort: a leaf holds a handful
            for (int j = i; j > 0 && key[j - 1] > key[j]; --j) std::swap(key[j - 1], key[j]), std::swap(placed[j - 1], placed[j]);
        for (int i = 0; i < count; ++i) {
            const std::uint32_t rays = slabs_.entering(level_.child_boxes[placed[i]], hits_.t);
            if (rays == 0) continue;
            const child_item& c = level_.children[placed[i]];
            std::uint32_t found = 0;
            if (__builtin_popcount(rays) <= one_by_one) {
                found = walk_one_by_one(c, rays);
            } else {
                const ray_packet inside = moved(p_, c.from_linear, c.from_offset);
                found = object_walk(d_, c.object, inside, tmin_, hits_).run(false);
            }
            for (; found != 0; found &= found - 1) {
                const int k = __builtin_ctz(found);
                hits_.normal[k] = c.normal_matrix * hits_.normal[k];
                hits_.point[k] = c.to_linear * hits_.point[k] + c.to_offset;
                own_[k] = -1;  // the closest hit is the instance's now, written out
            }
        }
    }

    // The rays of the mask that enter an instance's box, each on the one-ray
    // walk (instanced_path.cpp), which moves it into the instance's space as
    // moved() does: the same answer, and none of the other lanes' work.
    // Returns the rays whose closest hit is now in the instance.
    std::uint32_t walk_one_by_one(const child_item& c, std::uint32_t rays) {
        std::uint32_t found = 0;
        for (; rays != 0; rays &= rays - 1) {
            const int k = __builtin_ctz(rays);
            const vec3d o(p_.ox[k], p_.oy[k], p_.oz[k]), d(p_.dx[k], p_.dy[k], p_.dz[k]);
            local_hit best{hits_.t[k]};
            if (!closest_one_ray(d_, c.object, c.from_linear * o + c.from_offset, c.from_linear * d, tmin_, best))
                continue;
            hits_.t[k] = best.t, hits_.material[k] = best.material, hits_.normal[k] = best.normal;
            hits_.point[k] = best.point;
            found |= bit(k);
        }
        return found;
    }

    // The rays moved by m x + offset (origins) and m d (directions), in
    // glm's order of operations (mat3 * vec3, then + offset), as the one-ray
    // walk moves its ray.
    static ray_packet moved(const ray_packet& p, const mat3d& matrix, const vec3d& offset) {
        // The matrix and offset in locals first: out is written in the
        // loop, and might otherwise overlap them.
        double m[3][3];
        for (int c = 0; c < 3; ++c)
            for (int r = 0; r < 3; ++r) m[c][r] = matrix[c][r];
        const double tx = offset.x, ty = offset.y, tz = offset.z;
        ray_packet out;
        for (int k = 0; k < W; ++k) {
            out.ox[k] = ((m[0][0] * p.ox[k] + m[1][0] * p.oy[k]) + m[2][0] * p.oz[k]) + tx;
            out.oy[k] = ((m[0][1] * p.ox[k] + m[1][1] * p.oy[k]) + m[2][1] * p.oz[k]) + ty;
            out.oz[k] = ((m[0][2] * p.ox[k] + m[1][2] * p.oy[k]) + m[2][2] * p.oz[k]) + tz;
            out.dx[k] = (m[0][0] * p.dx[k] + m[1][0] * p.dy[k]) + m[2][0] * p.dz[k];
            out.dy[k] = (m[0][1] * p.dx[k] + m[1][1] * p.dy[k]) + m[2][1] * p.dz[k];
            out.dz[k] = (m[0][2] * p.dx[k] + m[1][2] * p.dy[k]) + m[2][2] * p.dz[k];
        }
        return out;
    }

    // The hits of this object's own shapes, written out as walker::closest
    // writes them; returns the rays whose closest hit is now in this object.
    std::uint32_t finish() {
        std::uint32_t found = 0;
        const size_t spheres = level_.spheres.size();
        for (int k = 0; k < W; ++k) {
            if (hits_.t[k] < t_on_entry_[k]) found |= bit(k);
            if (own_[k] < 0) continue;
            const vec3d o(p_.ox[k], p_.oy[k], p_.oz[k]), d(p_.dx[k], p_.dy[k], p_.dz[k]);
            const double t = hits_.t[k];
            if (size_t(own_[k]) < spheres) {
                const sphere_item& s = level_.spheres[size_t(own_[k])];
                const vec3d on = ch09::on_sphere(sphere<double>{s.center, s.radius}, o + t * d).point;
                hits_.material[k] = s.material, hits_.normal[k] = (on - s.center) / s.radius, hits_.point[k] = on;
            } else {
                const triangle_item& x = level_.triangles[size_t(own_[k]) - spheres];
                const vec3d normal = cross(x.e1, x.e2);
                hits_.material[k] = x.material, hits_.normal[k] = dot(normal, d) > 0 ? -normal : normal;
                hits_.point[k] = ch09::on_triangle(triangle<double>{x.a, x.b, x.c}, o + t * d).point;
            }
        }
        return found;
    }

    const instanced_scene_data& d_;
    const level_object& level_;
    const ray_packet& p_;
    const packet_slabs slabs_;
    const double tmin_;
    packet_hits& hits_;
    alignas(64) double a_[W];
    alignas(64) std::int64_t own_[W];
    alignas(64) double t_on_entry_[W];
};

}  // namespace

void closest_in_trees_packet(const instanced_scene_data& d, const ray<double>* rays, double tmin, local_hit* out) {
    ray_packet p;
    packet_hits hits;
    for (int k = 0; k < W; ++k) {
        p.ox[k] = rays[k].origin.x, p.oy[k] = rays[k].origin.y, p.oz[k] = rays[k].origin.z;
        p.dx[k] = rays[k].direction.x, p.dy[k] = rays[k].direction.y, p.dz[k] = rays[k].direction.z;
        hits.t[k] = out[k].t;
    }
    const std::uint32_t found = object_walk(d, d.top, p, tmin, hits).run(true);
    for (int k = 0; k < W; ++k)
        if (found & bit(k)) out[k] = {hits.t[k], hits.material[k], hits.normal[k], hits.point[k]};
}

}  // namespace rt::render_tool::RT_FAST_ISA
