// scene_file_test.cpp — the scene-file reader: good files load as written,
// bad files are rejected with the file, line, column and field of the
// mistake and a sentence saying what was expected.
#include "common/math.hpp"
#include "common/scene_file.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <utility>
#include <vector>

using namespace rt;

namespace {

// Parses text that must fail; returns the error for the checks.
scene_error error_of(const std::string& text) {
    try {
        parse_scene(text, "test.json");
    } catch (const scene_error& e) {
        return e;
    }
    FAIL("the scene was accepted but should have been rejected:\n" << text);
    return scene_error("", 0, 0, "", "");
}

bool contains(const std::string& haystack, const std::string& needle) {
    return haystack.find(needle) != std::string::npos;
}

const char* minimal_camera = R"("camera": {"eye": [0, 0, 5], "look_at": [0, 0, 0]})";

}  // namespace

TEST_CASE("a complete scene file loads with every field as written") {
    const std::string text = R"({
  // comments are allowed
  "description": "one of everything",
  "camera": {"type": "pinhole", "eye": [0, 1, 5], "look_at": [0, 0, 0], "up": [0, 1, 0],
             "fov": 50, "width": 64, "height": 48},
  "background": [0.1, 0.2, 0.3],
  "ambient": [0.01, 0.02, 0.03],
  "materials": [{"name": "red", "diffuse": [0.9, 0.1, 0.1], "specular": [1, 1, 1], "shininess": 64},
                {"name": "floor", "diffuse": [0.8, 0.8, 0.8], "checker": [0.1, 0.1, 0.1]}],
  "spheres": [{"center": [0, 0, 0], "radius": 1, "material": "red"}],
  "planes": [{"point": [0, -1, 0], "normal": [0, 2, 0], "material": 1}],
  "triangles": [{"a": [0, 0, 0], "b": [1, 0, 0], "c": [0, 1, 0]}],
  "meshes": [{"vertices": [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]], "faces": [[0, 1, 2], [0, 2, 3]],
              "material": "floor"}],
  "lights": [{"position": [5, 5, 5], "intensity": [20, 20, 20]}, {"position": [-5, 5, 5]}]
})";
    scene_description d = parse_scene(text, "full.json");
    CHECK(d.camera.type == camera_description::kind::pinhole);
    CHECK(d.camera.eye == vec3d(0, 1, 5));
    CHECK(d.camera.fov_degrees == 50);
    CHECK(d.camera.width == 64);
    CHECK(d.camera.height == 48);
    CHECK(d.world.background == color(0.1f, 0.2f, 0.3f));
    CHECK(d.world.ambient == color(0.01f, 0.02f, 0.03f));
    REQUIRE(d.world.materials.size() == 2);
    CHECK(d.world.materials[0].shininess == 64);
    CHECK(d.world.materials[1].checker);
    CHECK(d.world.materials[1].checker_color == color(0.1f, 0.1f, 0.1f));
    REQUIRE(d.world.spheres.size() == 1);
    CHECK(d.world.spheres[0].radius == 1);
    CHECK(d.world.spheres[0].material == 0);
    REQUIRE(d.world.planes.size() == 1);
    CHECK(d.world.planes[0].material == 1);
    CHECK(d.world.planes[0].normal == vec3d(0, 2, 0));  // kept as written; need not be unit length
    // One loose triangle plus the mesh's two faces.
    REQUIRE(d.world.triangles.size() == 3);
    CHECK(d.world.triangles[2].c == vec3d(0, 1, 0));
    CHECK(d.world.triangles[2].material == 1);
    CHECK(d.mesh_count == 1);
    REQUIRE(d.world.lights.size() == 2);
    CHECK(d.world.lights[1].intensity == color(1, 1, 1));
}

TEST_CASE("defaults: pinhole camera and one grey material") {
    scene_description d = parse_scene(std::string("{") + minimal_camera + R"(, "spheres": [{"center": [0,0,0], "radius": 2}]})", "t.json");
    CHECK(d.camera.type == camera_description::kind::pinhole);
    CHECK(d.camera.up == vec3d(0, 1, 0));
    CHECK(d.world.materials.size() == 1);
    CHECK(d.world.spheres[0].material == 0);
    CHECK(d.world.lights.empty());
}

