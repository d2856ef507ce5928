// instances_test.cpp — transforms and instances in scene files: what the
// reader builds (objects, placements, the transform and its inverse) and
// what it refuses (a singular transform, an object or a file that places
// itself, bad numbers), each error at its file, line and field.
#include "common/scene_file.hpp"
#include "common/spd.hpp"

#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <unistd.h>
#include <string>

using namespace rt;

namespace {

const std::string head = R"({"camera": {"eye": [0, 0, 5], "look_at": [0, 0, 0]}, )";

scene_error error_of(const std::string& text, const std::string& source = "test.json") {
    try {
        parse_scene(text, source);
    } catch (const scene_error& e) {
        return e;
    }
    FAIL("the scene was accepted but should have been rejected:\n" << text);
    return scene_error("", 0, 0, "", "");
}

bool contains(const std::string& haystack, const std::string& needle) {
    return haystack.find(needle) != std::string::npos;
}

vec3d apply(const affine_transform& t, const vec3d& p) { return t.linear * p + t.offset; }

// A folder of scene files for one test, removed after it.
struct scene_folder {
    std::filesystem::path dir;
    explicit scene_folder(const std::string& name)
        : dir(std::filesystem::temp_directory_path() / ("rt-instances-" + name + "-" + std::to_string(::getpid()))) {
        std::filesystem::create_directories(dir);
    }
    ~scene_folder() { std::filesystem::remove_all(dir); }
    std::string write(const std::string& file, const std::string& text) const {
        std::ofstream(dir / file) << text;
        return (dir / file).string();
    }
};

// Every sphere of the scene with its instances expanded, in world space
// (a test's own flattening: similarity transforms only, radius scaled by
// the length of the first column).
std::vector<sphere<double>> flat_spheres(const scene_description& d) {
    std::vector<sphere<double>> out = d.world.spheres;
    std::function<void(int, const affine_transform&)> expand = [&](int o, const affine_transform& to_world) {
        for (const auto& s : d.objects[size_t(o)].spheres)
            out.push_back({apply(to_world, s.center), s.radius * length(to_world.linear[0]), s.material});
        for (const auto& i : d.objects[size_t(o)].instances) expand(i.object, then(i.to_parent, to_world));
    };
    for (const auto& i : d.instances) expand(i.object, i.to_parent);
    return out;
}

}  // namespace

TEST_CASE("a transform is scale, then rotate, then translate; a list applies first to last") {
    const scene_description d = parse_scene(head + R"(
      "objects": {"ball": {"spheres": [{"center": [1, 0, 0], "radius": 1}]}},
      "instances": [
        {"object": "ball", "transform": {"translate": [0, 0, 10], "rotate": {"axis": [0, 0, 1], "degrees": 90}, "scale": 2}},
        {"object": "ball", "transform": [{"translate": [0, 0, 10]}, {"scale": [1, 3, 1]}]},
        {"object": "ball", "transform": {"matrix": [[1, 0, 0, 5], [0, 2, 0, 6], [0, 0, 1, 7]]}}
      ]})", "t.json");
    REQUIRE(d.objects.size() == 1);
    REQUIRE(d.instances.size() == 3);
    // (1, 0, 0) scaled to (2, 0, 0), turned a quarter about z to (0, 2, 0), moved up 10.
    const vec3d a = apply(d.instances[0].to_parent, vec3d(1, 0, 0));
    CHECK(a.x == doctest::Approx(0).epsilon(1e-15));
    CHECK(a.y == doctest::Approx(2));
    CHECK(a.z == doctest::Approx(10));
    // Moved up 10, then y tripled.
    const vec3d b = apply(d.instances[1].to_parent, vec3d(0, 1, 0));
    CHECK(b == vec3d(0, 3, 10));
    CHECK(apply(d.instances[1].to_parent, vec3d(0, 0, 1)) == vec3d(0, 0, 11));
    // Matrix rows, the last column the translation.
    CHECK(apply(d.instances[2].to_parent, vec3d(1, 1, 1)) == vec3d(6, 8, 8));
    // The inverse is stored with it.
    for (const auto& i : d.instances) {
        const vec3d p(0.3, -2, 7), back = apply(i.from_parent, apply(i.to_parent, p));
        CHECK(length(back - p) < 1e-13);
    }
}

