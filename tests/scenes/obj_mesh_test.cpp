// obj_mesh_test.cpp — OBJ meshes (common/obj_mesh.hpp): what is read, and
// bad files refused with the file and line, never a crash.
#include "common/obj_mesh.hpp"
#include "common/scene_file.hpp"

#include <doctest/doctest.h>

#include <string>

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