TEST_CASE("an orthographic camera builds and sends rays from its view rectangle") {
    scene_description d = parse_scene(R"({"camera": {"type": "orthographic", "eye": [0, 0, 5], "look_at": [0, 0, 0],
        "view_height": 4, "width": 10, "height": 10}})", "t.json");
    CHECK(d.camera.type == camera_description::kind::orthographic);
    scene_camera<double> camera(d.camera);
    CHECK(camera.width() == 10);
    CHECK(camera.primary_range().min == 0);
    ray<double> r = camera.primary_ray(0, 0);
    CHECK(r.direction == vec3d(0, 0, -1));
    CHECK(r.origin.x < 0);
    CHECK(r.origin.y > 0);
}

TEST_CASE("convert_scene keeps every object and material in float") {
    scene_description d = parse_scene(std::string("{") + minimal_camera +
        R"(, "spheres": [{"center": [1,2,3], "radius": 0.5}], "planes": [{"point": [0,0,0], "normal": [0,1,0]}]})", "t.json");
    scene<float> f = convert_scene<float>(d.world);
    CHECK(f.spheres.size() == 1);
    CHECK(f.spheres[0].center == vec3<float>(1, 2, 3));
    CHECK(f.planes.size() == 1);
    CHECK(f.object_count() == 2);
}

TEST_CASE("a misspelt key is named with its line and column and a suggestion") {
    scene_error e = error_of(std::string("{") + minimal_camera + R"(,
  "spheres": [
    {"center": [0, 0, 0], "radius": 1},
    {"center": [0, 0, 0], "raduis": 2}
  ]
})");
    CHECK(e.file() == "test.json");
    CHECK(e.line() == 4);
    CHECK(e.column() == 27);
    CHECK(e.field() == "spheres[1].raduis");
    CHECK(contains(e.problem(), "unknown key \"raduis\""));
    CHECK(contains(e.problem(), "did you mean \"radius\""));
    CHECK(contains(e.what(), "test.json:4:27: spheres[1].raduis: unknown key"));
}

TEST_CASE("a missing field is named at the object that lacks it") {
    scene_error e = error_of(std::string("{") + minimal_camera + R"(,
  "spheres": [ {"radius": 1} ]
})");
    CHECK(e.line() == 2);
    CHECK(e.column() == 16);
    CHECK(e.field() == "spheres[0]");
    CHECK(contains(e.problem(), "missing field \"center\""));
}

TEST_CASE("a missing camera is an error") {
    scene_error e = error_of(R"({"spheres": []})");
    CHECK(contains(e.problem(), "missing field \"camera\""));
}

TEST_CASE("a wrong type says what was expected and what was found") {
    scene_error e = error_of(std::string("{") + minimal_camera + R"(,
  "spheres": [ {"center": [0, 0, 0], "radius": "big"} ]
})");
    CHECK(e.line() == 2);
    CHECK(e.column() == 48);
    CHECK(e.field() == "spheres[0].radius");
    CHECK(contains(e.problem(), "expected a number"));
    CHECK(contains(e.problem(), "the string \"big\""));

    scene_error e2 = error_of(std::string("{") + minimal_camera + R"(, "planes": [ {"point": [0, 0], "normal": [0, 1, 0]} ]})");
    CHECK(e2.field() == "planes[0].point");
    CHECK(contains(e2.problem(), "a point [x, y, z]"));
    CHECK(contains(e2.problem(), "an array of 2 element(s)"));

    scene_error e3 = error_of(R"({"camera": {"eye": [0, 0, 5], "look_at": [0, 0, 0], "width": 12.5}})");
    CHECK(e3.field() == "camera.width");
    CHECK(contains(e3.problem(), "whole number"));
}

TEST_CASE("a number too large to be finite is rejected") {
    scene_error e = error_of(std::string("{") + minimal_camera + R"(, "spheres": [ {"center": [0, 1e999, 0], "radius": 1} ]})");
    CHECK(e.field() == "spheres[0].center[1]");
    CHECK(contains(e.problem(), "finite"));
    CHECK(contains(e.problem(), "1e999"));

    scene_error e2 = error_of(std::string("{") + minimal_camera + R"(, "spheres": [ {"center": [0, 1e20, 0], "radius": 1} ]})");
    CHECK(e2.field() == "spheres[0].center[1]");
    CHECK(contains(e2.problem(), "at most 1e15"));
}

