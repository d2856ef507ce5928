// fast_path.cpp — the specialised renderer: the pixel loops, and the one
// dispatch from the scene's plan to the kernel instantiation it needs.
//
// Layout. Objects are stored as structure-of-arrays: all sphere centres'
// x in one array, all y in the next, and so on. Rays go in packets of 32,
// the pixels of a tile of 8 x 4, also as arrays. The hot loop takes one
// object and tests it against the 32 rays: the same arithmetic on 32
// independent lanes, which the compiler turns into vector instructions
// (AVX2: one instruction for eight floats or four doubles). Each lane keeps
// its own closest t and object with a select instead of a branch, so there
// is nothing to stop the vectoriser. Shadow rays go 32 at a time too, each
// with its own origin, asked ahead of chapter 06's shade()
// (fast_path_shadows.hpp); one that shade() asks unexpectedly goes alone,
// with objects in the lanes instead.
//
// Specialisation. What changes the inner loops is a template argument:
// the scalar type, the sphere formulation (plain or robust), and whether
// all rays of a packet share their origin (a pinhole camera's primary rays
// do, so terms that depend only on the origin and the object move out of
// the lane loop). with_precision_and_mode() picks the instantiation the
// plan asks for. Whether the scene has spheres, planes, triangles or
// lights is a plain branch, once per packet or per shadow ray: it costs
// nothing a benchmark can see, while those four choices as template
// arguments multiplied the code compiled (67 instantiations of the packet
// query against 15, 3.1 MB of code against 0.8, and 89-91 s to compile a
// copy of this file against 21-22 s). The pixel loop alone is compiled lit
// and unlit (tile_row_render), so an unlit scene carries no shadow
// bookkeeping.
//
// Misses. Each lane function returns the hit's t, or +infinity for a miss;
// "t < closest so far" is false for infinity and for NaN, so neither a miss
// nor a NaN can ever be taken as a hit.
//
// Conditions are combined with & rather than &&: && may skip the second
// comparison, which is a branch, and a loop with branches is not
// vectorised. With & every comparison is computed in every lane and the
// answer is one select.
//
// The parts, in the order they build on each other (each is included below,
// inside this copy's namespace):
//   fast_path_arrays.hpp      the packet, the per-ray terms and closest hits, the scene's arrays and trees
//   fast_path_traversal.hpp   slab tests and the walks of the 8-wide tree (one ray, a packet)
//   fast_path_spheres.hpp     sphere kernels and their lane loops (closest and any hit)
//   fast_path_planes.hpp      plane lane loops (kernels in fast_path_kernels.hpp)
//   fast_path_triangles.hpp   triangle lane loops, brute force and in the wide tree
//   fast_path_queries.hpp     closest_hits (a packet) and any_hit (a shadow ray)
//   fast_path_shadows.hpp     shadow rays asked ahead of shade() and traced W at a time
#include "fast_path.hpp"

#include "bvh_build.hpp"
#include "look.hpp"

#include "common/timing.hpp"
#include "common/random.hpp"  // one PCG32 stream per pixel, for several samples per pixel
#include "common/scene.hpp"   // material_at: the checker pattern
#include "06-shading/shading.hpp"   // chapter 06's shade(), for lit scenes
#include "11-sampling/sampling.hpp"  // chapter 11's stratified_sample and thin_lens_ray, for --spp N
#include "09-reflection/surface_error.hpp"  // hit points put back on their surfaces, for shading

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
#include <tuple>
#include <type_traits>
#include <utility>
#include <vector>

// Run-time dispatch: this file (with its parts) is compiled once per
// instruction set, each copy in its own namespace; isa_target.hpp, included
// after every header, switches the copy's instruction set on (it says why
// there and not on the command line).
#include "isa_target.hpp"

namespace rt::render_tool::RT_FAST_ISA {

namespace {

#define RT_FAST_PATH_PARTS 1
#include "fast_path_arrays.hpp"
#include "fast_path_traversal.hpp"
#include "fast_path_spheres.hpp"
#include "fast_path_planes.hpp"
#include "fast_path_triangles.hpp"
#include "fast_path_queries.hpp"
#include "fast_path_shadows.hpp"
#undef RT_FAST_PATH_PARTS

// Everything the pixel loop needs, in precision T.
template <class T>
struct context {
    soa_scene<T> soa;
    scene_camera<T> camera;
    const scene<double>& world;
    T tmin;
    std::vector<checker_axes> plane_axes;  // each plane's checker axes, found once (three normalisations each)

