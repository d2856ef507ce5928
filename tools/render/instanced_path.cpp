// instanced_path.cpp — the two-level tree and its walk (see instanced_path.hpp).
#include "instanced_path.hpp"
#include "instanced_data.hpp"

#include "bvh_build.hpp"
#include "fast_path_kernels.hpp"  // the plane and triangle tests, as the specialised path has them
#include "look.hpp"

#include "06-shading/shading.hpp"  // chapter 06's shade(), for lit scenes
#include "09-reflection/surface_error.hpp"  // hit points put back on their surfaces
#include "common/render.hpp"
#include "common/timing.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <functional>
#include <stdexcept>

namespace rt::render_tool {

namespace {

vec3d apply(const affine_transform& t, const vec3d& p) { return t.linear * p + t.offset; }

// A box rounded outwards to float and widened by 1e-7 of its largest
// coordinate: the corners of a placed object's box are transformed with
// rounding, and so is the ray that meets it; the padding is far above both
// (double's rounding is 1e-16 of the coordinates) and below any visible size.
bvh_box to_float_box(const box3& b) {
    double magnitude = 0;
    for (int a = 0; a < 3; ++a) magnitude = std::max({magnitude, std::fabs(b.lo[a]), std::fabs(b.hi[a])});
    return float_box_around(b.lo, b.hi, 1e-7 * magnitude);
}

box3 of(const bvh_box& b) {
    box3 out;
    out.lo = vec3d(b.lo[0], b.lo[1], b.lo[2]);
    out.hi = vec3d(b.hi[0], b.hi[1], b.hi[2]);
    return out;
}

// The box of a placed object in its parent's space: its eight corners
// transformed (an affine map sends the box to a parallelepiped inside the
// corners' box), then widened by to_float_box.
box3 placed_box(const box3& b, const affine_transform& to_parent) {
    box3 out;
    for (int corner = 0; corner < 8; ++corner)
        out.add(apply(to_parent, vec3d(corner & 1 ? b.hi.x : b.lo.x, corner & 2 ? b.hi.y : b.lo.y,
                                       corner & 4 ? b.hi.z : b.lo.z)));
    return out;
}

triangle_item triangle_of(const triangle<double>& x) {
    triangle_item t;
    t.a = x.a, t.b = x.b, t.c = x.c;
    t.e1 = x.b - x.a, t.e2 = x.c - x.a;
    t.flat_scale = flat_scale(t.e1.x, t.e1.y, t.e1.z, t.e2.x, t.e2.y, t.e2.z);
    t.material = x.material;
    return t;
}

void flatten_into(const std::vector<object_definition>& defs, const object_definition& def,
                  const affine_transform& to_world, scene<double>& out);

// Builds object o's level (its children first), once. A placed object
// that expands to at most expand_at_most spheres and triangles is stored
// expanded, in its own space, in one tree (see instanced_scene's
// constructor); its spheres must be placed by similarities inside it (else
// it stays instanced). The top level never is.
void build_level(const std::vector<object_definition>& defs, const std::vector<expanded_counts>& counts, int o, int top,
                 std::uint64_t expand_at_most, const object_definition& given, std::vector<level_object>& levels,
                 std::vector<bool>& built) {
    if (built[size_t(o)]) return;
    level_object& level = levels[size_t(o)];
    object_definition expanded;
    const bool small = o != top && !given.instances.empty() &&
                       counts[size_t(o)].spheres + counts[size_t(o)].triangles <= expand_at_most;
    if (small) {
        scene<double> shapes;
        try {
            flatten_into(defs, given, affine_transform{}, shapes);
            expanded.spheres = std::move(shapes.spheres);
            expanded.triangles = std::move(shapes.triangles);
            level.expanded = true;
        } catch (const std::invalid_argument&) {  // an ellipsoid inside: keep the instances
        }
    }
    const object_definition& def = level.expanded ? expanded : given;
    std::vector<bvh_box> boxes;
    for (const auto& s : def.spheres) {
        level.spheres.push_back({s.center, s.radius, s.radius * s.radius, s.material});
        box3 b;
        b.add(s.center - vec3d(s.radius));
        b.add(s.center + vec3d(s.radius));
        level.bounds.add(b);
        boxes.push_back(to_float_box(b));
    }
    for (const auto& t : def.triangles) {
        level.triangles.push_back(triangle_of(t));
        box3 b;
        b.add(t.a), b.add(t.b), b.add(t.c);
        level.bounds.add(b);
        boxes.push_back(to_float_box(b));
    }
    for (const auto& i : def.instances) {
        build_level(defs, counts, i.object, top, expand_at_most, defs[size_t(i.object)], levels, built);
        const level_object& placed = levels[size_t(i.object)];
        if (placed.bounds.empty()) continue;  // nothing to hit in it
        const box3 b = of(to_float_box(placed_box(placed.bounds, i.to_parent)));
        level.children.push_back({i.object, i.from_parent.linear, i.from_parent.offset,
                                  glm::transpose(i.from_parent.linear), i.to_parent.linear, i.to_parent.offset});
        level.bounds.add(b);
        boxes.push_back(to_float_box(b));
        level.child_boxes.push_back(boxes.back());
    }
    if (!boxes.empty()) level.tree = build_bvh(boxes);
    built[size_t(o)] = true;
}

// Planes of placed objects, moved to world space for every way they are
// placed; only objects that hold planes somewhere are walked (the level-10
// flake has 9^10 ways to place its smallest object, and no plane in it).
void hoist_planes(const std::vector<object_definition>& defs, const std::vector<expanded_counts>& counts,
                  const object_definition& def, const affine_transform& to_world, std::vector<plane_item>& out) {
    const mat3d normals = glm::transpose(inverted(to_world).linear);
    for (const auto& p : def.planes) {
        const vec3d n = normals * p.normal;
        out.push_back({apply(to_world, p.point), normalize(n), n, p.material});
        if (out.size() > 10000)
            throw std::invalid_argument("instances place more than 10000 planes: planes are unbounded and tested "
                                        "one by one; put them at the top level");
    }
    for (const auto& i : def.instances)
        if (counts[size_t(i.object)].planes > 0)
            hoist_planes(defs, counts, defs[size_t(i.object)], then(i.to_parent, to_world), out);
}

double plane_hit_t(const plane_item& p, const vec3d& o, const vec3d& d, double tmin) {
    const vec3d n = p.unit_normal;
    const double num = dot(n, p.point - o);
    int unsure = 0;
    const double t = rt::render_tool::plane_t(num, n.x, n.y, n.z, d.x, d.y, d.z, tmin, unsure);
    return unsure ? plane_t_exact(num, n.x, n.y, n.z, d.x, d.y, d.z, tmin, p.normal) : t;
}

// ---- the walk -----------------------------------------------------------

// The ray as the slab tests use it: chapter 08's rule (slab_axis in
// fast_path_kernels.hpp), the exit widened by a few ulps.
struct slab_ray {
    vec3d o, inv;
    slab_ray(const vec3d& origin, const vec3d& d) : o(origin), inv(1 / d.x, 1 / d.y, 1 / d.z) {}
    // Where the ray enters the box within (tmin, tmax), or infinity when it
    // does not meet it there.
    double entry(const bvh_box& b, double tmin, double tmax) const {
        constexpr double widen = 1 + 8 * std::numeric_limits<double>::epsilon();
        double enter = tmin, leave = tmax;
        for (int a = 0; a < 3; ++a) slab_axis(double(b.lo[a]), double(b.hi[a]), o[a], inv[a], widen, enter, leave);
        return enter <= leave ? enter : infinity<double>;
    }
};

// A node or an instance waiting to be visited, with where the ray enters its box.
struct waiting {
    std::uint32_t index;
    double entry;
};

class walker {
public:
    explicit walker(const instanced_scene_data& d) : d_(d) {}

