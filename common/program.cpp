#include "program.hpp"

#include "chapter_scenes.hpp"
#include "image_compare.hpp"
#include "picture_page.hpp"
#include "stub.hpp"
#include "timing.hpp"

#include <CLI/CLI.hpp>

#include <cmath>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <iterator>
#include <vector>

namespace rt {

namespace {

// Removes the kinds of shape the chapter cannot draw yet, and says so:
// "ch04: the scene's 20 triangles are left out (chapter 05)".
void leave_out_undrawn_shapes(const chapter_program& program, scene<double>& world) {
    std::string shapes, chapters;
    int kinds = 0;
    const auto leave_out = [&](auto& list, const std::string& name, const char* chapter) {
        if (list.empty()) return;
        shapes += (kinds ? " and " : "") + std::to_string(list.size()) + " " + name + (list.size() > 1 ? "s" : "");
        chapters += (kinds ? " and " : "") + std::string(chapter);
        ++kinds;
        list.clear();
    };
    if (!program.draws_planes) leave_out(world.planes, "plane", "04");
    if (!program.draws_triangles) leave_out(world.triangles, "triangle", "05");
    if (kinds > 0)
        std::fprintf(stderr, "%s: the scene's %s are left out (chapter%s %s)\n", program.id.c_str(), shapes.c_str(),
                     kinds > 1 ? "s" : "", chapters.c_str());
}

// The scene to draw: the file given with --scene, or the chapter's own.
scene_description read_scene(const chapter_program& program, const std::string& path) {
    scene_description d;
    if (path.empty()) {
        const chapter_scene own = chapter_scene_file(program.id);
        d = parse_scene(own.text, own.source);
    } else {
        d = load_scene_file(path);
        std::printf("%s: rendering the scene file %s\n", program.id.c_str(), path.c_str());
    }
    leave_out_undrawn_shapes(program, d.world);
    if (!program.draws_instances && !d.instances.empty()) {
        std::fprintf(stderr, "%s: the scene's %zu instance%s left out (chapter 10)\n", program.id.c_str(),
                     d.instances.size(), d.instances.size() > 1 ? "s are" : " is");
        d.instances.clear();
        d.objects.clear();
    }
    return d;
}

// "out/ch04.png" -> "out/ch04-diff.png"
std::string diff_path(const std::string& out) {
    std::filesystem::path p(out);
    return (p.parent_path() / (p.stem().string() + "-diff.png")).string();
}

// "out/ch04.png" -> "out/ch04-compare.html"
std::string page_path(const std::string& out) {
    std::filesystem::path p(out);
    return (p.parent_path() / (p.stem().string() + "-compare.html")).string();
}

std::vector<unsigned char> file_bytes(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw std::runtime_error(path + ": cannot be read");
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// The comparison as a page (common/picture_page.hpp) next to the output: the reference, the
// render and the difference side by side, a slider between the first two.
void write_compare_page(const chapter_program& program, const image& img, const image& diff, bool same_size,
                        const std::string& verdict, const program_options& opt) {
    picture_page page;
    page.title = program.id + " " + program.title + ": your render and the reference " + opt.compare;
    page.id = program.id;
    page.caption = verdict;
    page.reference_png = file_bytes(opt.compare);
    page.render_png = encode_png(img);
    if (same_size) page.diff_png = encode_png(diff);
    const std::string path = page_path(opt.out);
    std::ofstream out(path, std::ios::binary);
    out << picture_page_html(page);
    if (!out.flush()) throw std::runtime_error(path + ": could not write the page");
    std::printf("%s comparison page (reference, render, difference): %s\n", program.id.c_str(), path.c_str());
}

// --compare: prints the verdict and writes the comparison page; a picture past tolerance also
// leaves its difference image next to the output. Returns true when the pictures match.
bool compare_with_reference(const chapter_program& program, const image& img, const program_options& opt) {
    image diff;
    bool matched = false, same_size = false;
    std::string figures;
    if (program.noisy_picture) {
        const noisy_tolerance tol;
        const noisy_compare_result r = compare_noisy_images(img, read_png(opt.compare), tol, &diff);
        matched = r.within(), same_size = r.same_size, figures = r.summary(tol);
    } else {
        const compare_tolerance tol;
        const compare_result r = compare_images(img, read_png(opt.compare), tol, &diff);
        matched = r.within(tol), same_size = r.same_size, figures = r.summary(tol);
    }
    const std::string verdict = std::string(matched ? "match" : "MISMATCH") + ": " + figures;
    std::printf("%s compare with %s: %s\n", program.id.c_str(), opt.compare.c_str(), verdict.c_str());
    try {  // a page that cannot be written must not hide the verdict
        write_compare_page(program, img, diff, same_size, verdict, opt);
    } catch (const std::exception& e) {
        std::printf("%s comparison page not written: %s\n", program.id.c_str(), e.what());
    }
    if (!matched && same_size) {
        const std::string path = diff_path(opt.out);
        try {  // a picture that cannot be written must not hide the verdict
            write_png(diff, path);
            std::printf("%s difference image (red: past tolerance): %s\n", program.id.c_str(), path.c_str());
        } catch (const std::exception& e) {
            std::printf("%s difference image not written: %s\n", program.id.c_str(), e.what());
        }
    }
    return matched;
}

// v turned by `degrees` about the unit axis k (Rodrigues' formula; right-handed:
// counter-clockwise seen from the tip of k).
vec3d rotated(const vec3d& v, const vec3d& k, double degrees) {
    const double a = degrees * 3.14159265358979323846 / 180.0;
    const double c = std::cos(a), s = std::sin(a);
    return v * c + cross(k, v) * s + k * (dot(k, v) * (1.0 - c));
}

}  // namespace

vec3d turned_eye(const view_turn& view, const vec3d& eye, const vec3d& target, const vec3d& up) {
    if (view.is_own_view()) return eye;  // the chapter's own picture, unchanged to the last bit
    const vec3d back = eye - target;     // from the target to the eye
    if (!(length(back) > 0.0) || !(length(up) > 0.0))
        throw std::invalid_argument("--view: the camera's eye and look-at point coincide");
    const vec3d k_up = normalize(up);
    // Yaw about up, counter-clockwise seen from above: a positive angle moves
    // the eye to its right (eye (0, 0, 3) looking at the origin goes towards +x).
    const vec3d yawed = rotated(back, k_up, view.yaw_degrees);
    // Pitch about the camera's right-hand axis (up x back points to the eye's
    // right): the negative turn about it takes back towards up, raising the eye.
    const vec3d right = cross(k_up, yawed);
    if (!(length(right) > 1e-12 * length(yawed)))
        throw std::invalid_argument("--view: the camera looks straight along its up direction");
    const vec3d pitched = rotated(yawed, normalize(right), -view.pitch_degrees);
    if (!(length(cross(k_up, pitched)) > 1e-6 * length(pitched)))
        throw std::invalid_argument("--view: the turned camera would look straight along its up direction");
    return target + pitched;
}

render_function by_precision(image (*as_float)(const program_options&), image (*as_double)(const program_options&)) {
    return [=](const program_options& opt, long& rays) {
        rays = long(opt.width) * long(opt.height);  // one primary ray per pixel
        return opt.prec == precision::single ? as_float(opt) : as_double(opt);
    };
}

render_function by_precision(image (*as_float)(const program_options&, long&),
                             image (*as_double)(const program_options&, long&)) {
    return [=](const program_options& opt, long& rays) {
        return opt.prec == precision::single ? as_float(opt, rays) : as_double(opt, rays);
    };
}

void add_whole_number_option(CLI::App& app, const std::string& name, int& value, int lo, int hi,
                             const std::string& help) {
    app.add_option(name, value, help)->check(CLI::Range(lo, hi))->type_name("INT");
}

void add_flag_option(CLI::App& app, const std::string& name, bool& value, const std::string& help) {
    app.add_flag(name, value, help);
}

int run_chapter_program(int argc, char** argv, const chapter_program& program) {
    program_options opt;
    opt.out = "out/" + program.id + ".png";
    opt.width = program.default_width;
    opt.height = program.default_height;
    std::string prec = program.default_precision == precision::single ? "float" : "double";

    CLI::App app{program.id + ": renders the " + program.title + " scene to a PNG file"};
    app.add_option("-o,--out", opt.out, "PNG file to write")->capture_default_str();
    CLI::Option* width_option = app.add_option("--width", opt.width, "image width in pixels")
                                    ->check(CLI::Range(1, max_image_side))
                                    ->capture_default_str();
    CLI::Option* height_option = app.add_option("--height", opt.height, "image height in pixels")
                                     ->check(CLI::Range(1, max_image_side))
                                     ->capture_default_str();
    app.add_option("--precision", prec, "scalar type of the intersection code")
        ->check(CLI::IsMember({"float", "double"}))
        ->capture_default_str();
    app.add_option("--compare", opt.compare,
                   "reference PNG: exit 2 if the render differs past tolerance (and write the difference image)")
        ->check(CLI::ExistingFile);
    app.add_flag("--error", opt.report_error, "also report the numerical error against a higher-precision reference");
    std::vector<double> view;
    app.add_option("--view", view,
                   "YAW,PITCH: see the scene from a camera turned about the point it looks at, YAW degrees about "
                   "its up direction (positive: the eye moves right) and PITCH degrees up over the scene "
                   "(positive: the eye rises); 0,0 is the chapter's own view")
        ->delimiter(',')
        ->expected(2)
        ->check(CLI::Range(-89.0, 89.0));
    std::string scene_path;
    if (program.draws_scene)
        app.add_option("--scene", scene_path,
                       "render this scene file (scenes/README.md) with your code instead of the chapter's scene");
    if (program.default_spp > 0) {
        opt.spp = program.default_spp;
        app.add_option("--spp", opt.spp, "samples per pixel")->check(CLI::Range(1, 1 << 20))->capture_default_str();
    }
    if (program.add_options) program.add_options(app);
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        return app.exit(e);
    }
    opt.prec = prec == "float" ? precision::single : precision::double_;
    if (view.size() == 2) opt.view = {view[0], view[1]};

