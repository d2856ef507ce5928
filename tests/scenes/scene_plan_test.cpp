// scene_plan_test.cpp — the renderer's plan: what it leaves out, and which
// precision and sphere formulation it picks for a scene's conditioning.
#include "scene_plan.hpp"

#include <doctest/doctest.h>

using namespace rt;
using namespace rt::render_tool;

namespace {

scene_description spheres_at_distance(double distance, double radius) {
    return parse_scene(R"({"camera": {"eye": [0, 0, )" + std::to_string(distance) +
                           R"(], "look_at": [0, 0, 0]}, "spheres": [{"center": [0, 0, 0], "radius": )" +
                           std::to_string(radius) + "}]}",
                       "plan-test.json");
}

bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

}  // namespace

TEST_CASE("a spheres-only scene leaves out planes, triangles, lighting and shadow rays") {
    const scene_plan plan = make_plan(spheres_at_distance(5, 1), 1e-3, std::nullopt);
    CHECK(plan.spheres == 1);
    CHECK(plan.planes == 0);
    CHECK(plan.lights == 0);
    const std::string line = plan.describe();
    CHECK(contains(line, "left out: plane loop, triangle loop, lighting and shadow rays (no lights)"));
}

TEST_CASE("a matte scene makes no secondary rays, and mirrors and glass are counted and named") {
    const scene_plan matte = make_plan(spheres_at_distance(5, 1), 1e-3, std::nullopt);
    CHECK(matte.mirrors == 0);
    CHECK(matte.glass == 0);
    CHECK_FALSE(matte.secondary_rays());
    CHECK(contains(matte.describe(), "reflection and refraction (no mirror or glass)"));

    // Two mirror spheres, one glass sphere and a matte plane; one material
    // both mirror and glass counts as both.
    const scene_description shiny = parse_scene(R"({"camera": {"eye": [0, 0, 5], "look_at": [0, 0, 0]},
        "materials": [{"name": "matte"}, {"name": "mirror", "mirror": [0.5, 0, 0]}, {"name": "glass", "ior": 1.5}],
        "spheres": [{"center": [0, 0, 0], "radius": 1, "material": "mirror"},
                    {"center": [2, 0, 0], "radius": 1, "material": "mirror"},
                    {"center": [-2, 0, 0], "radius": 1, "material": "glass"}],
        "planes": [{"point": [0, -1, 0], "normal": [0, 1, 0], "material": "matte"}]})",
                                                "plan-shiny.json");
    scene_plan plan = make_plan(shiny, 1e-3, std::nullopt);
    plan.depth = 3;
    CHECK(plan.mirrors == 2);
    CHECK(plan.glass == 1);
    CHECK(plan.secondary_rays());
    const std::string line = plan.describe();
    CHECK(contains(line, "reflected rays (2 mirror objects), reflected and refracted rays (1 glass objects), up to 3 bounces"));
    CHECK_FALSE(contains(line, "no mirror or glass"));
}

TEST_CASE("a scene that emits is path traced; without diffuse interreflection it leaves out the bounces") {
    // One matte sphere under an emitting one, black background: light reaches
    // the matte sphere only straight from the lamp, which next-event
    // estimation samples; no bounce can add anything.
    const std::string lamp_and_ball = R"({"camera": {"eye": [0, 0, 5], "look_at": [0, 0, 0]}, "background": [0, 0, 0],
        "materials": [{"name": "matte"}, {"name": "lamp", "diffuse": [0, 0, 0], "emission": [5, 5, 5]}],
        "spheres": [{"center": [0, 0, 0], "radius": 1, "material": "matte"},
                    {"center": [0, 3, 0], "radius": 0.5, "material": "lamp"}])";
    const scene_plan lone = make_plan(parse_scene(lamp_and_ball + "}", "plan-lamp.json"), 1e-3, std::nullopt);
    CHECK(lone.path_traced);
    CHECK(lone.emitting_spheres == 1);
    CHECK_FALSE(lone.bounces);
    CHECK(contains(lone.describe(), "next-event estimation of 1 sphere lights"));
    CHECK(contains(lone.describe(), "left out: bounces (at most one diffuse object and a black background"));
    // A floor under the ball: the floor lights the ball and the ball the floor.
    const scene_plan floor = make_plan(
        parse_scene(lamp_and_ball + R"(, "planes": [{"point": [0, -1, 0], "normal": [0, 1, 0], "material": "matte"}]})",
                    "plan-lamp-floor.json"),
        1e-3, std::nullopt);
    CHECK(floor.bounces);
    CHECK(contains(floor.describe(), "cosine-weighted bounces"));
    // Nothing emits: not path traced unless asked (rt-render --path).
    CHECK_FALSE(make_plan(spheres_at_distance(5, 1), 1e-3, std::nullopt).path_traced);
}

TEST_CASE("a well-conditioned scene gets float and the plain quadratic") {
    const scene_plan plan = make_plan(spheres_at_distance(5, 1), 1e-3, std::nullopt);
    CHECK(plan.prec == precision::single);
    CHECK(plan.form == sphere_formulation::plain);
    CHECK(plan.estimated_error <= plan.bound);
}

TEST_CASE("conditioning moves the plan to the robust form and then to double") {
    // extent / radius about 100: float's plain quadratic is past 1e-3, the robust form is not.
    const scene_plan mid = make_plan(spheres_at_distance(100, 1), 1e-3, std::nullopt);
    CHECK(mid.prec == precision::single);
    CHECK(mid.form == sphere_formulation::robust);
    // The precision chapter's sphere 4100 radii away: float is out altogether.
    const scene_plan far = make_plan(spheres_at_distance(4100, 1), 1e-3, std::nullopt);
    CHECK(far.prec == precision::double_);
    CHECK(far.estimated_error <= far.bound);
}

TEST_CASE("forcing a precision keeps it and says when the bound cannot be met") {
    const scene_plan forced = make_plan(spheres_at_distance(4100, 1), 1e-3, precision::single);
    CHECK(forced.prec == precision::single);
    CHECK(forced.form == sphere_formulation::robust);
    CHECK(forced.estimated_error > forced.bound);
    CHECK(contains(forced.describe(), "OVER the bound"));
}

TEST_CASE("the error model grows like k squared for the plain form and like k for the robust one") {
    const double plain10 = estimated_error(precision::single, sphere_formulation::plain, 10, true, false);
    const double plain100 = estimated_error(precision::single, sphere_formulation::plain, 100, true, false);
    const double robust10 = estimated_error(precision::single, sphere_formulation::robust, 10, true, false);
    const double robust100 = estimated_error(precision::single, sphere_formulation::robust, 100, true, false);
    CHECK(plain100 / plain10 == doctest::Approx(100));
    CHECK(robust100 / robust10 == doctest::Approx(10));
    CHECK(estimated_error(precision::double_, sphere_formulation::plain, 100, true, false) < plain100);
}
