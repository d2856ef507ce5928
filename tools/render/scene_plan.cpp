#include "scene_plan.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <vector>

namespace rt::render_tool {

namespace {

double epsilon_of(precision p) {
    return p == precision::single ? double(std::numeric_limits<float>::epsilon())
                                  : std::numeric_limits<double>::epsilon();
}

const char* name_of(precision p) { return p == precision::single ? "float" : "double"; }
const char* name_of(sphere_formulation f) { return f == sphere_formulation::plain ? "plain" : "robust"; }

bool is_black(const color& c) { return !(c.r > 0 || c.g > 0 || c.b > 0); }

// How many objects reflect diffusely (a diffuse colour above 0), counting up
// to 2: the path tracer only asks whether there is more than one.
size_t diffuse_objects(const scene<double>& w) {
    size_t n = 0;
    auto count = [&](const auto& shapes) {
        for (const auto& shape : shapes) {
            if (n >= 2) return;
            n += !is_black(w.materials[size_t(shape.material)].diffuse);
        }
    };
    count(w.spheres);
    count(w.planes);
    count(w.triangles);
    return n;
}

bool is_mirror(const material& m) { return m.mirror.r > 0 || m.mirror.g > 0 || m.mirror.b > 0; }
bool is_glass(const material& m) { return m.ior > 0; }

// How many objects have a mirror and how many a glass material. The
// materials are few, the objects may be millions: the objects are only
// counted when some material is shiny at all.
void count_shiny_objects(const scene<double>& w, size_t& mirrors, size_t& glass) {
    mirrors = glass = 0;
    if (std::none_of(w.materials.begin(), w.materials.end(),
                     [](const material& m) { return is_mirror(m) || is_glass(m); }))
        return;
    auto count = [&](const auto& shapes) {
        for (const auto& shape : shapes) {
            const material& m = w.materials[size_t(shape.material)];
            mirrors += is_mirror(m);
            glass += is_glass(m);
        }
    };
    count(w.spheres);
    count(w.planes);
    count(w.triangles);
}

}  // namespace

// The error model (precision chapter). With k = conditioning and eps the
// precision's machine epsilon:
//   * plain quadratic: the discriminant b^2 - c is a difference of two
//     numbers of size (distance)^2 whose true difference is at most
//     radius^2, so its absolute error is about eps * distance^2; through
//     the square root that moves the hit by about eps * k^2 / 2 radii.
//   * robust form (perpendicular foot, stable roots): the foot is formed
//     before squaring, so the error grows only like eps * k.
//   * triangles (plane crossing then edge tests): the crossing point is
//     known to about eps * distance, i.e. eps * k edge lengths.
// A safety factor of 4 covers the few roundings each formula adds.
double estimated_error(precision p, sphere_formulation f, double conditioning, bool has_spheres, bool has_triangles) {
    const double eps = epsilon_of(p), k = std::max(conditioning, 1.0), safety = 4;
    double error = 0;
    if (has_spheres) error = std::max(error, safety * eps * (f == sphere_formulation::plain ? k * k / 2 : k));
    if (has_triangles) error = std::max(error, safety * eps * k);
    return error;
}

scene_plan make_plan(const scene_description& scene, double bound, std::optional<precision> forced) {
    const auto& w = scene.world;
    scene_plan plan;
    plan.spheres = w.spheres.size();
    plan.planes = w.planes.size();
    plan.triangles = w.triangles.size();
    plan.lights = w.lights.size();
    plan.tree = plan.spheres + plan.triangles >= scene_plan::tree_threshold;
    count_shiny_objects(w, plan.mirrors, plan.glass);
    plan.sphere_lights = size_t(std::count_if(w.lights.begin(), w.lights.end(),
                                              [](const point_light& l) { return l.radius > 0; }));
    plan.aperture = scene.camera.type == camera_description::kind::pinhole ? scene.camera.aperture : 0;
    plan.bounces = !(diffuse_objects(w) <= 1 && is_black(w.background));
    for (const auto& x : w.spheres) plan.emitting_spheres += !is_black(w.materials[size_t(x.material)].emission);
    for (const auto& x : w.planes) plan.emitting_planes = plan.emitting_planes || !is_black(w.materials[size_t(x.material)].emission);
    plan.path_traced = plan.emitting_spheres > 0 || plan.emitting_planes;
    plan.pinhole = scene.camera.type == camera_description::kind::pinhole;
    plan.bound = bound;
    plan.precision_forced = forced.has_value();

    // The box around everything a ray starts from or can hit (planes are
    // unbounded and have no size, so they take no part).
    vec3d lo = scene.camera.eye, hi = scene.camera.eye;
    auto grow = [&](const vec3d& p) {
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    };
    for (const auto& l : w.lights) grow(l.position);
    double smallest = std::numeric_limits<double>::infinity();
    for (const auto& s : w.spheres) {
        grow(s.center - vec3d(s.radius));
        grow(s.center + vec3d(s.radius));
        smallest = std::min(smallest, s.radius);
    }
    for (const auto& t : w.triangles) {
        grow(t.a), grow(t.b), grow(t.c);
        smallest = std::min({smallest, length(t.b - t.a), length(t.c - t.b), length(t.a - t.c)});
    }
    plan.extent = length(hi - lo);
    plan.smallest = std::isfinite(smallest) ? smallest : 0;

    const bool spheres = plan.spheres > 0, triangles = plan.triangles > 0;
    const double k = plan.conditioning();
    // Cheapest first: float is twice as wide per vector register as double,
    // so float robust beats double plain.
    const std::pair<precision, sphere_formulation> order[] = {
        {precision::single, sphere_formulation::plain},
        {precision::single, sphere_formulation::robust},
        {precision::double_, sphere_formulation::plain},
        {precision::double_, sphere_formulation::robust},
    };
    bool chosen = false;
    for (const auto& [p, f] : order) {
        if (forced && p != *forced) continue;
        if (f == sphere_formulation::robust && !spheres) continue;
        plan.prec = p;
        plan.form = f;
        plan.estimated_error = estimated_error(p, f, k, spheres, triangles);
        if (plan.estimated_error <= bound) {
            chosen = true;
            break;
        }
    }
    if (!chosen) {  // nothing meets the bound: the most accurate there is
        plan.prec = forced ? *forced : precision::double_;
        plan.form = sphere_formulation::robust;
        plan.estimated_error = estimated_error(plan.prec, plan.form, k, spheres, triangles);
    }
    return plan;
}

// The three sampled renders (sampled_path.hpp): the path tracer, chapter
// 11's picture, and chapter 09's trace per sample.
std::string scene_plan::describe_sampled() const {
    auto join = [](const std::vector<std::string>& items) {
        std::string out;
        for (const std::string& item : items) out += (out.empty() ? "" : ", ") + item;
        return out.empty() ? std::string("nothing") : out;
    };
    const std::string shapes = std::to_string(spheres) + " spheres, " + std::to_string(planes) + " planes, " +
                               std::to_string(triangles) + " triangles";
    const std::string pixel = std::to_string(spp) + " samples per pixel, stratified (chapter 11's stratified_sample, "
                                                    "one PCG32 stream per pixel)";
    char aperture_text[32];
    std::snprintf(aperture_text, sizeof aperture_text, "%g", aperture);
    const std::string lens = aperture > 0 ? std::string("thin lens of aperture ") + aperture_text : "";
    std::vector<std::string> kept, left_out;
    std::string what;
    if (path_traced) {
        what = "path tracer (chapter 12)";
        kept.push_back(pixel + ", box filter");
        if (sphere_lights + emitting_spheres)
            kept.push_back("next-event estimation of " + std::to_string(sphere_lights + emitting_spheres) +
                           " sphere lights (chapter 11's cone sample)");
        else
            left_out.push_back("light sampling (no sphere lights)");
        if (emitting_planes) kept.push_back("emitting planes (met by bounces)");
        if (bounces)
            kept.push_back("cosine-weighted bounces, Russian roulette after 3, at most 24 vertices");
        else
            left_out.push_back("bounces (at most one diffuse object and a black background: no diffuse "
                               "interreflection, one vertex per path)");
        if (!lens.empty()) kept.push_back(lens); else left_out.push_back("the lens (aperture 0)");
        if (lights > sphere_lights)
            left_out.push_back(std::to_string(lights - sphere_lights) + " point lights (no area: no path meets one)");
        if (triangles) left_out.push_back(std::to_string(triangles) + " triangles (chapter 12 draws spheres and planes)");
        if (glass) kept.push_back(std::to_string(glass) + " glass objects (chapter 09's optics, one ray of the two per path)");
        left_out.push_back("ambient, highlights, checkers, mirrors (chapter 12's surfaces are matte or glass, and "
                           "emit)");
    } else if (secondary_rays()) {
        what = "sampled recursive trace (chapters 11 and 09)";
        kept.push_back(pixel + ", box filter, each sample chapter 09's trace (" + std::to_string(depth) + " bounces)");
        if (!lens.empty()) kept.push_back(lens); else left_out.push_back("the lens (aperture 0)");
        if (sphere_lights) left_out.push_back("soft shadows (chapter 09 lights a sphere light as its centre)");
        else left_out.push_back("light sampling (no sphere lights)");
    } else {
        what = "sampled (chapter 11's picture)";
        kept.push_back(pixel + ", tent filter");
        if (sphere_lights)
            kept.push_back(std::to_string(sphere_lights) + " sphere lights sampled by cone (soft shadows)");
        else
            left_out.push_back("light sampling (no sphere lights)");
        if (lights > sphere_lights) kept.push_back(std::to_string(lights - sphere_lights) + " point lights");
        if (!lens.empty()) kept.push_back(lens); else left_out.push_back("the lens (aperture 0)");
        left_out.push_back("highlights (chapter 11 lights the diffuse term)");
        left_out.push_back("bounces (no path tracer)");
    }
    return "plan: " + what + ": " + shapes + ", " + std::to_string(lights) + " lights; " + join(kept) +
           "; every ray through chapter 03's loop (chapters 02, 04, 05), " + name_of(prec) + "; left out: " +
           join(left_out);
}

std::string scene_plan::describe() const {
    if (sampled()) return describe_sampled();
    char buffer[1200];
    if (general) {
        std::snprintf(buffer, sizeof buffer,
                      "plan: GENERAL path (forced): %zu spheres, %zu planes, %zu triangles, %zu lights; "
                      "every object type tested through %s, %s, chapter 02's sphere test, "
                      "chapter 06 shading%s; nothing left out%s",
                      spheres, planes, triangles, lights,
                      tree ? "chapter 08's tree (build_sah, closest_hit, any_hit; planes one by one)"
                           : "chapter 03's loop",
                      name_of(prec), lights ? " with shadow rays" : "",
                      secondary_rays() ? " (mirrors and glass: chapter 09's recursive trace, every ray through chapter "
                                         "03's loop)"
                                       : "");
        return buffer;
    }
    const size_t bounded = spheres + triangles;
    const std::string search =
        tree ? "BVH over " + std::to_string(bounded) + " spheres and triangles (brute force would test all of them per ray)"
             : "brute force (" + std::to_string(bounded) + " spheres and triangles, fewer than " +
                   std::to_string(tree_threshold) + ": a tree would not pay for its build)";
    std::string kept, left_out;
    auto note = [](std::string& list, const std::string& item) { list += (list.empty() ? "" : ", ") + item; };
    if (spheres) note(kept, std::to_string(spheres) + " spheres"); else note(left_out, "sphere loop");
    if (planes) note(kept, std::to_string(planes) + " planes"); else note(left_out, "plane loop");
    if (triangles) note(kept, std::to_string(triangles) + " triangles"); else note(left_out, "triangle loop");
    if (lights) note(kept, std::to_string(lights) + " lights: shading + shadow rays");
    else note(left_out, "lighting and shadow rays (no lights)");
    if (secondary_rays()) {
        // Chapter 09's trace draws the whole picture: its own closest hit
        // (chapter 03's loop over chapters 02, 04 and 05), its shadow rays,
        // its recursion. The specialised kernels and the tree take no part.
        std::string rays;
        if (mirrors) rays = "reflected rays (" + std::to_string(mirrors) + " mirror objects)";
        if (glass)
            rays += (rays.empty() ? "" : ", ") + std::string("reflected and refracted rays (") + std::to_string(glass) +
                    " glass objects)";
        std::snprintf(buffer, sizeof buffer,
                      "plan: recursive trace (chapter 09): %zu spheres, %zu planes, %zu triangles, %zu lights%s; "
                      "secondary rays: %s, up to %d bounces, each from the error-bound offset origin; every ray "
                      "through chapter 03's loop (chapters 02, 04, 05), %s; left out: the specialised kernels and "
                      "the tree (the recursion is chapter 09's)",
                      spheres, planes, triangles, lights, lights ? " (shading + shadow rays)" : "", rays.c_str(), depth,
                      name_of(prec));
        return buffer;
    }
    note(left_out, "reflection and refraction (no mirror or glass)");
    std::snprintf(buffer, sizeof buffer,
                  "plan: specialised path: %s; left out: %s; conditioning %.3g (extent %.3g / smallest %.3g) -> "
                  "%s %s%s, estimated error %.2g of an object's size (bound %.2g)%s; %s%s",
                  kept.empty() ? "no objects (background only)" : kept.c_str(),
                  left_out.empty() ? "nothing" : left_out.c_str(), conditioning(), extent, smallest, name_of(prec),
                  spheres ? name_of(form) : "(no sphere test)", spheres ? " sphere test" : "", estimated_error, bound,
                  estimated_error <= bound ? ""
                  : precision_forced ? " - OVER the bound: no formulation in this precision meets it"
                                     : " - OVER the bound: no formulation meets it",
                  search.c_str(),
                  spp > 1 ? ("; " + std::to_string(spp) +
                             " samples per pixel, stratified (chapter 11's stratified_sample, one PCG32 stream per "
                             "pixel), box filter")
                                .c_str()
                          : "");
    return buffer;
}

}  // namespace rt::render_tool