TEST_CASE("a radius that is not positive is rejected") {
    for (const char* radius : {"0", "-2", "-0.0", "1e-50"}) {
        scene_error e = error_of(std::string("{") + minimal_camera + R"(, "spheres": [ {"center": [0, 0, 0], "radius": )" + radius + "} ]}");
        CHECK(e.field() == "spheres[0].radius");
        CHECK(e.line() == 1);
    }
}

TEST_CASE("a zero plane normal is rejected") {
    scene_error e = error_of(std::string("{") + minimal_camera + R"(, "planes": [ {"point": [0, 0, 0], "normal": [0, 0, 0]} ]})");
    CHECK(e.field() == "planes[0].normal");
    CHECK(contains(e.problem(), "non-zero"));
}

TEST_CASE("a degenerate camera is rejected") {
    scene_error same = error_of(R"({"camera": {"eye": [1, 2, 3], "look_at": [1, 2, 3]}})");
    CHECK(same.field() == "camera.look_at");
    CHECK(contains(same.problem(), "eye and look_at must be different"));

    scene_error parallel = error_of(R"({"camera": {"eye": [0, 5, 0], "look_at": [0, 0, 0]}})");
    CHECK(parallel.field() == "camera");
    CHECK(contains(parallel.problem(), "parallel to the view direction"));

    scene_error fov = error_of(R"({"camera": {"eye": [0, 0, 5], "look_at": [0, 0, 0], "fov": 180}})");
    CHECK(fov.field() == "camera.fov");

    scene_error zero_size = error_of(R"({"camera": {"eye": [0, 0, 5], "look_at": [0, 0, 0], "height": 0}})");
    CHECK(zero_size.field() == "camera.height");

    scene_error mixed = error_of(R"({"camera": {"eye": [0, 0, 5], "look_at": [0, 0, 0], "view_height": 3}})");
    CHECK(mixed.field() == "camera.view_height");
    CHECK(contains(mixed.problem(), "orthographic"));

    scene_error kind = error_of(R"({"camera": {"type": "fisheye", "eye": [0, 0, 5], "look_at": [0, 0, 0]}})");
    CHECK(kind.field() == "camera.type");
}

TEST_CASE("materials are referred to by a known name or an index in range") {
    const std::string head = std::string("{") + minimal_camera + R"(, "materials": [{"name": "red"}, {"name": "blue"}], )";
    scene_error name = error_of(head + R"("spheres": [{"center": [0,0,0], "radius": 1, "material": "green"}]})");
    CHECK(name.field() == "spheres[0].material");
    CHECK(contains(name.problem(), "no material is named \"green\""));
    CHECK(contains(name.problem(), "\"red\", \"blue\""));

    scene_error index = error_of(head + R"("spheres": [{"center": [0,0,0], "radius": 1, "material": 2}]})");
    CHECK(contains(index.problem(), "index from 0 to 1"));

    scene_error twice = error_of(std::string("{") + minimal_camera + R"(, "materials": [{"name": "a"}, {"name": "a"}]})");
    CHECK(twice.field() == "materials[1].name");

    scene_error negative = error_of(std::string("{") + minimal_camera + R"(, "materials": [{"diffuse": [0.5, -1, 0]}]})");
    CHECK(negative.field() == "materials[0].diffuse[1]");
}

TEST_CASE("triangles and meshes: zero area and bad indices are rejected") {
    scene_error flat = error_of(std::string("{") + minimal_camera + R"(, "triangles": [{"a": [0,0,0], "b": [1,1,1], "c": [2,2,2]}]})");
    CHECK(flat.field() == "triangles[0]");
    CHECK(contains(flat.problem(), "zero area"));

    scene_error index = error_of(std::string("{") + minimal_camera +
        R"(, "meshes": [{"vertices": [[0,0,0],[1,0,0],[0,1,0]], "faces": [[0, 1, 3]]}]})");
    CHECK(index.field() == "meshes[0].faces[0][2]");
    CHECK(contains(index.problem(), "index from 0 to 2"));

    scene_error repeated = error_of(std::string("{") + minimal_camera +
        R"(, "meshes": [{"vertices": [[0,0,0],[1,0,0],[0,1,0]], "faces": [[0, 1, 1]]}]})");
    CHECK(repeated.field() == "meshes[0].faces[0]");
}

