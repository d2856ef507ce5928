// spd_test.cpp — the Standard Procedural Databases (common/spd.hpp): the
// counts the SPD publishes, the counts each generator really produces at
// small sizes, and the geometry each description promises. Big sizes are
// benchmarks (tools/bench), never tests: only their formula is checked here.
#include "common/scene_file.hpp"
#include "common/spd.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <string>
#include <vector>

using namespace rt;

namespace {

// Keeps everything it is given.
struct collect : spd_sink {
    std::vector<rt::sphere<double>> spheres;
    std::vector<rt::triangle<double>> triangles;
    std::vector<rt::plane<double>> planes;
    void sphere(const vec3d& c, double r, int m) override { spheres.push_back({c, r, m}); }
    void triangle(const vec3d& a, const vec3d& b, const vec3d& c, int m) override { triangles.push_back({a, b, c, m}); }
    void plane(const vec3d& p, const vec3d& n, int m) override { planes.push_back({p, n, m}); }
};

double area(const triangle<double>& t) { return length(cross(t.b - t.a, t.c - t.a)) / 2; }

}  // namespace

TEST_CASE("the formulas give the SPD's published counts") {
    // The SPD's own table at its default sizes: balls 7,382 primitives
    // (7,381 spheres and a ground polygon), tetra 4,096, mount 8,196.
    CHECK(spd_expected_counts(spd_database::balls, 4).spheres == 7381);
    CHECK(spd_expected_counts(spd_database::balls, 4).total() == 7382);
    CHECK(spd_expected_counts(spd_database::tetra, 6).triangles == 4096);
    CHECK(spd_expected_counts(spd_database::mount, 6).triangles == 8192);
    CHECK(spd_expected_counts(spd_database::mount, 6).total() == 8196);
    // The precision lecture's 48 million spheres: 1 + 9 + ... + 9^8.
    CHECK(spd_expected_counts(spd_database::balls, 8).spheres == 48427561);
    for (int size = 1; size <= 8; ++size) {
        std::uint64_t nine = 1;
        for (int i = 0; i <= size; ++i) nine *= 9;
        CHECK(spd_expected_counts(spd_database::balls, size).spheres == (nine - 1) / 8);
    }
}

TEST_CASE("each generator produces exactly the counts of its formula at small sizes") {
    for (auto db : {spd_database::balls, spd_database::tetra, spd_database::mount})
        for (int size = 1; size <= (db == spd_database::balls ? 4 : 6); ++size) {
            CAPTURE(spd_name(db));
            CAPTURE(size);
            collect c;
            spd_counts got = spd_generate(db, size, c);
            spd_counts want = spd_expected_counts(db, size);
            CHECK(got.spheres == want.spheres);
            CHECK(got.triangles == want.triangles);
            CHECK(got.planes == want.planes);
            CHECK(c.spheres.size() == want.spheres);  // what the sink received, not what was counted
            CHECK(c.triangles.size() == want.triangles);
        }
}

TEST_CASE("sphereflake: the scene's generator (on every core, in place) gives the sink's spheres bit for bit") {
    // spd_generate into a scene writes each subtree into its own slots from
    // a thread of the pool; the order and every coordinate must be those of
    // the serial depth-first walk, whatever the number of threads.
    for (int size : {1, 2, 3, 5}) {
        CAPTURE(size);
        collect serial;
        spd_generate(spd_database::balls, size, serial);
        scene<double> s;
        s.spheres.push_back({vec3d(9, 9, 9), 1, 7});  // appended after what is there
        const spd_counts got = spd_generate(spd_database::balls, size, s, {3, 4});
        CHECK(got.spheres == serial.spheres.size());
        CHECK(got.planes == 1);
        REQUIRE(s.spheres.size() == serial.spheres.size() + 1);
        REQUIRE(s.planes.size() == 1);
        CHECK(s.planes[0].material == 3);
        CHECK(s.planes[0].point == serial.planes[0].point);
        size_t differ = 0;
        for (size_t i = 0; i < serial.spheres.size(); ++i) {
            const auto &a = s.spheres[i + 1], &b = serial.spheres[i];
            differ += !(a.center == b.center && a.radius == b.radius && a.material == 4);
        }
        CHECK(differ == 0);
    }
}

