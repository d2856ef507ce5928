// rt-bench — throughput of the specialised renderer against the general one
// and, when Intel Embree is installed, against Embree.
//
//   rt-bench [--quick] [--runs R] [--size S] [--wall] [--no-flake] [--flake-only]
//
// prints, at S x S pixels (default 512) with one primary ray per pixel on
// every core:
//   1. scenes of N spheres (N = 1 ... 4096): rays per second of the
//      specialised path and of the general path (full render with shading),
//      their ratio; then primary-hit-only throughput of the brute-force
//      kernel next to Embree's rtcIntersect1 and rtcIntersect16 on the same
//      spheres, and the ratios;
//   2. mixed scenes: the cost of each feature (planes, triangles, lights and
//      shadow rays) on top of spheres only;
//   3. how the time scales with the number of pixels;
//   8. samples per second at 16 samples per pixel: the Cornell box path
//      traced, and the sphereflake on the specialised path.
// Each figure is the fastest of R runs (default 3); brute force and Embree
// are timed in turn within each run, so both see the same machine. Timings are reported,
// never asserted: this is not a test.
#include "fast_path.hpp"
#include "general_path.hpp"
#include "instanced_path.hpp"
#include "render_planned.hpp"
#include "scene_plan.hpp"

#include "common/image_compare.hpp"
#include "common/render.hpp"
#include "common/scene_file.hpp"
#include "common/spd.hpp"
#include "common/stub.hpp"
#include "common/timing.hpp"

#include <CLI/CLI.hpp>

#ifdef RT_HAVE_EMBREE
#include <embree3/rtcore.h>
#endif

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <random>
#include <vector>

#include <memory>

#include <sys/resource.h>
#include <time.h>

using namespace rt;
using namespace rt::render_tool;