TEST_CASE("a key given twice is an error rather than a silent overwrite") {
    scene_error e = error_of(R"({"camera": {"eye": [0, 0, 5], "look_at": [0, 0, 0], "eye": [0, 0, 6]}})");
    CHECK(e.field() == "camera.eye");
    CHECK(e.column() == 53);
    CHECK(contains(e.problem(), "twice"));
}

TEST_CASE("a syntax error is reported at its line and column") {
    scene_error e = error_of("{\n  \"camera\": {\"eye\": [0, 0, 5],,\n}");
    CHECK(e.line() == 2);
    CHECK(e.column() == 31);
    CHECK(contains(e.problem(), "not valid JSON"));

    CHECK(error_of("").line() == 1);
    CHECK(contains(error_of("[1, 2, 3]").problem(), "JSON object"));
    CHECK(contains(error_of("{\"camera\": 5}").problem(), "expected an object"));
}

TEST_CASE("deeply nested input is refused without a crash") {
    std::string deep = "{\"description\": " + std::string(5000, '[') + std::string(5000, ']') + "}";
    scene_error e = error_of(deep);
    CHECK(contains(e.problem(), "nested"));
}

TEST_CASE("a missing file is named") {
    try {
        load_scene_file("no/such/scene.json");
        FAIL("a missing file was accepted");
    } catch (const scene_error& e) {
        CHECK(e.file() == "no/such/scene.json");
        CHECK(contains(e.what(), "no such file"));
    }
}

TEST_CASE("every scene file in scenes/ loads") {
    int count = 0;
    for (const auto& entry : std::filesystem::recursive_directory_iterator(RT_SCENES_DIR)) {
        if (entry.path().extension() != ".json") continue;
        CAPTURE(entry.path().string());
        CHECK_NOTHROW(load_scene_file(entry.path().string()));
        ++count;
    }
    CHECK(count > 0);
}

TEST_CASE("every broken scene in tests/scenes/broken/ is rejected with the error it names") {
    // Each broken file's first line is a comment: // expect: TEXT
    int count = 0;
    for (const auto& entry : std::filesystem::directory_iterator(RT_BROKEN_SCENES_DIR)) {
        if (entry.path().extension() != ".json") continue;
        ++count;
        std::string path = entry.path().string();
        CAPTURE(path);
        std::ifstream in(path);
        std::string first;
        std::getline(in, first);
        const std::string marker = "// expect: ";
        REQUIRE(first.rfind(marker, 0) == 0);
        std::string expected = first.substr(marker.size());
        try {
            load_scene_file(path);
            FAIL("accepted a broken scene");
        } catch (const scene_error& e) {
            CHECK_MESSAGE(contains(e.what(), expected), "got: " << std::string(e.what()));
        }
    }
    CHECK(count > 0);
}

TEST_CASE("a NUL byte is refused: nlohmann-json would ignore everything after it") {
    std::string text = std::string("{") + minimal_camera + "}";
    text += std::string(1, '\0') + "garbage";
    scene_error e = error_of(text);
    CHECK(contains(e.problem(), "NUL byte"));
    CHECK(e.column() == int(text.find('\0')) + 1);
}

TEST_CASE("a comment ended by a carriage return is read as nlohmann-json reads it") {
    scene_description d = parse_scene(std::string("// first line\r{") + minimal_camera + "}", "t.json");
    CHECK(d.camera.eye == vec3d(0, 0, 5));
}

TEST_CASE("a UTF-8 byte-order mark is skipped and columns on line 1 stay the ones an editor shows") {
    const std::string scene = std::string("{") + minimal_camera + "}";
    CHECK(parse_scene("\xEF\xBB\xBF" + scene, "bom.json").camera.eye.z == 5);
    scene_error e = error_of("\xEF\xBB\xBF" R"({"camera": {"eye": [0, 0, 5], "look_at": [0, 0, 0], "fov": -1}})");
    CHECK(e.field() == "camera.fov");
    CHECK(e.line() == 1);
    CHECK(e.column() == 60);  // counted from the '{', as without the mark
}

