// scene_plan.hpp — looking at a scene once, before rendering, to decide
// what the render loop needs and what it can leave out.
//
// Three questions decide the plan:
//   1. Which kinds of object are there? A loop over triangles in a scene
//      without triangles costs a test per pixel for nothing.
//   2. Are there lights? Without lights there is no shading model to apply
//      and no shadow ray to cast.
//   3. Does any surface send secondary rays? A mirror or a glass surface
//      (chapter 09's materials) needs reflected and refracted rays, a matte
//      scene none: the primary-ray fast path is kept for it.
//   4. How well conditioned is the scene? The precision chapter shows that
//      the plain sphere formula loses digits as the square of
//          conditioning = (size of the scene) / (size of its smallest object)
//      and the robust formula only in proportion to it. The plan picks the
//      cheapest formulation and precision whose estimated error stays
//      within a stated bound.
#pragma once

#include "common/program.hpp"
#include "common/scene_file.hpp"

#include <cstdint>
#include <optional>
#include <string>

namespace rt::render_tool {

enum class sphere_formulation { plain, robust };

struct scene_plan {
    // What the scene holds.
    size_t spheres = 0, planes = 0, triangles = 0, lights = 0;
    bool pinhole = true;

    // Secondary rays (chapter 09): how many objects have a mirror material
    // (any mirror component > 0) and how many a glass one (ior > 0). With
    // either, the picture is chapter 09's recursive trace, `depth` bounces
    // deep; without, no reflected or refracted ray is ever made.
    size_t mirrors = 0, glass = 0;
    int depth = 5;  // bounces after the first hit (rt-render --depth N); chapter 09's default
    bool secondary_rays() const { return mirrors + glass > 0; }

    // Sampling (chapters 11 and 12): samples per pixel (rt-render --spp N, a
    // square number: they are stratified), the seed of every pixel's stream,
    // the sphere lights (lights with a radius, soft shadows), a lens
    // (aperture > 0, depth of field) and the path tracer (rt-render --path).
    // With spp 1 and none of the others a pixel is one primary ray through
    // its centre, as before; with more samples and only point lights the
    // specialised path traces every sample's primary ray (fast_path.cpp).
    int spp = 1;
    std::uint64_t seed = 11;  // chapter 11's, so rt-render's picture of chapter 11's scene is the chapter's
    size_t sphere_lights = 0;
    double aperture = 0;
    // Path traced: a scene whose shapes emit light (a material's "emission",
    // chapter 12) is drawn by the path tracer, the only renderer that draws
    // emission; rt-render --path asks for it for any scene. emitting_spheres
    // and the sphere lights are what next-event estimation samples; an
    // emitting plane is found by bounces only.
    bool path_traced = false;
    size_t emitting_spheres = 0;
    bool emitting_planes = false;
    // The path tracer: whether any path needs a second vertex. Not when light
    // can reach a diffuse surface only straight from a light (at most one
    // diffuse object, which is convex, and a black background): then every
    // bounce would bring back nothing that next-event estimation has not
    // already counted.
    bool bounces = true;
    // Drawn by the chapters' samplers (sampled_path.hpp), not the specialised path.
    bool sampled() const { return path_traced || sphere_lights > 0 || aperture > 0 || (secondary_rays() && spp > 1); }

    // Conditioning: extent is the diagonal of the box around the eye, the
    // lights, the spheres and the triangles; smallest is the smallest sphere
    // radius or triangle edge.
    double extent = 0, smallest = 0;
    double conditioning() const { return smallest > 0 ? extent / smallest : 1; }

    // The choice, and the estimated hit-point error it gives, in units of
    // the smallest object's size.
    precision prec = precision::double_;
    sphere_formulation form = sphere_formulation::plain;
    double estimated_error = 0;
    double bound = 1e-3;
    // Search structure: brute force tests every object for every packet of
    // rays (cheap per object: most are culled after one discriminant), a
    // tree about 2 log2(N) boxes and a few objects per ray but must first be
    // built. rt-bench measures brute force level with a tree at a few
    // hundred objects; from tree_threshold spheres + triangles on, the
    // tree is used (planes, unbounded, stay in the brute-force loop).
    static constexpr size_t tree_threshold = 128;
    bool tree = false;

    bool general = false;          // the general path was forced (--general)
    bool precision_forced = false; // --precision fixed the precision

    // The plan in one line, naming what was left out.
    std::string describe() const;

private:
    std::string describe_sampled() const;  // describe() when sampled()
};

// What a render did besides its picture: the rays it traced (primary and
// shadow) and the time spent on setup (the scene's arrays and trees) before
// the first ray, so that rays per second can leave the setup out.
struct render_stats {
    long rays = 0;
    long samples = 0;              // sampled renders: samples taken (width * height * spp); 0 otherwise
    double setup_seconds = 0;      // wall clock: arrays and trees, before the first ray
    double setup_cpu_seconds = 0;  // the same as CPU time of the whole process (process_cpu_seconds)
    bool primary_only = false;     // rays counts the primary rays only (a chapter's loop that does not count its own)
};

// Estimated hit-point error, in object sizes, of a formulation in a precision
// for a scene of the given conditioning (see scene_plan.cpp for the model).
double estimated_error(precision p, sphere_formulation f, double conditioning, bool has_spheres, bool has_triangles);

// Analyses the scene and picks the cheapest (precision, formulation) whose
// estimated error is within `bound`; `forced` fixes the precision instead.
scene_plan make_plan(const scene_description& scene, double bound, std::optional<precision> forced);

}  // namespace rt::render_tool
