// rt-render — renders any scene file with the exercises the build selects.
//
//   rt-render SCENE.json [--out FILE.png] [--width W] [--height H] [--depth N] [--spp N] [--seed S] [--path]
//             [--precision auto|float|double] [--bound B] [--general] [--error] [--heatmap]
//
// Before rendering it prints its plan in one line: what the scene holds,
// what the render loop leaves out, and which precision and sphere
// formulation keep the estimated error within the bound. After rendering it
// prints the time and rays per second and, with --error, the measured error
// of the primary hits against a long double reference.
//
// Exit status: 0 rendered; 1 bad arguments or a bad scene file (the message
// names file, line, column and field); 3 an exercise the scene needs is not
// implemented yet.
#include "fast_path.hpp"
#include "general_path.hpp"
#include "instanced_path.hpp"
#include "render_planned.hpp"
#include "scene_plan.hpp"

#include "common/scene_file.hpp"
#include "common/stub.hpp"
#include "common/timing.hpp"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>

using namespace rt;
using namespace rt::render_tool;

namespace {

// The process's peak resident memory (VmHWM), in MB; 0 where /proc is not there.
double peak_memory_mb() {
    std::FILE* f = std::fopen("/proc/self/status", "r");
    if (!f) return 0;
    char line[256];
    double kb = 0;
    while (std::fgets(line, sizeof line, f))
        if (std::sscanf(line, "VmHWM: %lf kB", &kb) == 1) break;
    std::fclose(f);
    return kb / 1024;
}

// Size of object o, the unit in which hit-point errors are reported:
// a sphere's radius, a triangle's shortest edge; planes have no size, so
// their error is taken relative to the hit's distance.
double object_size(const scene<double>& w, int o, double distance) {
    size_t i = size_t(o);
    if (i < w.spheres.size()) return w.spheres[i].radius;
    i -= w.spheres.size();
    if (i < w.planes.size()) return distance;
    const auto& t = w.triangles[i - w.planes.size()];
    return std::min({length(t.b - t.a), length(t.c - t.b), length(t.a - t.c)});
}

void report_error(const scene_description& d, const scene_plan& plan, int width, int height) {
    const primary_hits got = trace_primary(d, plan, width, height);
    const primary_hits ref = trace_primary_reference(d, width, height);
    const scene_camera<double> camera(d.camera, width, height);
    long wrong = 0, compared = 0;
    std::vector<double> errors;
    for (int row = 0; row < height; ++row)
        for (int col = 0; col < width; ++col) {
            const size_t i = size_t(row) * size_t(width) + size_t(col);
            if (got.object[i] != ref.object[i]) {
                ++wrong;  // a false hit, a false miss or the wrong object
                continue;
            }
            if (ref.object[i] < 0) continue;
            const double speed = length(camera.primary_ray(col, row).direction);
            const double distance = double(ref.t[i]) * speed;
            errors.push_back(double(std::fabs(got.t[i] - ref.t[i])) * speed /
                             object_size(d.world, ref.object[i], distance));
            ++compared;
        }
    std::sort(errors.begin(), errors.end());
    auto at = [&](double q) { return errors.empty() ? 0.0 : errors[size_t(q * double(errors.size() - 1))]; };
    std::printf("error of %s %s (specialised kernels) vs long double (robust): %ld of %d pixels hit a different object; hit-point error in object "
                "sizes over %ld hits: median %.2g, 99th percentile %.2g, max %.2g (bound %.2g, estimate %.2g)\n",
                plan.prec == precision::single ? "float" : "double",
                plan.form == sphere_formulation::plain ? "plain" : "robust", wrong, width * height, compared, at(0.5),
                at(0.99), at(1.0), plan.bound, plan.estimated_error);
}

// --heatmap: OUT.png -> OUT-heatmap.png, the counts of heatmap_general, one
// line per map on stdout.
void write_heatmap(const scene_description& d, const scene_plan& plan, int width, int height, const std::string& out) {
    const bool png = out.size() > 4 && out.compare(out.size() - 4, 4, ".png") == 0;
    const std::string path = (png ? out.substr(0, out.size() - 4) : out) + "-heatmap.png";
    const std::vector<count_map> maps = heatmap_general(d, plan, width, height);
    write_png(draw_heatmap(maps), path);
    std::printf("heatmap %s (counted on the general path, chapter 08's tree; left to right; one colour scale, 0 to "
                "%ld, logarithmic):\n%s",
                path.c_str(), std::max({maps[0].max(), maps[1].max(), maps[2].max()}), heatmap_legend(maps).c_str());
}

}  // namespace

