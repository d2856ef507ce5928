// program.hpp — the shared front end of every chapter's program.
//
// A chapter program only says how to render its scene; this file gives all
// of them the same command line, the same report and the same polite exit
// when a stub is reached:
//
//   ch01-unit-sphere [--out FILE.png] [--width W] [--height H]
//                    [--precision float|double] [--compare REFERENCE.png] [--error]
//                    [--view YAW,PITCH]
//                    [--scene FILE.json]   (chapters 03 on, which draw scene files)
//                    [--spp N]             (chapters 11 on, which take several samples per pixel)
//
// --view YAW,PITCH sees the scene from a camera turned about the point it
// looks at: YAW degrees about the camera's up direction (positive: the eye
// moves to its right, the scene turns to the left), then PITCH degrees up
// over the scene (positive: the eye rises and looks down more steeply).
// 0,0 is the chapter's own view, exactly. The autograder grades the picture
// from a view it draws at random near 0,0 for each grading, so a picture
// cannot be known before the code that draws it runs.
//
// With --compare, a picture past tolerance also leaves its difference image
// next to the output (out/ch04-diff.png for out/ch04.png) and names it, and
// every comparison writes a page showing the reference, the render and the
// difference side by side (out/ch04-compare.html, common/picture_page.hpp).
//
// and prints one line such as
//   ch01 unit sphere: 400x300, 3.1 ms, 38.7 Mrays/s -> out/ch01.png
#pragma once

#include "image.hpp"
#include "scene_file.hpp"

#include <functional>
#include <string>

namespace CLI {
class App;
}

namespace rt {

enum class precision { single, double_ };

// --view: how far the camera is turned from the chapter's own view, in degrees.
struct view_turn {
    double yaw_degrees = 0;    // about the camera's up direction; positive moves the eye to its right
    double pitch_degrees = 0;  // then about its right-hand axis; positive raises the eye
    bool is_own_view() const { return yaw_degrees == 0 && pitch_degrees == 0; }
};

// The eye of a camera at `eye` looking at `target`, turned by `view` about
// the target (the distance to the target is kept; `up` says which way is up).
// The chapter's own view (0,0) returns `eye` itself, bit for bit. Throws
// std::invalid_argument when the turned eye would look along `up`.
vec3d turned_eye(const view_turn& view, const vec3d& eye, const vec3d& target, const vec3d& up);

struct program_options {
    std::string out;          // PNG to write
    int width = 0, height = 0;
    precision prec = precision::double_;
    std::string compare;      // optional reference PNG to compare against
    bool report_error = false;  // --error: also print the render's numerical error (chapter_program::error_report)
    // --view: programs that draw opt.scene get its camera already turned; a
    // program with its own camera turns it with turned_eye(opt.view, ...).
    view_turn view;
    // Programs with chapter_program::draws_scene: the scene to draw, already
    // read and checked: the chapter's own scenes/chNN-*.json, or the file
    // given with --scene. Kinds of shape the chapter cannot draw yet are
    // removed. width and height default to its camera's resolution.
    scene_description scene;
    // --spp: samples per pixel, for programs with chapter_program::default_spp > 0 (1 otherwise).
    int spp = 1;
};

// How a chapter draws its picture; rays_traced is how many rays it cast in
// all (primary and, in later chapters, shadow rays), for the rays/s figure.
using render_function = std::function<image(const program_options&, long& rays_traced)>;

// The usual render_function: the chapter's drawing code instantiated in both
// precisions, picked by --precision. The first form counts one ray per pixel;
// the second counts its own rays (shadow rays as well).
//   program.render = rt::by_precision(render_scene<float>, render_scene<double>);
render_function by_precision(image (*as_float)(const program_options&), image (*as_double)(const program_options&));
render_function by_precision(image (*as_float)(const program_options&, long&),
                             image (*as_double)(const program_options&, long&));

struct chapter_program {
    std::string id;           // "ch01"
    std::string title;        // "unit sphere"
    int default_width = 400;
    int default_height = 300;
    precision default_precision = precision::double_;  // when --precision is not given
    render_function render;  // draws the chapter's picture (usually by_precision(...))
    // Optional: with --error, called after the timed render; returns one line
    // describing the render's error against a higher-precision reference
    // (where a reference exists, the error is part of the report). Not part of the time.
    std::function<std::string(const program_options&)> error_report;
    // True when render() draws opt.scene: only then does the program read its
    // scene file and offer --scene (so no program silently ignores it).
    bool draws_scene = false;
    // > 0: render() takes several samples per pixel (chapters 11 on); the
    // program offers --spp N and opt.spp is this unless N is given.
    int default_spp = 0;
    // The kinds of shape render() can intersect besides spheres. A scene's
    // other shapes are left out, and the program says so.
    bool draws_planes = true;
    bool draws_triangles = true;
    bool draws_instances = false;  // chapter 10 on: a scene file's "instances" (else left out, and said so)
    // True for a Monte Carlo picture (chapter 12): --compare judges it by
    // statistics, tile by tile (image_compare.hpp, compare_noisy_images),
    // not by a pixel threshold that noise alone would fail.
    bool noisy_picture = false;
    // Optional: adds the chapter's own options (chapter 12's --spp) to the
    // command line before it is parsed; they are listed in --help with the rest.
    std::function<void(CLI::App&)> add_options;
};

// A chapter's own options (chapter 08's --level and --heatmap, 09's --depth,
// 10's --level and --copies), for chapter_program::add_options: parsed and
// checked with the shared ones and listed in --help beside them.
//   "NAME N": a whole number from lo to hi, stored in value (left as it is
//   when the option is not given); anything else is refused with a message.
//   "NAME": a flag, value set to true when it is given.
//   program.add_options = [](CLI::App& app) {
//       rt::add_whole_number_option(app, "--depth", depth, 0, 50, "bounces followed after the first hit");
//   };
void add_whole_number_option(CLI::App& app, const std::string& name, int& value, int lo, int hi,
                             const std::string& help);
void add_flag_option(CLI::App& app, const std::string& name, bool& value, const std::string& help);

// Parses argv, renders, writes the PNG and prints the report line.
// Returns the process exit status: 0 on success, 1 on bad arguments or an
// error, 2 when --compare finds the picture past tolerance, and
// rt::exit_not_implemented (3) when the render reached an exercise stub.
int run_chapter_program(int argc, char** argv, const chapter_program& program);

// main() of a chapter's study, a measurement with its own command line
// (ch11-sampling-study, ch12-path-study): returns study's exit status, and
// stops politely as run_chapter_program does when it throws: a stub reached
// prints "NAME: not implemented yet: ..." and returns rt::exit_not_implemented,
// any other error "NAME: error: ..." and returns 1.
//   int main(int argc, char** argv) { return rt::run_study("ch12-path-study", [&] { return study(argc, argv); }); }
int run_study(const char* name, const std::function<int()>& study);

}  // namespace rt
