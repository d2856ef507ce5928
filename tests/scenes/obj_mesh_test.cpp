// obj_mesh_test.cpp — OBJ meshes (common/obj_mesh.hpp): what is read, and
// bad files refused with the file and line, never a crash.
#include "common/obj_mesh.hpp"
#include "common/scene_file.hpp"

#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include <unistd.h>

using namespace rt;

namespace {

std::string error_of(const std::string& text) {
    try {
        parse_obj_mesh(text, "m.obj");
    } catch (const obj_error& e) {
        return e.what();
    }
    return "accepted";
}

}  // namespace

TEST_CASE("a quad is split into two triangles; negative indices count from the end") {
    obj_mesh m = parse_obj_mesh("# a unit square\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf -4 -3 -2 -1\n", "m.obj");
    CHECK(m.vertices == 4);
    CHECK(m.faces == 1);
    REQUIRE(m.triangles.size() == 2);
    CHECK(m.triangles[0].a == vec3d(0, 0, 0));
    CHECK(m.triangles[0].b == vec3d(1, 0, 0));
    CHECK(m.triangles[1].c == vec3d(0, 1, 0));
}

TEST_CASE("zero-area triangles are left out and counted") {
    obj_mesh m = parse_obj_mesh("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 2 0 0\nf 1 2 3\nf 1 2 4\n", "m.obj");
    CHECK(m.triangles.size() == 1);
    CHECK(m.degenerate == 1);
}

TEST_CASE("bad OBJ input names the file and the line") {
    CHECK(error_of("v 0 0 0\nv 1 0 0\nv 0 1 0\n\nf 1 2 7\n") == "m.obj:5: a vertex index out of range "
                                                                  "(the file has 3 vertices before or after this "
                                                                  "line, numbered from 1)");
    CHECK(error_of("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 2\n").find("m.obj:5: a face needs at least three") == 0);
    CHECK(error_of("v 0 0 0\nv 1e300 0 0\nv 0 1 0\nf 1 2 3\n").find("m.obj:2: expected a finite coordinate") == 0);
    CHECK(error_of("v 0 0 0\n").find("m.obj: no faces") == 0);
    CHECK(error_of("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n").find("m.obj") == 0);  // OBJ counts from 1
    CHECK(error_of("") .find("m.obj") == 0);
}

TEST_CASE("a scene file references an OBJ file beside it") {
    scene_description d = load_scene_file(RT_SCENES_DIR "/obj-pyramid.json");
    CHECK(d.world.triangles.size() == 6);  // four sides and a square base of two
    CHECK(d.mesh_count == 1);
}

TEST_CASE("a missing or broken OBJ file is reported at the mesh's field") {
    try {
        parse_scene(R"({"camera": {"eye": [0, 0, 5], "look_at": [0, 0, 0]},
                        "meshes": [{"obj": "no-such-file.obj"}]})", "dir/s.json");
        FAIL("accepted");
    } catch (const scene_error& e) {
        CHECK(std::string(e.what()).find("dir/s.json:2:44: meshes[0].obj: dir/no-such-file.obj: cannot open") == 0);
    }
}

// tinyobjloader reads a coordinate it cannot parse ("nan", "inf") as 0, and
// a face index too long for an int wraps around, possibly onto a vertex
// that exists: both were accepted without a word.
TEST_CASE("an OBJ vertex of nan or inf is refused with its line") {
    const std::string faces = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    CHECK(error_of("v 0 0 0\nv nan 0 0\n" + faces) ==
          "m.obj:2: expected a finite number for a vertex coordinate, got `nan`");
    CHECK(error_of("v 0 0 0\nv 1 0 -inf\n" + faces) ==
          "m.obj:2: expected a finite number for a vertex coordinate, got `-inf`");
    CHECK(error_of("v 0 0 0\nv 1 0 0\nv 0 1e999 0\nf 1 2 3\n") ==
          "m.obj:3: expected a finite number for a vertex coordinate, got `1e999`");  // overflows to inf
    CHECK(error_of("v 0 0 0\nv 0x1p3 0 0\n" + faces).find("m.obj:2: expected a finite number") == 0);
    CHECK(error_of("v 1 0 0 # a comment\nv 0 1 0\nv 0 0 1\nf 1 2 3\n") == "accepted");
}

TEST_CASE("an OBJ face index of 20 digits is refused with its line") {
    const std::string vertices = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
    // 2^64 + 1 as 20 digits: wrapped to 1 it would be the first vertex.
    CHECK(error_of(vertices + "f 1 2 3\nf 18446744073709551617 2 3\n") ==
          "m.obj:5: expected a vertex index (a whole number of at most 9 digits, from 1, or negative to count from "
          "the end), got `18446744073709551617`");
    CHECK(error_of(vertices + "f 1/1/1 2/18446744073709551617/2 3//3\n").find("m.obj:4: expected a vertex index") == 0);
    CHECK(error_of(vertices + "f 1 2 3x\n").find("m.obj:4: expected a vertex index") == 0);
    CHECK(error_of(vertices + "f 1/1 2//2 -1\n") == "accepted");
}

TEST_CASE("a bad OBJ vertex is reported at the scene's line and the OBJ's") {
    const std::string dir = "/tmp/rt-obj-mesh-test-" + std::to_string(::getpid());
    std::filesystem::create_directories(dir);
    std::ofstream(dir + "/nan.obj") << "v 0 0 0\nv 1 0 0\nv 0 nan 0\nf 1 2 3\n";
    try {
        parse_scene(R"({"camera": {"eye": [0, 0, 5], "look_at": [0, 0, 0]},
                        "meshes": [{"obj": "nan.obj"}]})", dir + "/s.json");
        FAIL("accepted");
    } catch (const scene_error& e) {
        CHECK(std::string(e.what()).find(dir + "/s.json:2:44: meshes[0].obj: " + dir +
                                         "/nan.obj:3: expected a finite number for a vertex coordinate, got `nan`") == 0);
    }
    std::filesystem::remove_all(dir);
}