namespace {

int runs = 3;

// N spheres scattered in a box in front of the camera. Their radius shrinks
// like N^(-1/3), so the spheres cover a similar share of the picture at
// every N and the figures compare the cost of N, not of coverage.
scene_description sphere_scene(int n, int size, unsigned seed = 12345) {
    scene_description d;
    d.source = "generated";
    d.camera.eye = {0, 0, 0};
    d.camera.look_at = {0, 0, -1};
    d.camera.fov_degrees = 60;
    d.camera.width = d.camera.height = size;
    d.world.materials = {material{color(0.8f, 0.3f, 0.2f)}, material{color(0.2f, 0.5f, 0.8f)}};
    d.material_names = {"", ""};
    std::mt19937 random(seed);
    std::uniform_real_distribution<double> x(-4, 4), y(-3.5, 3.5), z(-14, -5);
    const double radius = 1.6 / std::cbrt(double(n));
    for (int i = 0; i < n; ++i) d.world.spheres.push_back({vec3d(x(random), y(random), z(random)), radius, i % 2});
    return d;
}

// Spheres, then optionally a floor, a triangle mesh (a folded strip of
// `triangles` triangles standing on the floor) and two lights.
scene_description mixed_scene(int spheres, bool plane, int triangles, bool lights, int size) {
    scene_description d = sphere_scene(spheres, size);
    d.world.materials.push_back(material{color(0.7f, 0.7f, 0.7f), color(0), 32, true, color(0.3f, 0.3f, 0.3f)});
    if (plane) d.world.planes.push_back({vec3d(0, -4, 0), vec3d(0, 1, 0), 2});
    for (int i = 0; i < triangles; ++i) {
        // A zig-zag strip across the back of the scene.
        const double x0 = -6 + 12.0 * (i / 2) / std::max(1, triangles / 2), w = 12.0 / std::max(1, triangles / 2);
        const double z0 = -15 + (i % 4 < 2 ? 0.0 : 0.6);
        if (i % 2 == 0)
            d.world.triangles.push_back({vec3d(x0, -4, z0), vec3d(x0 + w, -4, z0), vec3d(x0, 2, z0 - 0.5), 1});
        else
            d.world.triangles.push_back({vec3d(x0 + w, -4, z0), vec3d(x0 + w, 2, z0 - 0.5), vec3d(x0, 2, z0 - 0.5), 0});
    }
    if (lights) {
        d.world.lights.push_back({vec3d(-6, 8, 2), color(150, 150, 140)});
        d.world.lights.push_back({vec3d(6, 5, 0), color(60, 60, 80)});
    }
    return d;
}

// The machine is shared (other builds, other users), and interference only
// ever makes a run slower: each figure is the fastest of `repeat` runs.
// By default "time" is the process's CPU time divided by the number of
// threads: a thread that the system takes off its core to run someone
// else's job stops its CPU clock, so the figure is what both cores would do
// undisturbed. --wall measures wall-clock time instead (the right choice on
// an otherwise idle machine).
bool wall_clock = false;

double best_seconds(const std::function<void()>& f, int repeat) {
    std::vector<double> samples;
    for (int r = 0; r < repeat; ++r) {
        stopwatch sw;
        const double cpu0 = process_cpu_seconds();
        f();
        samples.push_back(wall_clock ? sw.seconds() : (process_cpu_seconds() - cpu0) / double(render_threads()));
    }
    return summarize(samples).min;
}

// The time of one pass that takes a few milliseconds: several passes in
// each sample, enough for about 50 ms, then the fastest of `repeat`
// samples, per pass. Why: a single pass of 2.5-3 ms read up to 20% apart
// from one run to the next (section 2's primary rays, 2.28 against 2.79 ms
// on 4 December 2026, swinging its shadow ratio from 0.87x to 1.06x;
// with this, 0.87-0.88x in four runs). The pass must give the same result
// each time it runs.
double best_seconds_per_pass(const std::function<void()>& pass, int repeat) {
    const double one = best_seconds(pass, 1);
    const int passes = std::clamp(int(0.05 / std::max(one, 1e-6)), 1, 1000);
    return best_seconds([&] { for (int i = 0; i < passes; ++i) pass(); }, repeat) / passes;
}

// The same for a render that builds its own arrays and trees first and
// reports that setup in the render_stats it is given: each run is timed
// without its setup, so the figure is the tracing and shading alone. (A build
// timed in another run of the sphereflake differs by up to two seconds,
// more than its tracing.)
double best_seconds_after_setup(const std::function<void(render_stats&)>& f, int repeat) {
    std::vector<double> samples;
    for (int r = 0; r < repeat; ++r) {
        render_stats stats;
        const stopwatch sw;
        const double cpu0 = process_cpu_seconds();
        f(stats);
        samples.push_back(wall_clock ? sw.seconds() - stats.setup_seconds
                                     : (process_cpu_seconds() - cpu0 - stats.setup_cpu_seconds) / double(render_threads()));
    }
    return summarize(samples).min;
}

struct render_figures {
    double seconds = 0;
    long rays = 0;
    double mrays() const { return double(rays) / seconds / 1e6; }
};

render_figures time_fast(const scene_description& d, int size) {
    const scene_plan plan = make_plan(d, 1e-3, std::nullopt);
    render_figures f;
    render_stats stats;
    f.seconds = best_seconds([&] { render_fast(d, plan, size, size, stats); }, runs);
    f.rays = stats.rays;
    return f;
}

render_figures time_general(const scene_description& d, int size, int repeat) {
    scene_plan plan = make_plan(d, 1e-3, precision::double_);
    plan.general = true;
    render_figures f;
    render_stats stats;
    f.seconds = best_seconds([&] { render_general(d, plan, size, size, stats); }, repeat);
    f.rays = stats.rays;
    return f;
}

#ifdef RT_HAVE_EMBREE
// Primary hits over the image in an Embree scene, one rtcIntersect1 per ray,
// on every core: the single() of both Embree scenes below.
long embree_single(RTCScene scene, const pinhole_camera<float>& cam) {
    std::atomic<long> hits{0};
    for_each_row(cam.height, [&](int row) {
        RTCIntersectContext context;
        rtcInitIntersectContext(&context);
        long h = 0;
        for (int col = 0; col < cam.width; ++col) {
            const ray<float> r = cam.primary_ray(col, row);
            RTCRayHit rh;
            rh.ray.org_x = r.origin.x, rh.ray.org_y = r.origin.y, rh.ray.org_z = r.origin.z;
            rh.ray.dir_x = r.direction.x, rh.ray.dir_y = r.direction.y, rh.ray.dir_z = r.direction.z;
            rh.ray.tnear = 1.0f, rh.ray.tfar = infinity<float>, rh.ray.time = 0, rh.ray.mask = ~0u;
            rh.ray.id = 0, rh.ray.flags = 0;
            rh.hit.geomID = RTC_INVALID_GEOMETRY_ID, rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
            rtcIntersect1(scene, &context, &rh);
            h += rh.hit.geomID != RTC_INVALID_GEOMETRY_ID;
        }
        hits += h;
    });
    return hits.load();
}

// The same spheres in Embree: its point-sphere geometry (RTC_GEOMETRY_TYPE_SPHERE_POINT)
// in a BVH built at high quality. Rays are the pinhole camera's primary rays
// in float, with tnear = 1 (the image plane) like the course's.
class embree_scene {
public:
    explicit embree_scene(const scene_description& d) {
        device_ = rtcNewDevice("threads=2");
        scene_ = rtcNewScene(device_);
        rtcSetSceneBuildQuality(scene_, RTC_BUILD_QUALITY_HIGH);
        if (!d.world.spheres.empty()) {
            RTCGeometry g = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_SPHERE_POINT);
            float* v = static_cast<float*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT4,
                                                                   4 * sizeof(float), d.world.spheres.size()));
            for (size_t i = 0; i < d.world.spheres.size(); ++i) {
                const auto& s = d.world.spheres[i];
                v[4 * i + 0] = float(s.center.x), v[4 * i + 1] = float(s.center.y), v[4 * i + 2] = float(s.center.z);
                v[4 * i + 3] = float(s.radius);
            }
            rtcCommitGeometry(g);
            rtcAttachGeometry(scene_, g);
            rtcReleaseGeometry(g);
        }
        if (!d.world.triangles.empty()) {  // an unshared vertex triple per triangle, as the scene holds them
            const size_t n = d.world.triangles.size();
            RTCGeometry g = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
            float* v = static_cast<float*>(
                rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), 3 * n));
            unsigned* index = static_cast<unsigned*>(
                rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), n));
            for (size_t i = 0; i < n; ++i) {
                const auto& t = d.world.triangles[i];
                const vec3d corners[3] = {t.a, t.b, t.c};
                for (size_t c = 0; c < 3; ++c) {
                    for (int a = 0; a < 3; ++a) v[9 * i + 3 * c + size_t(a)] = float(corners[c][a]);
                    index[3 * i + c] = unsigned(3 * i + c);
                }
            }
            rtcCommitGeometry(g);
            rtcAttachGeometry(scene_, g);
            rtcReleaseGeometry(g);
        }
        stopwatch sw;
        rtcCommitScene(scene_);
        build_seconds = sw.seconds();
    }
    ~embree_scene() {
        rtcReleaseScene(scene_);
        rtcReleaseDevice(device_);
    }
    embree_scene(const embree_scene&) = delete;
    embree_scene& operator=(const embree_scene&) = delete;

    static bool spheres_supported() {
        RTCDevice dev = rtcNewDevice(nullptr);
        bool ok = dev && rtcGetDeviceProperty(dev, RTC_DEVICE_PROPERTY_POINT_GEOMETRY_SUPPORTED) != 0;
        if (dev) rtcReleaseDevice(dev);
        return ok;
    }

    // Hits over the whole image with one rtcIntersect1 per ray.
    long single(const pinhole_camera<float>& cam) const { return embree_single(scene_, cam); }

    // Hits over the whole image with one rtcIntersect16 per 4x4 block of pixels
    // (rows are handed out four at a time).
    long packets16(const pinhole_camera<float>& cam) const {
        std::atomic<long> hits{0};
        for_each_row((cam.height + 3) / 4, [&](int block_row) {
            RTCIntersectContext context;
            rtcInitIntersectContext(&context);
            context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
            long h = 0;
            for (int col0 = 0; col0 < cam.width; col0 += 4) {
                alignas(64) RTCRayHit16 rh;
                alignas(64) int valid[16];
                for (int k = 0; k < 16; ++k) {
                    const int col = col0 + k % 4, row = block_row * 4 + k / 4;
                    valid[k] = col < cam.width && row < cam.height ? -1 : 0;
                    const ray<float> r = cam.primary_ray(std::min(col, cam.width - 1), std::min(row, cam.height - 1));
                    rh.ray.org_x[k] = r.origin.x, rh.ray.org_y[k] = r.origin.y, rh.ray.org_z[k] = r.origin.z;
                    rh.ray.dir_x[k] = r.direction.x, rh.ray.dir_y[k] = r.direction.y, rh.ray.dir_z[k] = r.direction.z;
                    rh.ray.tnear[k] = 1.0f, rh.ray.tfar[k] = infinity<float>, rh.ray.time[k] = 0;
                    rh.ray.mask[k] = ~0u, rh.ray.id[k] = 0, rh.ray.flags[k] = 0;
                    rh.hit.geomID[k] = RTC_INVALID_GEOMETRY_ID, rh.hit.instID[0][k] = RTC_INVALID_GEOMETRY_ID;
                }
                rtcIntersect16(valid, scene_, &context, &rh);
                for (int k = 0; k < 16; ++k) h += valid[k] && rh.hit.geomID[k] != RTC_INVALID_GEOMETRY_ID;
            }
            hits += h;
        });
        return hits.load();
    }

    double build_seconds = 0;