    context(const scene_description& d, int width, int height, bool tree)
        : soa(d.world, tree, magnitude(d)), camera(d.camera, width, height), world(d.world),
          tmin(camera.primary_range().min) {
        for (const plane<double>& x : d.world.planes) plane_axes.push_back(checker_axes_of(x.normal));
    }

    // The material of object o (the scene's number, as closest_hits answers)
    // at a hit point: a plane's checker follows the plane's own axes
    // (common/scene.hpp, checker_axes_of).
    material material_at_hit(size_t o, const vec3<T>& point) const {
        const material& m = world.materials[size_t(material_index(world, int(o)))];
        if (!m.checker || o < soa.sphere_count || o >= soa.sphere_count + soa.plane_count) return material_at(m, point);
        return material_at(m, point, plane_axes[o - soa.sphere_count]);
    }

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
        const bvh_wide_tree& a = soa.sphere_tree;
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

    // The same packet through points of the pixels' squares instead of their
    // centres: lane k's ray passes through (col + film[k].x, row + film[k].y),
    // by chapter 11's thin_lens_ray with no lens (the pinhole's ray through
    // that point; through the centre it is primary_ray's, bit for bit).
    void fill_samples(packet<T>& p, int col0, int row0, const ch11::vec2<T>* film) const {
        const ch11::thin_lens<T> pinhole{T(0), T(1)};
        for (int k = 0; k < W; ++k) {
            const int col = std::min(col0 + k % tile_w, camera.width() - 1);
            const int row = std::min(row0 + k / tile_w, camera.height() - 1);
            const ray<T> r = ch11::thin_lens_ray(camera.pinhole, pinhole, T(col) + film[k].x, T(row) + film[k].y,
                                                 ch11::vec2<T>(T(0), T(0)));
            p.ox[k] = r.origin.x, p.oy[k] = r.origin.y, p.oz[k] = r.origin.z;
            p.dx[k] = r.direction.x, p.dy[k] = r.direction.y, p.dz[k] = r.direction.z;
        }
    }

    template <sphere_mode SM>
    void trace(const packet<T>& p, T* t, index_t<T>* object) const {
        if (camera.type == camera_description::kind::pinhole)
            closest_hits<T, SM, true>(soa, p, tmin, t, object);
        else
            closest_hits<T, SM, false>(soa, p, tmin, t, object);
    }

    // The hit point of object o put back on o's surface, for shading. The
    // point origin + t d carries the rounding of t: seen from 4100 units
    // away (scenes/far-sphere.json) it is off the surface by about
    // 4100 eps, while chapter 06's shadow ray leaves by 128 eps of the
    // point's own coordinates (here 1), so it starts below the surface and
    // hits it: shadow acne, in every sphere formulation. Reprojected
    // (chapter 09's given surface_error.hpp, pbrt-v4's idea) the point is
    // off only by the rounding of the shape's own numbers, which the offset
    // covers. A plane goes through its unit normal (soa_scene::unit_normal),
    // which a normal of any length gives without underflow.
    vec3<T> surface_point(size_t o, const vec3<T>& point) const {
        if (o < soa.sphere_count) {
            const sphere<double>& x = world.spheres[o];
            return ch09::on_sphere(sphere<T>{convert<T>(x.center), T(x.radius)}, point).point;
        }
        if (o < soa.sphere_count + soa.plane_count) {
            const plane<double>& x = world.planes[o - soa.sphere_count];
            return ch09::on_plane_through(convert<T>(x.point), convert<T>(soa_scene<T>::unit_normal(x)), point).point;
        }
        const triangle<double>& x = world.triangles[o - soa.sphere_count - soa.plane_count];
        return ch09::on_triangle(triangle<T>{convert<T>(x.a), convert<T>(x.b), convert<T>(x.c)}, point).point;
    }