    // The closest hit in object o with tmin < t < best.t; true when best was
    // improved. Near first: of a node's two children the one the ray enters
    // first is visited first, and so are the instances of a leaf, so that
    // best.t shrinks early and the farther boxes (a sub-flake behind a
    // nearer one) are skipped without moving the ray into their space. An
    // instance's box (in this object's space, widened) is tested before the
    // ray is moved into its space: most of a leaf's instances are missed.
    // The root's box is not tested when test_root is false: an instance's
    // box, tested in its parent's space, already holds it.
    bool closest(int o, const vec3d& org, const vec3d& dir, double tmin, local_hit& best, bool test_root = true) const {
        const level_object& level = d_.objects[size_t(o)];
        if (level.tree.nodes.empty()) return false;
        const slab_ray slabs(org, dir);
        const double a = dot(dir, dir);
        const size_t spheres = level.spheres.size(), triangles = level.triangles.size();
        const double d_max = triangles > 0 ? direction_max(dir.x, dir.y, dir.z) : 0;  // only triangles use it
        bool found = false;
        waiting stack[bvh_binary_walk_stack];
        int top = 0;
        const double root = test_root ? slabs.entry(level.tree.nodes[0].box, tmin, best.t) : tmin;
        if (root < best.t) stack[top++] = {0, root};
        while (top > 0) {
            const waiting w = stack[--top];
            if (!(w.entry < best.t)) continue;  // best.t shrank since it was pushed
            const bvh_node& n = level.tree.nodes[w.index];
            if (n.count == 0) {
                const double left = slabs.entry(level.tree.nodes[n.first].box, tmin, best.t);
                const double right = slabs.entry(level.tree.nodes[n.first + 1].box, tmin, best.t);
                const waiting l{n.first, left}, r{n.first + 1, right};
                const waiting& near = left <= right ? l : r;
                const waiting& far = left <= right ? r : l;
                if (far.entry < best.t) stack[top++] = far;
                if (near.entry < best.t) stack[top++] = near;
                continue;
            }
            waiting placed[16];  // the leaf's instances the ray enters (a leaf holds at most 8 items)
            int placed_count = 0;
            for (std::uint32_t k = n.first; k < n.first + n.count; ++k) {
                const size_t item = level.tree.order[k];
                if (item < spheres) {
                    const sphere_item& s = level.spheres[item];
                    const double t = sphere_t(s, org, dir, a, tmin);
                    if (t < best.t) {
                        const vec3d on = ch09::on_sphere(sphere<double>{s.center, s.radius}, org + t * dir).point;
                        best = {t, s.material, (on - s.center) / s.radius, on};
                        found = true;
                    }
                } else if (item < spheres + triangles) {
                    const triangle_item& x = level.triangles[item - spheres];
                    const double t = triangle_hit_t(x, org, dir, d_max, tmin);
                    if (t < best.t) {
                        const vec3d normal = cross(x.e1, x.e2);
                        const vec3d on = ch09::on_triangle(triangle<double>{x.a, x.b, x.c}, org + t * dir).point;
                        best = {t, x.material, dot(normal, dir) > 0 ? -normal : normal, on};
                        found = true;
                    }
                } else {
                    const std::uint32_t c = std::uint32_t(item - spheres - triangles);
                    const double entry = slabs.entry(level.child_boxes[c], tmin, best.t);
                    if (entry < best.t) {
                        // Insertion by entry: a leaf holds a handful of items.
                        int at = placed_count++;
                        for (; at > 0 && placed[at - 1].entry > entry; --at) placed[at] = placed[at - 1];
                        placed[at] = {c, entry};
                    }
                }
            }
            for (int k = 0; k < placed_count; ++k) {
                if (!(placed[k].entry < best.t)) break;  // this one and the rest lie beyond the closest hit
                // Into the placed object's space: the direction is not
                // normalised, so t (and best.t, the range's end) mean
                // the same point there.
                const child_item& c = level.children[placed[k].index];
                local_hit inside = best;
                if (closest(c.object, c.from_linear * org + c.from_offset, c.from_linear * dir, tmin, inside, false)) {
                    best = {inside.t, inside.material, c.normal_matrix * inside.normal,
                            c.to_linear * inside.point + c.to_offset};
                    found = true;
                }
            }
        }
        return found;
    }