private:
    RTCDevice device_;
    RTCScene scene_;
};
#endif

void sphere_table(const std::vector<int>& counts, int size) {
    std::printf("\n1. N spheres, %dx%d, no lights (the specialised plan keeps only the sphere loop)\n", size, size);
    std::printf("   full render (primary rays + colour), Mrays/s:\n");
    std::printf("   %6s | %12s | %12s | %12s | %9s\n", "N", "plan", "specialised", "general", "spec/gen");
    for (int n : counts) {
        const scene_description d = sphere_scene(n, size);
        const render_figures fast = time_fast(d, size);
        // The general path pays a std::function call per object and ray: at
        // large N one run takes seconds, so it is timed once there.
        const render_figures general = time_general(d, size, n >= 256 ? 1 : runs);
        const scene_plan plan = make_plan(d, 1e-3, std::nullopt);
        const std::string choice = std::string(plan.prec == precision::single ? "float " : "double ") +
                                   (plan.form == sphere_formulation::plain ? "plain" : "robust");
        std::printf("   %6d | %12s | %12.1f | %12.2f | %8.1fx\n", n, choice.c_str(), fast.mrays(), general.mrays(),
                    fast.mrays() / general.mrays());
        std::fflush(stdout);
    }

    std::printf("\n   primary hits only (closest hit, no shading), brute force (no tree at any N), Mrays/s");
#ifdef RT_HAVE_EMBREE
    const bool embree = embree_scene::spheres_supported();
    std::printf(embree ? ", against Embree %d.%d.%d (point spheres, BVH build quality high):\n"
                       : ": (this Embree has no point/sphere geometry)\n",
                RTC_VERSION_MAJOR, RTC_VERSION_MINOR, RTC_VERSION_PATCH);
    if (embree)
        std::printf("   %6s | %12s | %12s | %12s | %9s | %9s | %10s | %s\n", "N", "brute force", "rtcIntersect1",
                    "rtcIntersect16", "bf/E1", "bf/E16", "build ms", "hits bf/E1/E16");
#else
    const bool embree = false;
    std::printf(": (Embree not found at configure time: apt-get install libembree-dev and reconfigure)\n");
#endif
    if (!embree) std::printf("   %6s | %12s\n", "N", "brute force");
    for (int n : counts) {
        const scene_description d = sphere_scene(n, size);
        scene_plan plan = make_plan(d, 1e-3, std::nullopt);
        plan.tree = false;  // brute force at every N: section 4 is the tree's
        long ours_hits = 0;
        const double rays = double(size) * double(size);
        if (!embree) {
            const double ours = best_seconds([&] { ours_hits = count_primary_hits(d, plan, size, size); }, runs);
            std::printf("   %6d | %12.1f\n", n, rays / ours / 1e6);
            continue;
        }
#ifdef RT_HAVE_EMBREE
        const embree_scene e(d);
        const pinhole_camera<float> cam(
            camera_frame<float>::look_at(convert<float>(d.camera.eye), convert<float>(d.camera.look_at), {0, 1, 0}),
            float(d.camera.fov_degrees), size, size);
        long hits1 = 0, hits16 = 0;
        double ours = 1e300, single = 1e300, packets = 1e300;
        for (int r = 0; r < runs; ++r) {  // in turn, so all three see the same machine
            ours = std::min(ours, best_seconds([&] { ours_hits = count_primary_hits(d, plan, size, size); }, 1));
            single = std::min(single, best_seconds([&] { hits1 = e.single(cam); }, 1));
            packets = std::min(packets, best_seconds([&] { hits16 = e.packets16(cam); }, 1));
        }
        std::printf("   %6d | %12.1f | %12.1f | %12.1f | %8.2fx | %8.2fx | %10.2f | %ld/%ld/%ld\n", n, rays / ours / 1e6,
                    rays / single / 1e6, rays / packets / 1e6, single / ours, packets / ours, e.build_seconds * 1e3,
                    ours_hits, hits1, hits16);
        std::fflush(stdout);
#endif
    }
}