TEST_CASE("instances of instances: each object stored once, counted as often as placed") {
    const scene_description d = parse_scene(head + R"(
      "objects": {
        "pair": {"instances": [{"object": "ball"}, {"object": "ball", "transform": {"translate": [3, 0, 0]}}]},
        "ball": {"spheres": [{"center": [0, 0, 0], "radius": 1}]},
        "row": {"instances": [{"object": "pair"}, {"object": "pair", "transform": {"translate": [0, 3, 0]}},
                              {"spheres": [{"center": [0, 0, 9], "radius": 2}], "transform": {"scale": 0.5}}]}
      },
      "instances": [{"object": "row"}, {"object": "row", "transform": {"translate": [0, 0, -20]}}],
      "spheres": [{"center": [0, 0, 0], "radius": 1, "transform": {"scale": [1, 2, 1]}}]
    })", "t.json");
    // ball, pair, row, the sphere written in place inside row, the ellipsoid at the top.
    CHECK(d.objects.size() == 5);
    CHECK(d.world.spheres.empty());  // the transformed sphere is an instance
    CHECK(d.instances.size() == 3);
    const std::vector<expanded_counts> counts = expanded_counts_of(d.objects);
    std::uint64_t spheres = 0;
    for (const auto& i : d.instances) spheres += counts[size_t(i.object)].spheres;
    CHECK(spheres == 2 * (2 * 2 + 1) + 1);
    // The transformed sphere comes first (shapes are read before instances), then the two rows.
    CHECK(nesting_depths(d.objects)[size_t(d.instances[0].object)] == 0);
    CHECK(nesting_depths(d.objects)[size_t(d.instances[1].object)] == 2);
}

TEST_CASE("a singular transform is refused where it is written") {
    const scene_error e = error_of(head + R"(
      "spheres": [{"center": [0, 0, 0], "radius": 1,
                   "transform": {"matrix": [[1, 0, 0, 0], [0, 1, 0, 0], [1, 0, 0, 0]]}}]})");
    CHECK(e.line() == 3);
    CHECK(e.field() == "spheres[0].transform");
    CHECK(contains(e.problem(), "singular matrix (determinant 0)"));
    const scene_error scale = error_of(head + R"("spheres": [{"center": [0, 0, 0], "radius": 1, "transform": {"scale": [1, 0, 1]}}]})");
    CHECK(scale.field() == "spheres[0].transform.scale[1]");
    CHECK(contains(scale.problem(), "singular"));
    // Two steps that are each invertible can still be; this list is not:
    // a squash to 1e-9 after a shear that leaves it nearly flat is fine, but
    // the same columns made parallel are refused.
    const scene_error sheared = error_of(head + R"("spheres": [{"center": [0, 0, 0], "radius": 1,
        "transform": {"matrix": [[1, 1, 0, 0], [1, 1.0000000000001, 0, 0], [0, 0, 1, 0]]}}]})");
    CHECK(contains(sheared.problem(), "singular"));
}

TEST_CASE("bad numbers and shapes of a transform are named with what was expected") {
    CHECK(contains(error_of(head + R"("spheres": [{"center": [0,0,0], "radius": 1, "transform": {"matrix": [[1, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0]]}}]})").problem(),
                   "expected a row of 4 numbers"));
    const scene_error big = error_of(head + R"("spheres": [{"center": [0,0,0], "radius": 1, "transform": {"translate": [0, 1e20, 0]}}]})");
    CHECK(big.field() == "spheres[0].transform.translate[1]");
    const scene_error word = error_of(head + R"("spheres": [{"center": [0,0,0], "radius": 1, "transform": {"rotate": {"axis": [0, 1, 0], "degrees": "ninety"}}}]})");
    CHECK(word.field() == "spheres[0].transform.rotate.degrees");
    const scene_error typo = error_of(head + R"("spheres": [{"center": [0,0,0], "radius": 1, "transform": {"translat": [1, 0, 0]}}]})");
    CHECK(contains(typo.problem(), "did you mean \"translate\""));
    const scene_error mixed = error_of(head + R"("spheres": [{"center": [0,0,0], "radius": 1, "transform": {"matrix": [[1,0,0,0],[0,1,0,0],[0,0,1,0]], "scale": 2}}]})");
    CHECK(contains(mixed.problem(), "a matrix is a whole transform"));
}

TEST_CASE("an object that places itself, or an unknown name, is refused") {
    const scene_error cycle = error_of(head + R"(
      "objects": {"a": {"instances": [{"object": "b"}]}, "b": {"instances": [{"object": "a"}]}},
      "instances": [{"object": "a"}]})");
    CHECK(contains(cycle.problem(), "places itself (\"a\" -> \"b\" -> \"a\")"));
    CHECK(cycle.line() == 2);
    const scene_error unknown = error_of(head + R"("objects": {"ball": {"spheres": []}}, "instances": [{"object": "bal"}]})");
    CHECK(unknown.field() == "instances[0].object");
    CHECK(contains(unknown.problem(), "no object is named \"bal\" (the names are \"ball\")"));
    const scene_error both = error_of(head + R"("objects": {"ball": {}}, "instances": [{"object": "ball", "spheres": []}]})");
    CHECK(contains(both.problem(), "not both"));
    CHECK(contains(error_of(head + R"("instances": [{"transform": {"scale": 2}}]})").problem(), "missing what to place"));
}

