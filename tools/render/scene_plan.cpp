#include "scene_plan.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

namespace rt::render_tool {

namespace {

double epsilon_of(precision p) {
    return p == precision::single ? double(std::numeric_limits<float>::epsilon())
                                  : std::numeric_limits<double>::epsilon();
}

const char* name_of(precision p) { return p == precision::single ? "float" : "double"; }
const char* name_of(sphere_formulation f) { return f == sphere_formulation::plain ? "plain" : "robust"; }

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

std::string scene_plan::describe() const {
    char buffer[900];
    if (general) {
        std::snprintf(buffer, sizeof buffer,
                      "plan: GENERAL path (forced): %zu spheres, %zu planes, %zu triangles, %zu lights; "
                      "every object type tested through %s, %s, chapter 02's sphere test, "
                      "chapter 06 shading%s; nothing left out",
                      spheres, planes, triangles, lights,
                      tree ? "chapter 08's tree (build_sah, closest_hit, any_hit; planes one by one)"
                           : "chapter 03's loop",
                      name_of(prec), lights ? " with shadow rays" : "");
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
    std::snprintf(buffer, sizeof buffer,
                  "plan: specialised path: %s; left out: %s; conditioning %.3g (extent %.3g / smallest %.3g) -> "
                  "%s %s%s, estimated error %.2g of an object's size (bound %.2g)%s; %s",
                  kept.empty() ? "no objects (background only)" : kept.c_str(),
                  left_out.empty() ? "nothing" : left_out.c_str(), conditioning(), extent, smallest, name_of(prec),
                  spheres ? name_of(form) : "(no sphere test)", spheres ? " sphere test" : "", estimated_error, bound,
                  estimated_error <= bound ? ""
                  : precision_forced ? " - OVER the bound: no formulation in this precision meets it"
                                     : " - OVER the bound: no formulation meets it",
                  search.c_str());
    return buffer;
}

}  // namespace rt::render_tool