void feature_table(int size) {
    std::printf("\n2. per-feature cost, 64 spheres, %dx%d (full render; rays = primary + shadow)\n", size, size);
    std::printf("   %-36s | %9s | %12s | %12s | %12s | %9s\n", "scene", "ms spec", "Mrays/s spec", "cost vs 1st",
                "Mrays/s gen", "spec/gen");
    struct row {
        const char* name;
        bool plane;
        int triangles;
        bool lights;
    };
    const row rows[] = {{"spheres only", false, 0, false},
                        {"+ a plane", true, 0, false},
                        {"+ a plane + 64 triangles", true, 64, false},
                        {"+ a plane + 64 triangles + 2 lights", true, 64, true}};
    double base = 0, unlit = 0;
    for (const row& r : rows) {
        const scene_description d = mixed_scene(64, r.plane, r.triangles, r.lights, size);
        const render_figures fast = time_fast(d, size);
        const render_figures general = time_general(d, size, 1);
        if (base == 0) base = fast.seconds;
        std::printf("   %-36s | %9.2f | %12.1f | %11.2fx | %12.2f | %8.1fx\n", r.name, fast.seconds * 1e3, fast.mrays(),
                    fast.seconds / base, general.mrays(), fast.mrays() / general.mrays());
        std::fflush(stdout);
        if (!r.lights) {
            unlit = fast.seconds;
        } else {
            // What each light adds (its shadow rays and its share of the
            // shading), against the same scene's render without lights.
            const double lights = double(d.world.lights.size());
            std::printf("   one light's shadow rays and shading: %.2fx the render without lights ((%.2f - %.2f) / %.0f ms "
                        "against %.2f)\n",
                        (fast.seconds - unlit) / lights / unlit, fast.seconds * 1e3, unlit * 1e3, lights, unlit * 1e3);
            // The shadow rays alone: the render's own shadow rays, traced
            // without shading, against its primary rays traced alone.
            const shadow_figures s = time_shadow_rays(d, make_plan(d, 1e-3, std::nullopt), size, size,
                                                      [](const std::function<void()>& pass) { return best_seconds_per_pass(pass, runs); });
            const double per_light = 1.0 / lights / s.primary_seconds;
            std::printf("   one light's shadow rays, traced: %.2fx the primary rays' time (in packets of 32: %.2f ms for %ld "
                        "shadow rays, %.0f%% blocked, / %.0f lights, against %.2f ms for %ld primary rays; target at most "
                        "1x)\n",
                        s.shadow_seconds * per_light, s.shadow_seconds * 1e3, s.shadow_rays,
                        100.0 * double(s.occluded) / double(s.shadow_rays), lights, s.primary_seconds * 1e3,
                        s.primary_rays);
            std::printf("   and made by chapter 06's lambert and shadow_ray: %.2fx more (%.2f ms); traced one at a time "
                        "instead (any_hit): %.2fx (%.2f ms)\n",
                        s.ask_seconds * per_light, s.ask_seconds * 1e3, s.one_at_a_time_seconds * per_light,
                        s.one_at_a_time_seconds * 1e3);
            std::printf("   blocked: %ld in packets, %ld one at a time; rays shade() asked that were not asked ahead: %ld\n",
                        s.occluded, s.occluded_one_at_a_time, s.asked_but_not_ahead);
        }
    }
}

void pixel_table(const std::vector<int>& sizes) {
    std::printf("\n3. scaling with pixel count, 64 spheres, specialised path, full render\n");
    std::printf("   %10s | %10s | %9s | %12s | %10s\n", "image", "pixels", "ms", "Mrays/s", "ns/pixel");
    for (int s : sizes) {
        const scene_description d = sphere_scene(64, s);
        const render_figures fast = time_fast(d, s);
        std::printf("   %4dx%-5d | %10ld | %9.2f | %12.1f | %10.2f\n", s, s, long(s) * s, fast.seconds * 1e3,
                    fast.mrays(), fast.seconds / double(long(s) * s) * 1e9);
        std::fflush(stdout);
    }
}

double peak_rss_gb() {
    rusage u{};
    getrusage(RUSAGE_SELF, &u);
    return double(u.ru_maxrss) / (1024.0 * 1024.0);  // ru_maxrss is in KiB on Linux
}

#ifdef RT_HAVE_EMBREE
// The camera the scene file describes, in float, for Embree's rays.
pinhole_camera<float> float_camera(const scene_description& d, int size) {
    return pinhole_camera<float>(camera_frame<float>::look_at(convert<float>(d.camera.eye), convert<float>(d.camera.look_at),
                                                              convert<float>(d.camera.up)),
                                 float(d.camera.fov_degrees), size, size);
}
#endif

// Our tree against Embree's on one scene: build, then primary hits only.
// Both traces are timed alike: the fastest of `runs` samples of about 50 ms
// each (best_seconds_per_pass: a short trace repeated within a sample),
// ours after one build of the scene's arrays and tree, untimed; all CPU
// time per thread. (A mean over several traces beside Embree's fastest
// one would favour Embree.)
double trace_seconds_of(const std::function<void()>& trace) { return best_seconds_per_pass(trace, runs); }