    try {
        if (program.draws_scene) {
            opt.scene = read_scene(program, scene_path);
            camera_description& cam = opt.scene.camera;
            cam.eye = turned_eye(opt.view, cam.eye, cam.look_at, cam.up);
            if (width_option->count() == 0) opt.width = opt.scene.camera.width;
            if (height_option->count() == 0) opt.height = opt.scene.camera.height;
        }
        long rays = 0;
        stopwatch sw;
        image img = program.render(opt, rays);
        double seconds = sw.seconds();

        std::filesystem::path out(opt.out);
        if (out.has_parent_path()) std::filesystem::create_directories(out.parent_path());
        write_png(img, opt.out);
        const std::string spp = program.default_spp > 0 ? ", " + std::to_string(opt.spp) + " spp" : "";
        std::printf("%s %s: %dx%d%s, %s, %.1f ms, %.1f Mrays/s -> %s\n", program.id.c_str(), program.title.c_str(),
                    img.width, img.height, spp.c_str(), prec.c_str(), seconds * 1e3, double(rays) / seconds / 1e6,
                    opt.out.c_str());
        if (opt.report_error) {
            const std::string report =
                program.error_report ? program.error_report(opt) : "this chapter has no error reference";
            std::printf("%s error: %s\n", program.id.c_str(), report.c_str());
        }
        if (!opt.compare.empty() && !compare_with_reference(program, img, opt)) return 2;
        return 0;
    } catch (const scene_error& e) {
        std::fprintf(stderr, "%s: %s\n", program.id.c_str(), e.what());
        return 1;
    } catch (const not_implemented& e) {
        std::fprintf(stderr, "%s: %s\n", program.id.c_str(), e.what());
        return exit_not_implemented;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "%s: error: %s\n", program.id.c_str(), e.what());
        return 1;
    }
}

int run_study(const char* name, const std::function<int()>& study) {
    try {
        return study();
    } catch (const not_implemented& e) {
        std::fprintf(stderr, "%s: %s\n", name, e.what());
        return exit_not_implemented;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "%s: error: %s\n", name, e.what());
        return 1;
    }
}

}  // namespace rt