    // Unit outward normal at a hit point of object o (the scene's number), as
    // the chapters' exercises report it: from the scene's shapes rounded to T,
    // as soa_scene stores them.
    vec3<T> outward_normal(size_t o, const vec3<T>& point) const {
        if (o < soa.sphere_count) {
            const sphere<double>& x = world.spheres[o];
            return (point - convert<T>(x.center)) / T(x.radius);
        }
        vec3<T> n;
        if (o < soa.sphere_count + soa.plane_count) {
            n = convert<T>(soa_scene<T>::unit_normal(world.planes[o - soa.sphere_count]));
        } else {
            const triangle<double>& x = world.triangles[o - soa.sphere_count - soa.plane_count];
            const vec3<T> a = convert<T>(x.a);
            n = normalize(cross(convert<T>(x.b) - a, convert<T>(x.c) - a));
        }
        return n;
    }

    // Where lane k of the packet just traced hit object o at t: the point
    // put back on its surface, the normal on the viewer's side (the
    // chapters' one face rule, common/hit_record.hpp) and the material there.
    struct surface_hit {
        vec3<T> point, normal, direction;
        material m;
    };
    surface_hit hit_of(const packet<T>& p, T t, size_t o, int k) const {
        surface_hit h;
        const vec3<T> origin(p.ox[k], p.oy[k], p.oz[k]);
        h.direction = vec3<T>(p.dx[k], p.dy[k], p.dz[k]);
        h.point = surface_point(o, origin + t * h.direction);
        h.normal = facing_normal(outward_normal(o, h.point), h.direction);
        h.m = material_at_hit(o, h.point);
        return h;
    }
};

// One tile row of a render: its packets traced, shaded and written to the
// picture. Lit (the scene has lights) is the one choice the pixel loop
// makes at compile time: a lit row asks each packet's shadow rays ahead and
// traces them W at a time (fast_path_shadows.hpp), an unlit one carries
// none of that bookkeeping. The traversal and the kernels are the same
// functions either way.
template <class T, sphere_mode SM, bool Lit>
class tile_row_render {
public:
    tile_row_render(const context<T>& ctx, const scene_description& d, int width, int height, int tile_row)
        : ctx_(ctx), d_(d), width_(width), height_(height), row0_(tile_row * tile_h) {
        if constexpr (Lit)
            occluded_ = [this](const ray<T>& r, const interval<T>& range) {
                return batch_.template replay<SM>(ctx_.soa, lane_, r, range);
            };
    }
    tile_row_render(const tile_row_render&) = delete;  // occluded_ holds `this`
    tile_row_render& operator=(const tile_row_render&) = delete;

    // One ray through each pixel's centre.
    void one_sample(image& img) {
        for (int col0 = 0; col0 < width_; col0 += tile_w) {
            ctx_.fill(p_, col0, row0_);
            trace_and_shade(col0);
            for (int k = 0; k < W; ++k)
                if (inside(col0, k)) img.at(col0 + k % tile_w, row0_ + k / tile_w) = colour_[k];
        }
    }

    // spp samples per pixel, one in each cell of a strata x strata grid over
    // the pixel's square, jittered by the pixel's own stream: the picture is
    // the same on every run and thread count. A box filter: the pixel is the
    // samples' mean.
    void samples(image& img, int spp, std::uint64_t seed) {
        const int strata = int(std::lround(std::sqrt(double(spp))));  // spp is a square: strata x strata cells
        std::vector<pcg32> streams;
        for (int col0 = 0; col0 < width_; col0 += tile_w) {
            streams.clear();
            for (int k = 0; k < W; ++k)
                streams.push_back(pixel_stream(seed, std::min(col0 + k % tile_w, width_ - 1),
                                               std::min(row0_ + k / tile_w, height_ - 1), width_));
            color sum[W];
            for (color& c : sum) c = color(0.0f);
            ch11::vec2<T> film[W];
            for (int sample = 0; sample < spp; ++sample) {
                for (int k = 0; k < W; ++k) {
                    const T u = streams[size_t(k)].template uniform<T>(), v = streams[size_t(k)].template uniform<T>();
                    film[k] = ch11::stratified_sample(sample, strata, ch11::vec2<T>(u, v));
                }
                ctx_.fill_samples(p_, col0, row0_, film);
                trace_and_shade(col0);
                for (int k = 0; k < W; ++k)
                    if (inside(col0, k)) sum[k] += colour_[k];
            }
            for (int k = 0; k < W; ++k)
                if (inside(col0, k)) img.at(col0 + k % tile_w, row0_ + k / tile_w) = sum[k] / float(spp);
        }
    }