void tree_row(const char* name, const scene_description& d, int size) {
    scene_plan plan = make_plan(d, 1e-3, std::nullopt);
    plan.tree = true;
    const double objects = double(d.world.spheres.size() + d.world.triangles.size());
    const double rays = double(size) * double(size);
    tree_figures tf;
    const double build = best_seconds([&] { tf = build_trees_only(d); }, runs);
    double trace = 0;
    const long ours_hits = count_primary_hits(d, plan, size, size, trace_seconds_of, &trace);
    std::printf("   %-22s | %10.0f | %9.1f | %8.1f | %9.1f | %7.0f", name, objects, build * 1e3,
                build * 1e3 / (objects / 1e6), rays / trace / 1e6, trace / rays * 1e9 * render_threads());
#ifdef RT_HAVE_EMBREE
    if (embree_scene::spheres_supported()) {
        std::unique_ptr<embree_scene> e;
        const double ebuild = best_seconds([&] { e.reset(), e = std::make_unique<embree_scene>(d); }, 1);
        const pinhole_camera<float> cam = float_camera(d, size);
        long hits1 = 0, hits16 = 0;
        const double single = trace_seconds_of([&] { hits1 = e->single(cam); });
        const double packets = trace_seconds_of([&] { hits16 = e->packets16(cam); });
        std::printf(" | %9.1f | %8.1f | %8.1f | %7.0f | %6.2fx | %6.2fx | %ld/%ld/%ld", ebuild * 1e3, rays / single / 1e6,
                    rays / packets / 1e6, single / rays * 1e9 * render_threads(), single / trace, packets / trace,
                    ours_hits, hits1, hits16);
    }
#endif
    std::printf(" | %.1f MB, depth %zu\n", double(tf.bytes) / 1e6, tf.depth);
    std::fflush(stdout);
}

void tree_header(const char* title, int size) {
    std::printf("\n%s, %dx%d, primary hits only (closest hit, no shading)\n", title, size, size);
    std::printf("   %-22s | %10s | %9s | %8s | %9s | %7s", "scene", "objects", "build ms", "ms/Mobj", "Mrays/s",
                "ns/ray");
#ifdef RT_HAVE_EMBREE
    std::printf(" | %9s | %8s | %8s | %7s | %7s | %7s | %s", "E build", "E1 Mr/s", "E16 Mr/s", "E1 ns", "ours/E1",
                "ours/E16", "hits ours/E1/E16");
#endif
    std::printf(" | tree\n");
    std::printf("   (ns/ray: time per ray on one thread; ours/E1 > 1 means faster than Embree's rtcIntersect1)\n");
}

void tree_table(const std::vector<int>& counts, int size) {
    tree_header("4. BVH against Embree on N random spheres", size);
    for (int n : counts) tree_row(("N = " + std::to_string(n)).c_str(), sphere_scene(n, size), size);
}

// A scene file's shapes made by an SPD generator, with the camera given.
scene_description generated_scene(spd_database db, int level, const vec3d& eye, const vec3d& at, int size,
                                  double& generation_seconds) {
    scene_description d;
    d.source = spd_name(db);
    d.camera.eye = eye, d.camera.look_at = at, d.camera.up = {0, 0, 1};
    d.camera.width = d.camera.height = size;
    d.world.materials = {material{color(0.75f, 0.75f, 0.7f), color(0), 32, true, color(0.35f, 0.35f, 0.4f)},
                         material{color(0.8f, 0.55f, 0.45f), color(0.6f), 60}};
    d.material_names = {"", ""};
    d.world.lights.push_back({vec3d(4, 3, 2), color(30, 30, 28)});
    const double cpu0 = process_cpu_seconds();
    spd_generate(db, level, d.world, {0, 1});
    generation_seconds = process_cpu_seconds() - cpu0;
    return d;
}

#ifdef RT_HAVE_EMBREE
// A scene with instances in Embree 3, which (as Debian builds it) follows
// one level of instances: RTC_MAX_INSTANCE_LEVEL_COUNT is 1. So the
// instances of instances are cut at depth `split`: the spheres of the
// objects above it go into the top-level scene as world-space point
// spheres, and each placement at depth `split` becomes one Embree instance
// (a float 3x4 transform, composed in double) of a shared scene holding
// that object flattened in its own space. For the sphereflake of level L
// cut at depth s: 1 + 9 + ... + 9^(s-1) top spheres and 9^s instances of
// one level-(L - s) flake. Spheres only (Embree has no infinite plane);
// spheres must be placed by similarities (the flake's are).
class embree_instanced_scene {
public:
    embree_instanced_scene(const scene_description& d, int split) {
        device_ = rtcNewDevice("threads=2");
        top_ = rtcNewScene(device_);
        rtcSetSceneBuildQuality(top_, RTC_BUILD_QUALITY_HIGH);
        const stopwatch sw;
        for (const instance_placement& i : d.instances) place(d, i.object, i.to_parent, 0, split);
        top_spheres = spheres_.size() / 4;  // x, y, z, r each
        if (!spheres_.empty()) {
            RTCGeometry g = point_spheres(spheres_);
            rtcAttachGeometry(top_, g);
            rtcReleaseGeometry(g);
        }
        rtcCommitScene(top_);
        build_seconds = sw.seconds();
    }
    ~embree_instanced_scene() {
        rtcReleaseScene(top_);
        for (auto& s : shared_) rtcReleaseScene(s.second);
        rtcReleaseDevice(device_);
    }
    embree_instanced_scene(const embree_instanced_scene&) = delete;
    embree_instanced_scene& operator=(const embree_instanced_scene&) = delete;

    // Primary hits over the image, one rtcIntersect1 per ray, on every core.
    long single(const pinhole_camera<float>& cam) const { return embree_single(top_, cam); }

    double build_seconds = 0;
    size_t top_spheres = 0, instances = 0, shared_spheres = 0;

private:
    RTCDevice device_;
    RTCScene top_;
    std::vector<std::pair<int, RTCScene>> shared_;  // object -> its flattened scene
    std::vector<float> spheres_;                    // x, y, z, r of the top-level spheres

