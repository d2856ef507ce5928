#include "program.hpp"

#include "image_compare.hpp"
#include "stub.hpp"
#include "timing.hpp"

#include <CLI/CLI.hpp>

#include <cstdio>
#include <exception>
#include <filesystem>

namespace rt {

int run_chapter_program(int argc, char** argv, const chapter_program& program) {
    program_options opt;
    opt.out = "out/" + program.id + ".png";
    opt.width = program.default_width;
    opt.height = program.default_height;
    std::string prec = program.default_precision == precision::single ? "float" : "double";

    CLI::App app{program.id + ": renders the " + program.title + " scene to a PNG file"};
    app.add_option("-o,--out", opt.out, "PNG file to write")->capture_default_str();
    app.add_option("--width", opt.width, "image width in pixels")->check(CLI::Range(1, 16384))->capture_default_str();
    app.add_option("--height", opt.height, "image height in pixels")->check(CLI::Range(1, 16384))->capture_default_str();
    app.add_option("--precision", prec, "scalar type of the intersection code")
        ->check(CLI::IsMember({"float", "double"}))
        ->capture_default_str();
    app.add_option("--compare", opt.compare, "reference PNG: exit 2 if the render differs past tolerance")
        ->check(CLI::ExistingFile);
    app.add_flag("--error", opt.report_error, "also report the numerical error against a higher-precision reference");
    std::string scene_path;
    CLI::Option* width_option = app.get_option("--width");
    CLI::Option* height_option = app.get_option("--height");
    if (program.accepts_scene_file)
        app.add_option("--scene", scene_path,
                       "render this scene file (scenes/README.md) with your code instead of the chapter's scene");
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        return app.exit(e);
    }
    if (!scene_path.empty()) {
        try {
            opt.scene_file = load_scene_file(scene_path);
        } catch (const scene_error& e) {
            std::fprintf(stderr, "%s: %s\n", program.id.c_str(), e.what());
            return 1;
        }
        if (width_option->count() == 0) opt.width = opt.scene_file->camera.width;
        if (height_option->count() == 0) opt.height = opt.scene_file->camera.height;
        std::printf("%s: rendering the scene file %s\n", program.id.c_str(), scene_path.c_str());
    }
    opt.prec = prec == "float" ? precision::single : precision::double_;

    try {
        long rays = 0;
        stopwatch sw;
        image img = program.render(opt, rays);
        double seconds = sw.seconds();

        std::filesystem::path out(opt.out);
        if (out.has_parent_path()) std::filesystem::create_directories(out.parent_path());
        write_png(img, opt.out);
        std::printf("%s %s: %dx%d, %s, %.1f ms, %.1f Mrays/s -> %s\n", program.id.c_str(), program.title.c_str(),
                    img.width, img.height, prec.c_str(), seconds * 1e3, double(rays) / seconds / 1e6,
                    opt.out.c_str());
        if (opt.report_error) {
            const std::string report =
                program.error_report ? program.error_report(opt) : "this chapter has no error reference";
            std::printf("%s error: %s\n", program.id.c_str(), report.c_str());
        }

        if (!opt.compare.empty()) {
            compare_tolerance tol;
            compare_result r = compare_images(img, read_png(opt.compare), tol);
            std::printf("%s compare with %s: %s: %s\n", program.id.c_str(), opt.compare.c_str(),
                        r.within(tol) ? "match" : "MISMATCH", r.summary(tol).c_str());
            if (!r.within(tol)) return 2;
        }
        return 0;
    } catch (const not_implemented& e) {
        std::fprintf(stderr, "%s: %s\n", program.id.c_str(), e.what());
        return exit_not_implemented;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "%s: error: %s\n", program.id.c_str(), e.what());
        return 1;
    }
}

}  // namespace rt