int main(int argc, char** argv) {
    std::string scene_path, out = "out/render.png", prec = "auto";
    int width = 0, height = 0, depth = 5, spp = 1;
    std::uint64_t seed = scene_plan{}.seed;
    double bound = 1e-3;
    bool general = false, error = false, heatmap = false, flatten = false, path_trace = false;

    CLI::App app{"rt-render: renders a scene file (scenes/README.md) with the exercises this build selects"};
    app.add_option("scene", scene_path, "scene file (.json)")->required();
    app.add_option("-o,--out", out, "PNG file to write")->capture_default_str();
    app.add_option("--width", width, "image width (default: the scene's)")->check(CLI::Range(1, max_image_side));
    app.add_option("--height", height, "image height (default: the scene's)")->check(CLI::Range(1, max_image_side));
    app.add_option("--depth", depth, "mirrors and glass: bounces followed after the first hit (chapter 09's --depth)")
        ->check(CLI::Range(0, 50))
        ->capture_default_str();
    app.add_option("--spp", spp, "samples per pixel, a square number (stratified on a grid): 1, 4, 9, 16, ...")
        ->check(CLI::Range(1, 4096 * 4096))
        ->capture_default_str();
    app.add_option("--seed", seed, "seed of every pixel's random stream (sampled renders)")->capture_default_str();
    app.add_flag("--path", path_trace, "path trace the scene (chapter 12): sphere lights, diffuse surfaces, bounces");
    app.add_option("--precision", prec, "auto: the cheapest that meets --bound")
        ->check(CLI::IsMember({"auto", "float", "double"}))
        ->capture_default_str();
    app.add_option("--bound", bound, "largest acceptable hit-point error, in object sizes")
        ->check(CLI::PositiveNumber)
        ->capture_default_str();
    app.add_flag("--general", general, "force the general path (every loop, chapter exercises) to measure the saving");
    app.add_flag("--heatmap", heatmap,
                 "also write OUT-heatmap.png: boxes opened and objects asked per pixel by chapter 08's tree "
                 "(counted on the general path) and by brute force");
    app.add_flag("--flatten", flatten,
                 "expand a scene's instances into world-space shapes and render those (flat), to compare with the "
                 "two-level tree");
    app.add_flag("--error", error, "measure the primary hits' error against a long double reference");
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        return app.exit(e);
    }

    if (const int side = int(std::lround(std::sqrt(double(spp)))); side * side != spp) {
        std::fprintf(stderr, "rt-render: --spp expects a square number of samples per pixel (1, 4, 9, 16, ...): they "
                             "are stratified on a grid of sqrt(N) x sqrt(N) cells; got %d\n", spp);
        return 1;
    }
    try {
        scene_description scene = load_scene_file(scene_path);
        const int w = width > 0 ? width : scene.camera.width, h = height > 0 ? height : scene.camera.height;
        // Instances: the two-level tree, unless --flatten (or --general, which
        // has no instances before chapter 10) asks for the scene expanded.
        if (!scene.instances.empty() && (flatten || general)) {
            const stopwatch sw;
            scene = flattened(scene);
            std::fprintf(stderr, "flattened: %zu spheres, %zu planes, %zu triangles in %.1f ms\n",
                         scene.world.spheres.size(), scene.world.planes.size(), scene.world.triangles.size(),
                         sw.seconds() * 1e3);
        }
        if (!scene.instances.empty()) {
            if (error || heatmap) throw std::runtime_error("--error and --heatmap do not draw instances (use --flatten)");
            const stopwatch sw;
            const instanced_scene built(scene);
            std::printf("plan: %s; %zu lights%s\n", built.describe().c_str(), scene.world.lights.size(),
                        scene.world.lights.empty() ? "" : ": shading + shadow rays");
            std::fflush(stdout);
            render_stats stats;
            stats.setup_seconds = sw.seconds();
            image img = render_instanced(scene, built, w, h, stats);
            const double seconds = sw.seconds(), tracing = seconds - stats.setup_seconds;
            std::filesystem::path path(out);
            if (path.has_parent_path()) std::filesystem::create_directories(path.parent_path());
            write_png(img, out);
            std::printf("rendered %s: %dx%d, specialised path (instances), %.1f ms (setup %.1f ms, tracing and shading "
                        "%.1f ms), %ld rays (%ld primary), %.2f Mrays/s while tracing, peak memory %.0f MB -> %s\n",
                        scene_path.c_str(), w, h, seconds * 1e3, stats.setup_seconds * 1e3, tracing * 1e3, stats.rays,
                        long(w) * long(h), double(stats.rays) / tracing / 1e6, peak_memory_mb(), out.c_str());
            return 0;
        }
        std::optional<precision> forced;
        if (prec == "float") forced = precision::single;
        if (prec == "double") forced = precision::double_;
        scene_plan plan = make_plan(scene, bound, forced);
        plan.depth = depth;
        plan.spp = spp;
        plan.seed = seed;
        plan.path_traced = plan.path_traced || path_trace;
        // Mirrors and glass (chapter 09's trace) and sampled renders (chapters
        // 11 and 12): in double unless told, as the chapters' programs draw
        // them, on either path.
        if (general || plan.secondary_rays() || plan.sampled()) plan.prec = forced.value_or(precision::double_);
        if (plan.sampled() && (error || heatmap))
            throw std::runtime_error("--error and --heatmap measure one primary ray per pixel, not a sampled render");
        if (general && spp > 1 && !plan.sampled())
            throw std::runtime_error("--general draws one ray per pixel (chapter 03 to 08's loops): leave out --spp "
                                     "or --general");
        plan.general = general;
        std::printf("%s\n", plan.describe().c_str());
        std::fflush(stdout);

        render_stats stats;
        stopwatch sw;
        image img = render_planned(scene, plan, w, h, stats);
        const double seconds = sw.seconds();
        const double tracing = seconds - stats.setup_seconds;  // rays per second leave the tree's build out

        std::filesystem::path path(out);
        if (path.has_parent_path()) std::filesystem::create_directories(path.parent_path());
        write_png(img, out);
        const char* path_name = renderer_name(plan);
        const bool on_isa = !general && !plan.secondary_rays() && !plan.sampled();
        std::printf("rendered %s: %dx%d, %s path%s%s, %.1f ms (setup %.1f ms, tracing and shading %.1f ms), %ld %s, "
                    "%.2f M%s/s while tracing -> %s\n",
                    scene_path.c_str(), w, h, path_name, on_isa ? " on " : "", on_isa ? fast_path_isa() : "",
                    seconds * 1e3, stats.setup_seconds * 1e3, tracing * 1e3, stats.rays,
                    stats.primary_only ? "primary rays (the chapter's loop does not count its secondary and shadow rays)"
                                       : ("rays (" + std::to_string(stats.samples > 0 ? stats.samples : long(w) * long(h)) +
                                          " primary)").c_str(),
                    double(stats.rays) / tracing / 1e6, stats.primary_only ? " primary rays" : "rays", out.c_str());
        if (stats.samples > 0)
            std::printf("samples: %ld (%d per pixel), %.3f Msamples/s while tracing\n", stats.samples, plan.spp,
                        double(stats.samples) / tracing / 1e6);
        if (error) report_error(scene, plan, w, h);
        if (heatmap) write_heatmap(scene, plan, w, h, out);
        return 0;
    } catch (const scene_error& e) {
        std::fprintf(stderr, "rt-render: %s\n", e.what());
        return 1;
    } catch (const not_implemented& e) {
        std::fprintf(stderr, "rt-render: %s\n", e.what());
        return exit_not_implemented;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "rt-render: error: %s\n", e.what());
        return 1;
    }
}