    RTCGeometry point_spheres(const std::vector<float>& xyzr) {
        RTCGeometry g = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_SPHERE_POINT);
        float* v = static_cast<float*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT4,
                                                               4 * sizeof(float), xyzr.size() / 4));
        std::copy(xyzr.begin(), xyzr.end(), v);
        rtcCommitGeometry(g);
        return g;
    }

    RTCScene shared_scene(const scene_description& d, int object) {
        for (auto& s : shared_)
            if (s.first == object) return s.second;
        scene_description alone = d;  // the object alone, expanded in its own space
        alone.world = {};
        alone.instances = {instance_placement{object, {}, {}, "embree"}};
        const scene_description flat = flattened(alone);
        std::vector<float> xyzr;
        for (const auto& s : flat.world.spheres)
            xyzr.insert(xyzr.end(), {float(s.center.x), float(s.center.y), float(s.center.z), float(s.radius)});
        shared_spheres = flat.world.spheres.size();
        RTCScene scene = rtcNewScene(device_);
        rtcSetSceneBuildQuality(scene, RTC_BUILD_QUALITY_HIGH);
        RTCGeometry g = point_spheres(xyzr);
        rtcAttachGeometry(scene, g);
        rtcReleaseGeometry(g);
        rtcCommitScene(scene);
        shared_.emplace_back(object, scene);
        return scene;
    }

    void place(const scene_description& d, int object, const affine_transform& to_world, int depth, int split) {
        if (depth == split) {
            RTCGeometry g = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_INSTANCE);
            rtcSetGeometryInstancedScene(g, shared_scene(d, object));
            float xfm[12];  // column major: the linear part's columns, then the offset
            for (int c = 0; c < 3; ++c)
                for (int r = 0; r < 3; ++r) xfm[3 * c + r] = float(to_world.linear[c][r]);
            for (int r = 0; r < 3; ++r) xfm[9 + r] = float(to_world.offset[r]);
            rtcSetGeometryTransform(g, 0, RTC_FORMAT_FLOAT3X4_COLUMN_MAJOR, xfm);
            rtcCommitGeometry(g);
            rtcAttachGeometry(top_, g);
            rtcReleaseGeometry(g);
            ++instances;
            return;
        }
        const object_definition& def = d.objects[size_t(object)];
        const double scale = glm::length(to_world.linear[0]);  // a similarity: every column this long
        for (const auto& s : def.spheres) {
            const vec3d c = to_world.linear * s.center + to_world.offset;
            spheres_.insert(spheres_.end(), {float(c.x), float(c.y), float(c.z), float(s.radius * scale)});
        }
        for (const auto& i : def.instances) place(d, i.object, then(i.to_parent, to_world), depth + 1, split);
    }
};
#endif

// The sphereflake of section 6's view, light and materials, flat (the
// generator's spheres in one tree) or as instances of instances.
scene_description flake_scene(int level, bool instanced, int size, double& generation_seconds) {
    if (!instanced) return generated_scene(spd_database::balls, level, {2.1, 1.3, 1.7}, {0, 0, 0}, size, generation_seconds);
    scene_description d = generated_scene(spd_database::balls, 1, {2.1, 1.3, 1.7}, {0, 0, 0}, size, generation_seconds);
    d.world.spheres.clear(), d.world.planes.clear();
    const double cpu0 = process_cpu_seconds();
    object_definition top;
    spd_generate_instanced(spd_database::balls, level, top, d.objects, {0, 1});
    d.world.planes = top.planes;
    d.instances = top.instances;
    generation_seconds = process_cpu_seconds() - cpu0;
    return d;
}

// What section 6 measures of one flake, for the comparison at its end.
struct flake_figures {
    double render_seconds = 0, primary_seconds = 0;  // CPU per thread, after setup
    long rays = 0;
    image picture{1, 1};
    double ns_per_ray() const { return render_seconds / double(rays) * 1e9 * render_threads(); }
};

// The sphereflake by instancing at `level`: from nothing to a PNG (wall and
// CPU time), then its render and its primary rays timed without the build.
flake_figures instanced_flake_row(int level, int fsize,
                                  std::uint64_t expand_at_most = instanced_scene::default_expand_at_most) {
    const stopwatch wall;
    const double cpu0 = process_cpu_seconds();
    double generation = 0;
    const scene_description d = flake_scene(level, true, fsize, generation);
    const instanced_scene built(d, expand_at_most);
    render_stats st;
    flake_figures f;
    f.picture = render_instanced(d, built, fsize, fsize, st);
    const std::string png = (std::filesystem::temp_directory_path() / ("rt-bench-flake-" + std::to_string(level) + ".png")).string();
    write_png(f.picture, png);
    const double start_to_png = wall.seconds(), start_to_png_cpu = process_cpu_seconds() - cpu0;
    f.rays = st.rays;
    f.render_seconds = best_seconds([&] { render_instanced(d, built, fsize, fsize, st); }, 1);
    f.primary_seconds = trace_seconds_of([&] { count_primary_hits_instanced(d, built, fsize, fsize); });
    const double px = double(fsize) * fsize;
    std::printf("   level %2d by instancing (placed objects of up to %llu shapes stored expanded): %llu spheres from %zu objects; start to PNG %.2f s wall (%.2f s CPU); tree "
                "%.3f MB, built in %.1f ms; render with shadows %.2f s, %ld rays, %.0f ns/ray; primary rays only %.0f "
                "ns/ray; peak memory so far %.3f GB\n",
                level, (unsigned long long)expand_at_most, (unsigned long long)spd_expected_counts(spd_database::balls, level).spheres, d.objects.size(),
                start_to_png, start_to_png_cpu, double(built.bytes()) / 1e6, built.build_seconds() * 1e3,
                f.render_seconds, f.rays, f.ns_per_ray(), f.primary_seconds / px * 1e9 * render_threads(), peak_rss_gb());
    std::fflush(stdout);
#ifdef RT_HAVE_EMBREE
    if (embree_scene::spheres_supported()) {
        // Embree follows one level of instances: cut the flake at depth
        // level / 2 (level 8: 820 top spheres and 6,561 instances of one
        // level-4 flake of 7,381 spheres; level 10: 7,381 and 59,049 of a
        // level-5 flake of 66,430). Spheres only, against ours without the
        // ground plane on the same rays.
        scene_description no_ground = d;
        no_ground.world.planes.clear();
        const instanced_scene ours(no_ground, expand_at_most);
        long ours_hits = 0, hits1 = 0;
        const double ours_primary = trace_seconds_of([&] { ours_hits = count_primary_hits_instanced(no_ground, ours, fsize, fsize); });
        const embree_instanced_scene e(d, level / 2);
        const double single = trace_seconds_of([&] { hits1 = e.single(float_camera(d, fsize)); });
        std::printf("   level %2d in Embree (two levels: %zu top spheres, %zu instances of one flake of %zu spheres; no "
                    "ground plane): build %.2f s, primary rays %.0f ns/ray (rtcIntersect1); ours on the same spheres "
                    "%.0f ns/ray (ours/E1 %.2fx); hits ours/E1 %ld/%ld\n",
                    level, e.top_spheres, e.instances, e.shared_spheres, e.build_seconds,
                    single / px * 1e9 * render_threads(), ours_primary / px * 1e9 * render_threads(), single / ours_primary,
                    ours_hits, hits1);
        std::fflush(stdout);
    }
#endif
    return f;
}