    long shadow_rays() const { return shadows_; }

private:
    bool inside(int col0, int k) const { return col0 + k % tile_w < width_ && row0_ + k / tile_w < height_; }

    // The colours of the packet p_, lanes inside the picture. Every hit is
    // found first, so that a lit scene's shadow rays are asked ahead.
    void trace_and_shade(int col0) {
        ctx_.template trace<SM>(p_, t_, object_);
        for (int k = 0; k < W; ++k) {
            has_hit_[k] = inside(col0, k) && object_[k] >= 0;
            if (has_hit_[k]) hit_[k] = ctx_.hit_of(p_, t_[k], size_t(object_[k]), k);
        }
        if constexpr (Lit) {
            ask_every_light(batch_, d_.world.lights, hit_, has_hit_);
            batch_.template answer<SM>(ctx_.soa);
            shadows_ += long(batch_.size());
        }
        for (int k = 0; k < W; ++k) {
            if (!inside(col0, k)) continue;
            lane_ = k;
            const auto& h = hit_[k];
            if (object_[k] < 0)
                colour_[k] = d_.world.background;
            else if constexpr (Lit)
                colour_[k] = ch06::shade(h.point, h.normal, -h.direction, h.m, d_.world.lights, d_.world.ambient, occluded_);
            else
                colour_[k] = unlit_colour(h.m, h.normal, h.direction);
        }
        if constexpr (Lit) shadows_ += batch_.alone, batch_.alone = 0;
    }