    // Is anything in object o hit with tmin < t < tmax? (Any order will do;
    // instances whose box the ray misses are not entered.)
    bool blocked(int o, const vec3d& org, const vec3d& dir, double tmin, double tmax) const {
        const level_object& level = d_.objects[size_t(o)];
        if (level.tree.nodes.empty()) return false;
        const slab_ray slabs(org, dir);
        const double a = dot(dir, dir), d_max = direction_max(dir.x, dir.y, dir.z);
        const size_t spheres = level.spheres.size(), triangles = level.triangles.size();
        std::uint32_t stack[bvh_binary_walk_stack];
        int top = 0;
        stack[top++] = 0;
        while (top > 0) {
            const bvh_node& n = level.tree.nodes[stack[--top]];
            if (!(slabs.entry(n.box, tmin, tmax) < tmax)) continue;
            if (n.count == 0) {
                stack[top++] = n.first + 1;
                stack[top++] = n.first;
                continue;
            }
            for (std::uint32_t k = n.first; k < n.first + n.count; ++k) {
                const size_t item = level.tree.order[k];
                if (item < spheres) {
                    if (sphere_t(level.spheres[item], org, dir, a, tmin) < tmax) return true;
                } else if (item < spheres + triangles) {
                    if (triangle_hit_t(level.triangles[item - spheres], org, dir, d_max, tmin) < tmax) return true;
                } else {
                    const size_t ci = item - spheres - triangles;
                    if (!(slabs.entry(level.child_boxes[ci], tmin, tmax) < tmax)) continue;
                    const child_item& c = level.children[ci];
                    if (blocked(c.object, c.from_linear * org + c.from_offset, c.from_linear * dir, tmin, tmax))
                        return true;
                }
            }
        }
        return false;
    }

private:
    const instanced_scene_data& d_;
};

}  // namespace

instanced_scene::instanced_scene(const scene_description& scene, std::uint64_t expand_at_most)
    : data_(std::make_unique<instanced_scene_data>()) {
    const stopwatch clock;
    instanced_scene_data& d = *data_;
    // The top level is one more object: the world's spheres and triangles and its instances.
    std::vector<object_definition> defs = scene.objects;
    object_definition top;
    top.name = scene.source;
    top.spheres = scene.world.spheres;
    top.triangles = scene.world.triangles;
    top.instances = scene.instances;
    defs.push_back(std::move(top));
    d.top = int(defs.size()) - 1;
    d.objects.resize(defs.size());
    std::vector<bool> built(defs.size(), false);
    const std::vector<expanded_counts> counts = expanded_counts_of(defs);
    build_level(defs, counts, d.top, d.top, expand_at_most, defs[size_t(d.top)], d.objects, built);
    for (const auto& p : scene.world.planes)
        d.planes.push_back({p.point, normalize(p.normal), p.normal, p.material});
    hoist_planes(defs, counts, object_definition{"", {}, {}, {}, scene.instances}, affine_transform{}, d.planes);
    d.expanded = counts[size_t(d.top)];
    d.expanded.planes = scene.world.planes.size() + (d.planes.size() - scene.world.planes.size());
    for (size_t o = 0; o < defs.size(); ++o) {
        if (!built[o]) continue;
        d.stored_spheres += d.objects[o].spheres.size();
        d.stored_triangles += d.objects[o].triangles.size();
        d.placements += d.objects[o].children.size();
        d.expanded_objects += d.objects[o].expanded;
    }
    d.expand_at_most = expand_at_most;
    d.build_seconds = clock.seconds();
}

instanced_scene::~instanced_scene() = default;
instanced_scene::instanced_scene(instanced_scene&&) noexcept = default;

std::vector<instanced_scene::placed_box> instanced_scene::top_instance_boxes() const {
    std::vector<placed_box> out;
    for (const bvh_box& b : data_->objects[size_t(data_->top)].child_boxes)
        out.push_back({vec3d(b.lo[0], b.lo[1], b.lo[2]), vec3d(b.hi[0], b.hi[1], b.hi[2])});
    return out;
}

double instanced_scene::build_seconds() const { return data_->build_seconds; }

size_t instanced_scene::bytes() const {
    size_t b = data_->planes.size() * sizeof(plane_item);
    for (const auto& o : data_->objects) b += o.bytes();
    return b;
}

std::string instanced_scene::describe() const {
    const instanced_scene_data& d = *data_;
    size_t used = 0;
    for (const auto& o : d.objects) used += !o.tree.nodes.empty();
    char line[800];
    std::snprintf(line, sizeof line,
                  "two-level tree (instances): %zu objects, each with its own tree, %zu instances in them (instances of "
                  "instances); expanded: %llu spheres, %llu triangles, %llu planes; stored: %zu spheres, %zu "
                  "triangles (%zu placed objects of at most %llu shapes stored expanded in their own space); %.3f MB "
                  "of trees and shapes, built in %.1f ms; double, robust sphere test, rays moved into each "
                  "instance's space, nearest instance first; primary rays in packets of 32 (%s), shadow rays one "
                  "at a time",
                  used, d.placements, (unsigned long long)d.expanded.spheres, (unsigned long long)d.expanded.triangles,
                  (unsigned long long)d.expanded.planes, d.stored_spheres, d.stored_triangles, d.expanded_objects,
                  (unsigned long long)d.expand_at_most, double(bytes()) / 1e6, d.build_seconds * 1e3, fast_path_isa());
    return line;
}

bool closest_one_ray(const instanced_scene_data& d, int o, const vec3d& origin, const vec3d& direction, double tmin,
                     local_hit& best) {
    return walker(d).closest(o, origin, direction, tmin, best, false);
}

namespace {

// The closest hit of one ray in the trees (best) and then among the planes,
// which are in no tree, as the scene's hit.
instanced_scene::hit with_planes(const instanced_scene_data& d, const ray<double>& r, double tmin, local_hit best) {
    const plane_item* plane = nullptr;
    for (const auto& p : d.planes) {
        const double t = plane_hit_t(p, r.origin, r.direction, tmin);
        if (t < best.t) {
            best = {t, p.material, dot(p.unit_normal, r.direction) > 0 ? -p.unit_normal : p.unit_normal,
                    ch09::on_plane_through(p.point, p.unit_normal, r.origin + t * r.direction).point};
            plane = &p;
        }
    }
    instanced_scene::hit h;
    if (best.material < 0) return h;
    if (plane) h.plane_normal = plane->normal;  // the planes come last: the closest hit is this plane's
    h.t = best.t;
    h.material = best.material;
    h.normal = normalize(best.normal);
    h.point = best.point;
    return h;
}

}  // namespace

instanced_scene::hit instanced_scene::closest(const ray<double>& r, double tmin, double tmax) const {
    const instanced_scene_data& d = *data_;
    local_hit best{tmax};
    walker(d).closest(d.top, r.origin, r.direction, tmin, best);
    return with_planes(d, r, tmin, best);
}

void instanced_scene::closest(const ray<double> (&rays)[packet_width], double tmin, double tmax,
                              hit (&out)[packet_width]) const {
    const instanced_scene_data& d = *data_;
    local_hit best[packet_width];
    for (local_hit& b : best) b.t = tmax;
    closest_in_trees_packet(d, rays, tmin, best);
    for (int k = 0; k < packet_width; ++k) out[k] = with_planes(d, rays[k], tmin, best[k]);
}

bool instanced_scene::blocked(const ray<double>& r, double tmin, double tmax) const {
    const instanced_scene_data& d = *data_;
    for (const auto& p : d.planes)
        if (plane_hit_t(p, r.origin, r.direction, tmin) < tmax) return true;
    return walker(d).blocked(d.top, r.origin, r.direction, tmin, tmax);
}

namespace {

// Primary rays go in packets: the pixels of a tile of 8 x 4, walked
// together (instanced_packets.cpp). tile(row0, col0, body) finds the
// closest hits of the tile whose top-left pixel is (col0, row0) and calls
// body(col, row, ray, hit) for each of its pixels inside the image.
constexpr int tile_w = 8, tile_h = packet_width / tile_w;

template <class Body>
void for_each_tile_pixel(const scene_camera<double>& camera, const instanced_scene& built, double tmin, int row0,
                         Body&& body) {
    const int width = camera.width(), height = camera.height();
    ray<double> rays[packet_width];
    instanced_scene::hit hits[packet_width];
    for (int col0 = 0; col0 < width; col0 += tile_w) {
        // A tile over the image's edge repeats its last column or row.
        for (int k = 0; k < packet_width; ++k)
            rays[k] = camera.primary_ray(std::min(col0 + k % tile_w, width - 1), std::min(row0 + k / tile_w, height - 1));
        built.closest(rays, tmin, infinity<double>, hits);
        for (int k = 0; k < packet_width; ++k) {
            const int col = col0 + k % tile_w, row = row0 + k / tile_w;
            if (col < width && row < height) body(col, row, rays[k], hits[k]);
        }
    }
}

int tile_rows(int height) { return (height + tile_h - 1) / tile_h; }

}  // namespace

image render_instanced(const scene_description& description, const instanced_scene& built, int width, int height,
                       render_stats& stats) {
    const scene_camera<double> camera(description.camera, width, height);
    const double tmin = camera.primary_range().min;
    const rt::scene<double>& world = description.world;
    image img(width, height);
    std::atomic<long> shadow_rays{0};
    for_each_row(tile_rows(height), [&](int tile_row) {
        long shadows = 0;
        ch06::occlusion_test<double> occluded = [&](const ray<double>& r, const interval<double>& range) {
            ++shadows;
            return built.blocked(r, range.min, range.max);
        };
        for_each_tile_pixel(camera, built, tmin, tile_row * tile_h,
                            [&](int col, int row, const ray<double>& r, const instanced_scene::hit& h) {
            color& out = img.at(col, row);
            if (h.material < 0) {
                out = world.background;
                return;
            }
            const vec3d& point = h.point;  // on the surface (local_hit::point)
            // A plane's checker follows the plane's own axes, as on the flat path (common/scene.hpp).
            const material& given = world.materials[size_t(h.material)];
            const material m = given.checker && h.plane_normal != vec3d(0)
                                   ? material_at(given, point, checker_axes_of(h.plane_normal))
                                   : material_at(given, point);
            const vec3d n = facing_normal(h.normal, r.direction);  // the side the viewer sees (common/hit_record.hpp)
            out = world.lights.empty() ? unlit_colour(m, n, r.direction)
                                       : ch06::shade(point, n, -r.direction, m, world.lights, world.ambient, occluded);
        });
        shadow_rays += shadows;
    });
    stats.rays = long(width) * long(height) + shadow_rays.load();
    return img;
}

long count_primary_hits_instanced(const scene_description& description, const instanced_scene& built, int width,
                                  int height) {
    const scene_camera<double> camera(description.camera, width, height);
    const double tmin = camera.primary_range().min;
    std::atomic<long> hits{0};
    for_each_row(tile_rows(height), [&](int tile_row) {
        long h = 0;
        for_each_tile_pixel(camera, built, tmin, tile_row * tile_h,
                            [&](int, int, const ray<double>&, const instanced_scene::hit& x) { h += x.material >= 0; });
        hits += h;
    });
    return hits.load();
}

// ---- flattening ---------------------------------------------------------

namespace {

// A similarity (rotation, mirror, uniform scale): perpendicular columns of
// one length, to rounding; its scale factor, or 0 when it is not one.
double similarity_scale(const mat3d& m) {
    const double s = length(m[0]);
    const double tol = 1e-9 * s * s;
    for (int i = 0; i < 3; ++i)
        if (std::fabs(dot(m[i], m[i]) - s * s) > tol || std::fabs(dot(m[i], m[(i + 1) % 3])) > tol) return 0;
    return s;
}

void flatten_into(const std::vector<object_definition>& defs, const object_definition& def,
                  const affine_transform& to_world, scene<double>& out) {
    const double scale = def.spheres.empty() ? 1 : similarity_scale(to_world.linear);
    if (!(scale > 0))
        throw std::invalid_argument(def.name + ": a sphere placed by a transform that is not a similarity is an "
                                    "ellipsoid, and a flat scene has only spheres");
    for (const auto& s : def.spheres) out.spheres.push_back({apply(to_world, s.center), s.radius * scale, s.material});
    for (const auto& t : def.triangles)
        out.triangles.push_back({apply(to_world, t.a), apply(to_world, t.b), apply(to_world, t.c), t.material});
    const mat3d normals = glm::transpose(inverted(to_world).linear);
    for (const auto& p : def.planes) out.planes.push_back({apply(to_world, p.point), normals * p.normal, p.material});
    for (const auto& i : def.instances) flatten_into(defs, defs[size_t(i.object)], then(i.to_parent, to_world), out);
}

}  // namespace

scene_description flattened(const scene_description& scene) {
    scene_description flat = scene;
    flat.objects.clear();
    flat.instances.clear();
    const std::vector<expanded_counts> counts = expanded_counts_of(scene.objects);
    std::uint64_t spheres = 0, triangles = 0;
    for (const auto& i : scene.instances) {
        spheres = saturating_add(spheres, counts[size_t(i.object)].spheres);
        triangles = saturating_add(triangles, counts[size_t(i.object)].triangles);
    }
    if (saturating_add(spheres, triangles) > 100'000'000)
        throw std::invalid_argument("the scene expands to more than 100 million shapes: too many to store flat");
    flat.world.spheres.reserve(flat.world.spheres.size() + spheres);
    flat.world.triangles.reserve(flat.world.triangles.size() + triangles);
    for (const auto& i : scene.instances) flatten_into(scene.objects, scene.objects[size_t(i.object)], i.to_parent, flat.world);
    return flat;
}

}  // namespace rt::render_tool