TEST_CASE("sizes out of range are refused with the range") {
    collect c;
    CHECK_THROWS_WITH(spd_generate(spd_database::balls, 9, c), doctest::Contains("from 1 to 8"));
    CHECK_THROWS_WITH(spd_generate(spd_database::tetra, 0, c), doctest::Contains("from 1 to 11"));
}

TEST_CASE("sphereflake: each sphere touches its parent and no two spheres overlap") {
    collect c;
    spd_generate(spd_database::balls, 2, c);  // 91 spheres: all pairs are cheap
    REQUIRE(c.spheres.size() == 91);
    REQUIRE(c.planes.size() == 1);
    const auto& s = c.spheres;
    int touching = 0;
    for (size_t i = 0; i < s.size(); ++i) {
        // Resting on or above the ground plane z = -0.5.
        CHECK(s[i].center.z - s[i].radius >= -0.5 - 1e-12);
        for (size_t j = i + 1; j < s.size(); ++j) {
            double gap = length(s[i].center - s[j].center) - (s[i].radius + s[j].radius);
            CHECK(gap > -1e-12);               // never overlapping
            if (std::fabs(gap) < 1e-12) ++touching;
        }
    }
    CHECK(touching == 90);  // exactly the parent-child pairs: every sphere but the root touches one
}

TEST_CASE("Sierpinski tetrahedron: the total area is the same at every size") {
    // Each level replaces a triangle by four of a quarter of its area.
    double first = 0;
    for (int size = 1; size <= 5; ++size) {
        collect c;
        spd_generate(spd_database::tetra, size, c);
        double total = 0;
        for (const auto& t : c.triangles) {
            CHECK(area(t) > 0);
            total += area(t);
        }
        if (size == 1) first = total;
        CHECK(total == doctest::Approx(first).epsilon(1e-12));
    }
    CHECK(first == doctest::Approx(4 * std::sqrt(3.0) * 2));  // four faces of edge 2 sqrt(2)
}

TEST_CASE("fractal mountain: a closed surface over the square, the same every time") {
    collect a, b;
    spd_generate(spd_database::mount, 4, a);
    spd_generate(spd_database::mount, 4, b);
    REQUIRE(a.triangles.size() == 512);
    double projected = 0;
    bool same = true;
    for (size_t i = 0; i < a.triangles.size(); ++i) {
        const auto& t = a.triangles[i];
        CHECK(area(t) > 0);
        // Seen from above, counter-clockwise, tiling the square [-1, 1]^2.
        double z = cross(t.b - t.a, t.c - t.a).z;
        CHECK(z > 0);
        projected += z / 2;
        same = same && t.a == b.triangles[i].a && t.b == b.triangles[i].b && t.c == b.triangles[i].c;
    }
    CHECK(projected == doctest::Approx(4.0));
    CHECK(same);
    CHECK(a.spheres.size() == 4);
}

TEST_CASE("a scene file can name a generator and its size") {
    scene_description d = parse_scene(R"({
        "camera": {"eye": [2.1, 1.3, 1.7], "look_at": [0, 0, 0], "up": [0, 0, 1]},
        "materials": [{"name": "ground"}, {"name": "flake", "diffuse": [0.9, 0.8, 0.6]}],
        "generate": {"name": "balls", "size": 2}
    })", "gen.json");
    CHECK(d.world.spheres.size() == 91);
    CHECK(d.world.planes.size() == 1);
    CHECK(d.world.planes[0].material == 0);
    CHECK(d.world.spheres[0].material == 1);
}

TEST_CASE("a bad generator entry is refused at its field") {
    auto error_of = [](const std::string& generate) -> std::string {
        try {
            parse_scene(R"({"camera": {"eye": [0, 0, 5], "look_at": [0, 0, 0]},
                            "materials": [{}, {}], "generate": )" + generate + "}", "gen.json");
        } catch (const scene_error& e) {
            return e.what();
        }
        return "accepted";
    };
    CHECK(error_of(R"({"name": "teapot", "size": 2})").find("generate.name: expected \"balls\"") != std::string::npos);
    CHECK(error_of(R"({"name": "balls", "size": 9})").find("generate.size: expected a size from 1 to 8") !=
          std::string::npos);
    CHECK(error_of(R"({"name": "balls"})").find("size") != std::string::npos);
    CHECK(error_of(R"({"name": "balls", "size": 1, "level": 3})").find("unknown key \"level\"") != std::string::npos);
}