void big_scenes(int size, bool flake, bool mesh_too, bool flakes_too = true) {
    double generation = 0;
    if (mesh_too) {
        const scene_description mesh = generated_scene(spd_database::tetra, 10, {3.2, -4.8, 2.4}, {0, 0, 0}, size,
                                                       generation);
        tree_header("5. a 1M-triangle mesh: SPD tetra size 10", size);
        tree_row("tetra 10", mesh, size);
    }
    if (!flakes_too) return;
    const int fsize = 1024;
    std::printf("\n6. the sphereflake, SPD balls, 1024x1024, one light with shadows: by instancing (levels 10 and 8; "
                "rt-render's two-level tree, tools/render/instanced_path.hpp), then flat (level 8: the same spheres "
                "in one tree)\n");
    std::printf("   (ns/ray: time per ray on one thread, CPU time; render: primary and shadow rays with shading)\n");
    instanced_flake_row(10, fsize);
    // Level 8 with its level-4 and level-6 sub-flakes (7,381 and 597,871
    // spheres) stored expanded in their own space, then with every instance
    // walked (the default).
    instanced_flake_row(8, fsize, 8192);
    instanced_flake_row(8, fsize, 600000);
    const flake_figures by_instances = instanced_flake_row(8, fsize);
    if (!flake) return;
    const scene_description d = flake_scene(8, false, fsize, generation);
    std::printf("   level  8 flat: %zu spheres and a ground plane\n", d.world.spheres.size());
    std::printf("   generation: %.2f s CPU\n", generation);
    const scene_plan plan = make_plan(d, 1e-3, std::nullopt);
    std::printf("   %s\n", plan.describe().c_str());
    tree_figures tf;
    const double build = best_seconds([&] { tf = build_trees_only(d); }, 1);
    flake_figures flat;
    const double render_trace = best_seconds_after_setup(
        [&](render_stats& st) {
            flat.picture = render_fast(d, plan, fsize, fsize, st);
            flat.rays = st.rays;
        },
        1);
    flat.render_seconds = render_trace;
    std::printf("   ours: tree build %.2f s (CPU per thread; %.1f MB, depth %zu), render with shading and shadows %.2f s "
                "after its own setup, %ld rays, %.2f Mrays/s, %.0f ns/ray; peak memory so far %.2f GB\n",
                build, double(tf.bytes) / 1e6, tf.depth, render_trace, flat.rays, double(flat.rays) / render_trace / 1e6,
                flat.ns_per_ray(), peak_rss_gb());
    std::fflush(stdout);
    const double px = double(fsize) * fsize;
    const long ours_hits = count_primary_hits(d, plan, fsize, fsize, trace_seconds_of, &flat.primary_seconds);
    const compare_result same = compare_images(by_instances.picture, flat.picture, compare_tolerance{});
    std::printf("   level 8, flat against by instancing, same run: render with shadows %.0f against %.0f ns/ray "
                "(instanced/flat %.2fx the time), primary rays %.0f against %.0f ns/ray (%.2fx); pictures: %s\n",
                flat.ns_per_ray(), by_instances.ns_per_ray(), by_instances.ns_per_ray() / flat.ns_per_ray(),
                flat.primary_seconds / px * 1e9 * render_threads(), by_instances.primary_seconds / px * 1e9 * render_threads(),
                by_instances.primary_seconds / flat.primary_seconds, same.summary(compare_tolerance{}).c_str());
    std::fflush(stdout);
#ifdef RT_HAVE_EMBREE
    if (embree_scene::spheres_supported()) {
        std::unique_ptr<embree_scene> e;
        const double ebuild = best_seconds([&] { e = std::make_unique<embree_scene>(d); }, 1);
        const pinhole_camera<float> cam = float_camera(d, fsize);
        long hits1 = 0, hits16 = 0;
        // Timed as ours just above (trace_seconds_of): a trace of these rays
        // takes a tenth of a second, and one run of it read anywhere from
        // 5.7 to 9.7 Mrays/s, so each is the fastest of `runs`.
        const double single = trace_seconds_of([&] { hits1 = e->single(cam); });
        const double packets = trace_seconds_of([&] { hits16 = e->packets16(cam); });
        std::printf("   Embree, flat (spheres only: no infinite plane in Embree): build %.2f s, primary rays %.2f Mrays/s "
                    "(rtcIntersect1), %.2f Mrays/s (rtcIntersect16); ours on the same primary rays %.2f Mrays/s "
                    "(%s); hits ours/E1/E16 %ld/%ld/%ld; peak memory %.2f GB\n",
                    ebuild, px / single / 1e6, px / packets / 1e6, px / flat.primary_seconds / 1e6,
                    plan.prec == precision::single ? "float" : "double", ours_hits, hits1, hits16, peak_rss_gb());
    }
#endif
}