TEST_CASE("a scene file placed in another: its shapes and materials, read once; a file that places itself is refused") {
    const scene_folder folder("files");
    folder.write("ball.json", head + R"("materials": [{"name": "red", "diffuse": [1, 0, 0]}],
                                         "spheres": [{"center": [0, 0, 0], "radius": 1, "material": "red"}]})");
    const std::string host = folder.write("host.json", head + R"("materials": [{"name": "grey"}],
        "instances": [{"scene": "ball.json"}, {"scene": "ball.json", "transform": {"translate": [3, 0, 0]}}]})");
    const scene_description d = load_scene_file(host);
    REQUIRE(d.objects.size() == 1);  // read once
    CHECK(d.instances.size() == 2);
    REQUIRE(d.world.materials.size() == 2);  // grey, then the placed file's red
    CHECK(d.objects[0].spheres[0].material == 1);
    CHECK(d.world.materials[1].diffuse == color(1, 0, 0));

    const std::string self = folder.write("self.json", head + R"(
      "instances": [{"scene": "self.json"}]})");
    try {
        load_scene_file(self);
        FAIL("a file that places itself was accepted");
    } catch (const scene_error& e) {
        CHECK(e.line() == 2);
        CHECK(e.field() == "instances[0].scene");
        CHECK(contains(e.problem(), "places itself"));
    }
    folder.write("a.json", head + R"("instances": [{"scene": "b.json"}]})");
    folder.write("b.json", head + R"(
      "instances": [{"scene": "a.json"}]})");
    try {
        load_scene_file((folder.dir / "a.json").string());
        FAIL("two files that place each other were accepted");
    } catch (const scene_error& e) {
        CHECK(contains(e.file(), "b.json"));  // the error is where the cycle closes
        CHECK(e.line() == 2);
        CHECK(contains(e.problem(), "a.json -> "));
        CHECK(contains(e.problem(), "(in the scene file placed at "));
    }
    const std::string missing = folder.write("missing.json", head + R"("instances": [{"scene": "nowhere.json"}]})");
    try {
        load_scene_file(missing);
        FAIL("a missing placed file was accepted");
    } catch (const scene_error& e) {
        CHECK(contains(e.file(), "missing.json"));
        CHECK(contains(e.problem(), "no such file"));
    }
}

TEST_CASE("the instanced sphereflake: 3,922,632,451 spheres at level 10 in eleven objects") {
    const scene_description d = parse_scene(head + R"("materials": [{"name": "ground"}, {"name": "flake"}],
        "generate": {"name": "balls", "size": 10, "instanced": true}})", "t.json");
    CHECK(d.objects.size() == 11);
    CHECK(d.world.planes.size() == 1);
    REQUIRE(d.instances.size() == 1);
    CHECK(expanded_counts_of(d.objects)[size_t(d.instances[0].object)].spheres == 3922632451ull);
    CHECK(error_of(head + R"("materials": [{}, {}], "generate": {"name": "mount", "size": 2, "instanced": true}})")
              .field() == "generate.instanced");
    CHECK(contains(error_of(head + R"("materials": [{}, {}], "generate": {"name": "balls", "size": 13, "instanced": true}})").problem(),
                   "a size from 1 to 12 for balls (instanced)"));
}

TEST_CASE("the instanced flake and tetrahedron are the flat ones where the flat ones are self-similar") {
    // Balls up to size 2 (from 3 on the flat generator turns sub-flakes by
    // their world direction, spd.hpp), tetra at any size: the same shapes
    // to rounding, in the same order for the spheres' set.
    for (const char* name : {"balls", "tetra"}) {
        const int size = std::string(name) == "balls" ? 2 : 4;
        const std::string g = std::string(R"("name": ")") + name + R"(", "size": )" + std::to_string(size);
        const scene_description flat = parse_scene(head + R"("materials": [{}, {}], "generate": {)" + g + "}}", "f.json");
        const scene_description inst =
            parse_scene(head + R"("materials": [{}, {}], "generate": {)" + g + R"(, "instanced": true}})", "i.json");
        const std::vector<sphere<double>> mine = flat_spheres(inst);
        REQUIRE(mine.size() == flat.world.spheres.size());
        for (const auto& s : flat.world.spheres) {
            double nearest = 1e9;
            for (const auto& m : mine)
                if (std::fabs(m.radius - s.radius) < 1e-12) nearest = std::min(nearest, length(m.center - s.center));
            CHECK(nearest < 1e-12);
        }
        CHECK(inst.world.planes.size() == flat.world.planes.size());
        const expanded_counts c = expanded_counts_of(inst.objects)[size_t(inst.instances[0].object)];
        CHECK(c.triangles == flat.world.triangles.size());
    }
}