    const context<T>& ctx_;
    const scene_description& d_;
    const int width_, height_, row0_;
    packet<T> p_;
    alignas(64) T t_[W];
    alignas(64) index_t<T> object_[W];
    typename context<T>::surface_hit hit_[W];
    bool has_hit_[W];
    color colour_[W];
    shadow_batch<T> batch_;
    int lane_ = 0;  // the lane shade() is shading: the one whose shadow rays replay answers
    ch06::occlusion_test<T> occluded_;
    long shadows_ = 0;
};

template <class T, sphere_mode SM>
image render_with(const scene_description& d, int width, int height, bool tree, int spp, std::uint64_t seed,
                  render_stats& stats) {
    const stopwatch setup;
    const double setup_cpu = process_cpu_seconds();
    const context<T> ctx(d, width, height, tree);
    stats.setup_seconds = setup.seconds();
    stats.setup_cpu_seconds = process_cpu_seconds() - setup_cpu;
    if (tree) std::fprintf(stderr, "%s\n", ctx.describe_trees().c_str());  // stderr: outside rt-bench's tables
    if (spp > 1 && ctx.camera.type != camera_description::kind::pinhole)
        throw std::invalid_argument("several samples per pixel are drawn through a pinhole camera (chapter 11's), not "
                                    "an orthographic one");
    image img(width, height);
    std::atomic<long> shadow_rays{0};
    auto every_row = [&](auto lit) {
        for_each_row((height + tile_h - 1) / tile_h, [&](int tile_row) {
            tile_row_render<T, SM, decltype(lit)::value> row(ctx, d, width, height, tile_row);
            if (spp == 1)
                row.one_sample(img);
            else
                row.samples(img, spp, seed);
            shadow_rays += row.shadow_rays();
        });
    };
    if (d.world.lights.empty())
        every_row(std::false_type{});
    else
        every_row(std::true_type{});
    const long primary = long(width) * long(height) * long(spp);
    stats.rays = primary + shadow_rays.load();
    if (spp > 1) stats.samples = primary;
    return img;
}

// The primary rays of tile row `tile_row`, traced; then
// visit(p, t, object, k, col, row) for every lane k inside the picture
// (pixel col, row).
template <class T, sphere_mode SM, class Visit>
void trace_tile_row(const context<T>& ctx, int width, int height, int tile_row, Visit&& visit) {
    const int row0 = tile_row * tile_h;
    packet<T> p;
    alignas(64) T t[W];
    alignas(64) index_t<T> object[W];
    for (int col0 = 0; col0 < width; col0 += tile_w) {
        ctx.fill(p, col0, row0);
        ctx.template trace<SM>(p, t, object);
        for (int k = 0; k < W; ++k) {
            const int col = col0 + k % tile_w, row = row0 + k / tile_w;
            if (col < width && row < height) visit(p, t, object, k, col, row);
        }
    }
}

template <class T, sphere_mode SM>
primary_hits trace_with(const scene_description& d, int width, int height, bool tree) {
    const context<T> ctx(d, width, height, tree);
    primary_hits hits;
    hits.object.assign(size_t(width) * size_t(height), -1);
    hits.t.assign(size_t(width) * size_t(height), 0);
    for_each_row((height + tile_h - 1) / tile_h, [&](int tile_row) {
        trace_tile_row<T, SM>(ctx, width, height, tile_row,
                              [&](const packet<T>&, const T* t, const index_t<T>* object, int k, int col, int row) {
                                  const size_t i = size_t(row) * size_t(width) + size_t(col);
                                  hits.object[i] = object[k] < 0 ? -1 : int(object[k]);
                                  hits.t[i] = (long double)t[k];
                              });
    });
    return hits;
}

// How many pixels' primary rays hit something, on every core.
template <class T, sphere_mode SM>
long count_hits(const context<T>& ctx, int width, int height) {
    std::atomic<long> hits{0};
    for_each_row((height + tile_h - 1) / tile_h, [&](int tile_row) {
        long row_hits = 0;
        trace_tile_row<T, SM>(
            ctx, width, height, tile_row,
            [&](const packet<T>&, const T*, const index_t<T>* object, int k, int, int) { row_hits += object[k] >= 0; });
        hits += row_hits;
    });
    return hits.load();
}

template <class T, sphere_mode SM>
long count_with(const scene_description& d, int width, int height, bool tree, const pass_timer& timed,
                double* trace_seconds) {
    const context<T> ctx(d, width, height, tree);
    long hits = 0;
    const auto trace = [&] { hits = count_hits<T, SM>(ctx, width, height); };
    if (!timed) {
        trace();
        return hits;
    }
    const double seconds = timed(trace);
    if (trace_seconds) *trace_seconds = seconds;
    return hits;
}

// The shadow rays of a lit render apart from its shading. Every primary
// hit's surface is found once, tile by tile. Then, under the caller's clock
// and on every core as the render does: the primary rays alone (trace
// only); the shadow rays built as the render asks them ahead
// (ask_every_light: chapter 06's lambert and shadow_ray); those rays
// traced as the render traces them (shadow_batch::answer, W at a time);
// and the same rays one at a time (any_hit). Last, each tile is shaded by
// chapter 06's shade() with the packets' answers, counting the rays shade()
// asks that were not asked ahead (replay traces those alone): none, when
// the render's packets answer every shadow ray.
template <class T, sphere_mode SM>
shadow_figures shadows_with(const scene_description& d, int width, int height, bool tree, const pass_timer& timed) {
    const context<T> ctx(d, width, height, tree);
    const int tile_rows = (height + tile_h - 1) / tile_h, tile_cols = (width + tile_w - 1) / tile_w;
    struct tile {
        typename context<T>::surface_hit hit[W];
        bool has_hit[W] = {};
        shadow_batch<T> batch;
    };
    std::vector<tile> tiles(static_cast<size_t>(tile_rows) * static_cast<size_t>(tile_cols));
    auto tile_at = [&](int tile_row, int c) -> tile& { return tiles[size_t(tile_row) * size_t(tile_cols) + size_t(c)]; };
    for_each_row(tile_rows, [&](int tile_row) {
        trace_tile_row<T, SM>(
            ctx, width, height, tile_row,
            [&](const packet<T>& p, const T* t, const index_t<T>* object, int k, int col, int) {
                tile& x = tile_at(tile_row, col / tile_w);
                x.has_hit[k] = object[k] >= 0;
                if (x.has_hit[k]) x.hit[k] = ctx.hit_of(p, t[k], size_t(object[k]), k);
            });
    });
    // f(tile) for every tile, on every core.
    auto every_tile = [&](auto&& f) {
        for_each_row(tile_rows, [&](int tile_row) {
            for (int c = 0; c < tile_cols; ++c) f(tile_at(tile_row, c));
        });
    };
    auto blocked = [&] {
        long n = 0;
        for (const tile& x : tiles) n += x.batch.blocked();
        return n;
    };
    shadow_figures f;
    f.primary_rays = long(width) * long(height);
    f.primary_seconds = timed([&] { f.primary_hits = count_hits<T, SM>(ctx, width, height); });
    f.ask_seconds = timed([&] { every_tile([&](tile& x) { ask_every_light(x.batch, d.world.lights, x.hit, x.has_hit); }); });
    for (const tile& x : tiles) f.shadow_rays += long(x.batch.size());
    f.shadow_seconds = timed([&] { every_tile([&](tile& x) { x.batch.template answer<SM>(ctx.soa); }); });
    f.occluded = blocked();
    f.one_at_a_time_seconds = timed(
        [&] { every_tile([&](tile& x) { x.batch.template answer_one_at_a_time<SM>(ctx.soa); }); });
    f.occluded_one_at_a_time = blocked();
    std::atomic<long> alone{0};
    every_tile([&](tile& x) {
        x.batch.template answer<SM>(ctx.soa);
        int lane = 0;
        const ch06::occlusion_test<T> occluded = [&](const ray<T>& r, const interval<T>& range) {
            return x.batch.template replay<SM>(ctx.soa, lane, r, range);
        };
        for (lane = 0; lane < W; ++lane) {
            const auto& h = x.hit[lane];
            if (x.has_hit[lane])
                (void)ch06::shade(h.point, h.normal, -h.direction, h.m, d.world.lights, d.world.ambient, occluded);
        }
        alone += x.batch.alone;
    });
    f.asked_but_not_ahead = alone.load();
    return f;
}

// Calls f(type, SM) with the plan's precision (a value of the scalar type)
// and its sphere formulation (std::integral_constant) as compile-time
// choices: nothing else about the scene is one (see the opening comment).
template <class F>
decltype(auto) with_precision_and_mode(const scene_plan& plan, F&& f) {
    auto in = [&](auto type) {
        if (plan.form == sphere_formulation::plain)
            return f(type, std::integral_constant<sphere_mode, sphere_mode::plain>{});
        return f(type, std::integral_constant<sphere_mode, sphere_mode::robust>{});
    };
    return plan.prec == precision::single ? in(float{}) : in(double{});
}

}  // namespace

image render_fast(const scene_description& d, const scene_plan& plan, int width, int height, render_stats& stats) {
    return with_precision_and_mode(plan, [&](auto type, auto SM) {
        return render_with<decltype(type), decltype(SM)::value>(d, width, height, plan.tree, plan.spp, plan.seed, stats);
    });
}

primary_hits trace_primary(const scene_description& d, const scene_plan& plan, int width, int height) {
    return with_precision_and_mode(
        plan, [&](auto type, auto SM) { return trace_with<decltype(type), decltype(SM)::value>(d, width, height, plan.tree); });
}

long count_primary_hits(const scene_description& d, const scene_plan& plan, int width, int height,
                        const pass_timer& timed, double* trace_seconds) {
    return with_precision_and_mode(plan, [&](auto type, auto SM) {
        return count_with<decltype(type), decltype(SM)::value>(d, width, height, plan.tree, timed, trace_seconds);
    });
}

shadow_figures time_shadow_rays(const scene_description& d, const scene_plan& plan, int width, int height,
                                const pass_timer& timed) {
    return with_precision_and_mode(plan, [&](auto type, auto SM) {
        return shadows_with<decltype(type), decltype(SM)::value>(d, width, height, plan.tree, timed);
    });
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
    return trace_with<long double, sphere_mode::robust>(d, width, height, false);
}

}  // namespace rt::render_tool::RT_FAST_ISA