// 8. Samples per second at 16 samples per pixel (stratified), the renderer
// the plan picks for each scene (render_planned): the Cornell box path traced
// (chapter 12's path loop, every ray through chapter 03's loop) and the
// sphereflake on the specialised path (16 primary rays per pixel in the
// packets, shading and shadow rays). CPU time per thread without the
// scene's setup, best of `runs`.
void samples_row(const char* name, const scene_description& d, bool path_traced, int size, int spp) {
    scene_plan plan = make_plan(d, 1e-3, std::nullopt);
    plan.spp = spp;
    plan.path_traced = path_traced;
    if (plan.sampled()) plan.prec = precision::double_;  // as rt-render draws it
    long samples = 0;
    const double seconds = best_seconds_after_setup(
        [&](render_stats& st) {
            render_planned(d, plan, size, size, st);
            samples = st.samples;
        },
        runs);
    std::printf("   %-50s | %7dx%-5d | %10ld | %9.0f | %11.3f | %s\n", name, size, size, samples, seconds * 1e3,
                double(samples) / seconds / 1e6, renderer_name(plan));
    std::fflush(stdout);
}

void samples_table(int size, bool quick) {
    constexpr int spp = 16;
    std::printf("\n8. samples per second, %d samples per pixel (stratified, one PCG32 stream per pixel)\n", spp);
    std::printf("   %-50s | %13s | %10s | %9s | %11s | %s\n", "scene", "image", "samples", "ms", "Msamples/s",
                "renderer");
    const char* box_file = RT_SCENES_DIR "/ch12-cornell-box.json";
    if (std::ifstream(box_file).good())
        samples_row("Cornell box (scenes/ch12-cornell-box.json)", load_scene_file(box_file), true, quick ? 16 : 128, spp);
    else
        std::printf("   Cornell box: %s is not there\n", box_file);
    double generation = 0;
    const int level = quick ? 2 : 6;
    const scene_description flake =
        generated_scene(spd_database::balls, level, {2.1, 1.3, 1.7}, {0, 0, 0}, size, generation);
    samples_row(("sphereflake, SPD balls size " + std::to_string(level) + " (" +
                 std::to_string(flake.world.spheres.size()) + " spheres)")
                    .c_str(),
                flake, false, size, spp);
}

}  // namespace

int main(int argc, char** argv) {
    bool quick = false;
    int size = 512;
    CLI::App app{"rt-bench: specialised vs general renderer, and brute force vs Embree"};
    app.add_flag("--quick", quick, "a tiny smoke run (small image, few scenes, one run each)");
    app.add_option("--runs", runs, "runs per figure (the fastest is printed)")->check(CLI::Range(1, 50))->capture_default_str();
    app.add_flag("--wall", wall_clock, "wall-clock time instead of CPU time per thread");
    app.add_option("--size", size, "image side in pixels")->check(CLI::Range(8, 4096))->capture_default_str();
    bool no_flake = false, flake_only = false, samples_only = false, features_only = false, trees_only = false;
    app.add_flag("--no-flake", no_flake, "leave out the flat 48-million-sphere sphereflake (section 6; its rows by instancing stay)");
    app.add_flag("--flake-only", flake_only, "section 6 only (the sphereflake by instancing and flat)");
    app.add_flag("--samples-only", samples_only, "only section 8, samples per second at 16 samples per pixel");
    app.add_flag("--features-only", features_only, "only section 2, each feature's cost (and the shadow rays')");
    app.add_flag("--trees-only", trees_only, "only sections 4 and 5, the trees against Embree on random spheres and the tetra");
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        return app.exit(e);
    }
    std::vector<int> counts = {1, 4, 16, 64, 256, 1024, 4096};  // 1024: to place the crossover with Embree
    std::vector<int> sizes = {128, 256, 512, 1024};
    std::vector<int> tree_counts = {4096, 16384, 65536, 262144, 1048576};
    if (quick) {
        size = 64;
        runs = 1;
        counts = {1, 16};
        sizes = {32, 64};
        tree_counts = {4096};
    }
    std::printf("rt-bench: %dx%d, one primary ray per pixel, %d threads, best of %d run(s), %s\n", size, size,
                render_threads(), runs,
                wall_clock ? "wall-clock time" : "time = process CPU time / threads (immune to other jobs' load)");
    try {
        if (flake_only) {
            big_scenes(size, !no_flake, false);
            return 0;
        }
        if (samples_only) {
            samples_table(size, quick);
            return 0;
        }
        if (features_only) {
            feature_table(size);
            return 0;
        }
        if (trees_only) {
            tree_table(tree_counts, size);
            if (!quick) big_scenes(size, false, true, false);
            return 0;
        }
        sphere_table(counts, size);
        feature_table(size);
        pixel_table(sizes);
        tree_table(tree_counts, size);
        if (!quick) big_scenes(size, !no_flake, true);
        samples_table(size, quick);
    } catch (const not_implemented& e) {
        std::fprintf(stderr, "rt-bench: %s\n", e.what());
        return exit_not_implemented;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "rt-bench: error: %s\n", e.what());
        return 1;
    }
    return 0;
}