TEST_CASE("an error message stays short whatever the file holds") {
    const std::string long_key(100000, 'k');
    scene_error e = error_of(std::string("{") + minimal_camera + R"(, ")" + long_key + R"(": 1})");
    CHECK(std::string(e.what()).size() < 1500);
    CHECK(contains(e.what(), "more characters"));
    CHECK(contains(e.what(), "unknown key"));

    const std::string long_number = "1" + std::string(500, '0');  // 1e500: too large for a double
    scene_error big = error_of(std::string("{") + minimal_camera + R"(, "spheres": [{"center": [0, 0, 0], "radius": )" +
                               long_number + "}]}");
    CHECK(big.field() == "spheres[0].radius");
    CHECK(std::string(big.what()).size() < 1500);
}

TEST_CASE("a camera that degenerates only in float is named with its field") {
    scene_error e = error_of(
        R"({"camera": {"type": "orthographic", "eye": [0, 0, 5], "look_at": [0, 0, 0], "view_height": 1e-50}})");
    CHECK(e.field() == "camera.view_height");
    CHECK(e.line() == 1);
    CHECK(contains(e.problem(), "in float"));
}

namespace {

// The signed volumes of the closed surfaces among a scene's triangles: the
// triangles are joined into pieces by the edges they share (corners equal to
// the bit), and a piece whose every edge has exactly two triangles is closed.
// Its signed volume, the sum of a . (b x c) / 6 over its triangles, is
// positive when every face runs counter-clockwise seen from outside, i.e.
// when chapter 05's outward normal (b - a) x (c - a) points out of the solid.
std::vector<double> closed_surface_volumes(const std::vector<triangle<double>>& triangles) {
    using corner = std::array<double, 3>;
    auto key = [](const vec3d& p) { return corner{p.x, p.y, p.z}; };
    std::map<std::pair<corner, corner>, std::vector<size_t>> edges;  // unordered edge -> its triangles
    for (size_t i = 0; i < triangles.size(); ++i) {
        const corner v[3] = {key(triangles[i].a), key(triangles[i].b), key(triangles[i].c)};
        for (int k = 0; k < 3; ++k) edges[std::minmax(v[k], v[(k + 1) % 3])].push_back(i);
    }
    std::vector<size_t> piece(triangles.size());
    for (size_t i = 0; i < piece.size(); ++i) piece[i] = i;
    auto root = [&](size_t i) {
        while (piece[i] != i) i = piece[i] = piece[piece[i]];
        return i;
    };
    for (const auto& [edge, sharing] : edges)
        for (size_t s : sharing) piece[root(s)] = root(sharing[0]);
    std::map<size_t, bool> closed;
    for (const auto& [edge, sharing] : edges) {
        auto [it, fresh] = closed.emplace(root(sharing[0]), true);
        it->second = it->second && sharing.size() == 2;
    }
    std::map<size_t, double> volume;
    for (size_t i = 0; i < triangles.size(); ++i) {
        const triangle<double>& t = triangles[i];
        volume[root(i)] += dot(t.a, cross(t.b, t.c)) / 6;
    }
    std::vector<double> volumes;
    for (const auto& [p, is_closed] : closed)
        if (is_closed) volumes.push_back(volume[p]);
    return volumes;
}

}  // namespace

// A mesh wound inward has every normal pointing into the solid: shading
// looks right (the face rule turns the normal to the viewer), but chapter
// 09's front-face flag calls every ray from outside a ray leaving the solid.
TEST_CASE("the closed meshes of the course's scene files are wound outward") {
    for (const char* file : {"triangles-and-mesh.json", "ch05-triangle-mesh.json", "ch06-shading.json",
                             "obj-pyramid.json"}) {
        CAPTURE(file);
        const scene_description d = load_scene_file(std::string(RT_SCENES_DIR) + "/" + file);
        const std::vector<double> volumes = closed_surface_volumes(d.world.triangles);
        CHECK(volumes.size() == size_t(d.mesh_count));
        for (double v : volumes) CHECK(v > 0);
    }
}
