// Tests of the shared core: the conventions every chapter relies on.
#include "common/big_array.hpp"
#include "common/camera.hpp"
#include "common/error_metrics.hpp"
#include "common/hit_record.hpp"
#include "common/image.hpp"
#include "common/image_compare.hpp"
#include "common/chapter_scenes.hpp"
#include "common/interval.hpp"
#include "common/object_dispatch.hpp"
#include "common/ray.hpp"
#include "common/render.hpp"
#include "common/scene_file.hpp"
#include "common/stub.hpp"

#include "test_support.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <atomic>
#include <cstdio>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>

using namespace rt;

TEST_CASE_TEMPLATE("interval: the rule is tmin < t < tmax and NaN never passes", T, RT_SCALARS) {
    interval<T> range{T(1), T(2)};
    CHECK(range.surrounds(T(1.5)));
    CHECK_FALSE(range.surrounds(T(1)));
    CHECK_FALSE(range.surrounds(T(2)));
    CHECK_FALSE(range.surrounds(std::numeric_limits<T>::quiet_NaN()));
    CHECK_FALSE(interval<T>{}.surrounds(infinity<T>));
    CHECK(interval<T>::in_front_of_image_plane().surrounds(T(1.0001)));
    CHECK_FALSE(interval<T>::in_front_of_image_plane().surrounds(T(1)));
}

TEST_CASE_TEMPLATE("ray: at(t) walks along the direction", T, RT_SCALARS) {
    ray<T> r{{1, 2, 3}, {0, 0, -2}};
    CHECK(r.at(T(0)) == vec3<T>(1, 2, 3));
    CHECK(r.at(T(1.5)) == vec3<T>(1, 2, 0));
}

TEST_CASE_TEMPLATE("hit_record: one face rule, the side the ray arrives on", T, RT_SCALARS) {
    // The ground y = 0, whose outward normal is +y, hit from above and from below.
    hit_record<T> hit;
    hit.point = vec3<T>(0, 0, 0);
    hit.normal = vec3<T>(0, 1, 0);
    const ray<T> from_above{{0, 2, 1}, {0, -2, -1}}, from_below{{0, -2, 1}, {0, 2, -1}};
    CHECK(hit.front_face(from_above));
    CHECK(hit.facing_normal(from_above) == vec3<T>(0, 1, 0));
    CHECK_FALSE(hit.front_face(from_below));
    CHECK(hit.facing_normal(from_below) == vec3<T>(0, -1, 0));
    // The facing normal is always against the ray, whichever side it came from.
    CHECK(dot(hit.facing_normal(from_above), from_above.direction) < T(0));
    CHECK(dot(hit.facing_normal(from_below), from_below.direction) < T(0));
    // Turning is the rule's job alone, so asking again changes nothing: a normal already on the
    // ray's side stays there (a second flip elsewhere would be the only way to get it wrong).
    CHECK(facing_normal(hit.facing_normal(from_below), from_below.direction) == hit.facing_normal(from_below));
    // The member functions and the vector form are the same rule.
    CHECK(hit.front_face(from_below) == front_face(hit.normal, from_below.direction));
    // A ray in the tangent plane (dot 0) counts as a back face; NaN gives no front face either.
    CHECK_FALSE(front_face(hit.normal, vec3<T>(1, 0, 0)));
    CHECK_FALSE(front_face(hit.normal, vec3<T>(0, std::numeric_limits<T>::quiet_NaN(), 0)));
}

TEST_CASE_TEMPLATE("pinhole camera: the image plane is at t = 1 and row 0 is the top", T, RT_SCALARS) {
    auto frame = camera_frame<T>::look_at({0, 0, 0}, {0, 0, -1}, {0, 1, 0});
    pinhole_camera<T> cam(frame, T(90), 4, 2);
    ray<T> top_left = cam.primary_ray(0, 0);
    ray<T> bottom_right = cam.primary_ray(3, 1);
    // The direction ends on the plane z = -1: r(1) is on the image plane.
    CHECK(top_left.at(T(1)).z == doctest::Approx(-1));
    CHECK(top_left.direction.x < 0);  // left
    CHECK(top_left.direction.y > 0);  // top
    CHECK(bottom_right.direction.x > 0);
    CHECK(bottom_right.direction.y < 0);
    // A 90 degree vertical field of view spans y in [-1, 1] on the plane; pixel centres sit inside.
    CHECK(top_left.direction.y == doctest::Approx(0.5));
}

TEST_CASE_TEMPLATE("orthographic camera: parallel unit rays from the view rectangle", T, RT_SCALARS) {
    auto frame = camera_frame<T>::look_at({0, 0, 5}, {0, 0, 0}, {0, 1, 0});
    orthographic_camera<T> cam(frame, T(2), 2, 2);
    ray<T> a = cam.primary_ray(0, 0), b = cam.primary_ray(1, 1);
    CHECK(a.direction == b.direction);
    CHECK(length(a.direction) == doctest::Approx(1));
    CHECK(a.origin.x == doctest::Approx(-0.5));
    CHECK(a.origin.y == doctest::Approx(0.5));
}

TEST_CASE("camera: a degenerate frame or field of view is an error, not a NaN") {
    CHECK_THROWS_AS(camera_frame<double>::look_at({0, 0, 0}, {0, 0, 0}, {0, 1, 0}), std::invalid_argument);
    CHECK_THROWS_AS(camera_frame<double>::look_at({0, 0, 0}, {0, 1, 0}, {0, 1, 0}), std::invalid_argument);
    auto frame = camera_frame<double>::look_at({0, 0, 0}, {0, 0, -1}, {0, 1, 0});
    CHECK_THROWS_AS(pinhole_camera<double>(frame, 0.0, 10, 10), std::invalid_argument);
    CHECK_THROWS_AS(pinhole_camera<double>(frame, 45.0, 0, 10), std::invalid_argument);
}

TEST_CASE("ulp_distance counts representable numbers between two values") {
    CHECK(ulp_distance(1.0f, 1.0f) == 0);
    CHECK(ulp_distance(1.0f, std::nextafter(1.0f, 2.0f)) == 1);
    CHECK(ulp_distance(-0.0, 0.0) == 0);
    CHECK(ulp_distance(-std::numeric_limits<double>::denorm_min(), std::numeric_limits<double>::denorm_min()) == 2);
    CHECK(ulp_distance(1.0, 1.0 + 4 * std::numeric_limits<double>::epsilon()) == 4);
    CHECK(std::isinf(ulp_distance(std::nan(""), 1.0)));
}

TEST_CASE("relative_error is |computed - exact| / |exact|") {
    CHECK(relative_error(1.1, 1.0L) == doctest::Approx(0.1));
    CHECK(relative_error(0.5f, 0.0L) == doctest::Approx(0.5));  // absolute error at zero
    CHECK(std::isinf(relative_error(std::nan(""), 1.0L)));
}

TEST_CASE("sRGB encoding: 0 and 1 map to 0 and 255, NaN to 0, and it round-trips") {
    CHECK(linear_to_srgb8(0.0f) == 0);
    CHECK(linear_to_srgb8(1.0f) == 255);
    CHECK(linear_to_srgb8(2.0f) == 255);
    CHECK(linear_to_srgb8(std::nanf("")) == 0);
    for (int v = 0; v < 256; ++v) CHECK(linear_to_srgb8(srgb8_to_linear((unsigned char)v)) == v);
}

TEST_CASE("PNG: an image survives writing and reading") {
    image img(5, 3);
    for (int row = 0; row < 3; ++row)
        for (int col = 0; col < 5; ++col) img.at(col, row) = color(col / 4.0f, row / 2.0f, 0.25f);
    const std::string path = "common_test_roundtrip.png";
    write_png(img, path);
    image back = read_png(path);
    std::remove(path.c_str());
    REQUIRE(back.width == 5);
    REQUIRE(back.height == 3);
    compare_tolerance exact{0, 0.0};
    CHECK(compare_images(back, img, exact).within(exact));
}

TEST_CASE("PNG: reading a missing or broken file names the file") {
    try {
        read_png("no/such/file.png");
        FAIL("read_png should throw");
    } catch (const std::runtime_error& e) {
        CHECK(std::string(e.what()).find("no/such/file.png") != std::string::npos);
    }
    CHECK_THROWS_AS(write_png(image(2, 2), "no/such/folder/out.png"), std::runtime_error);
}

TEST_CASE("compare_images: tolerance on pixels and channels") {
    image a(10, 10, color(0.5f)), b = a;
    b.at(3, 3) = color(1, 0, 0);
    compare_tolerance strict{8, 0.0}, loose{8, 0.02};
    image diff;
    compare_result r = compare_images(b, a, strict, &diff);
    CHECK(r.differing_pixels == 1);
    CHECK_FALSE(r.within(strict));
    CHECK(r.within(loose));
    CHECK(diff.at(3, 3) == color(1, 0, 0));
    CHECK_FALSE(compare_images(image(3, 3), a, loose).within(loose));  // size differs
}

TEST_CASE("render: every pixel is shaded once, rows top to bottom") {
    image img = render(7, 5, [](int col, int row) { return color(float(col), float(row), 0); });
    for (int row = 0; row < 5; ++row)
        for (int col = 0; col < 7; ++col) CHECK(img.at(col, row) == color(float(col), float(row), 0));
}

TEST_CASE("render: a stub's exception reaches the caller unchanged") {
    auto shade = [](int, int row) -> color {
        if (row == 3) RT_NOT_IMPLEMENTED("chapter 00", "example");
        return color(0);
    };
    CHECK_THROWS_WITH_AS(render(4, 8, shade), "not implemented yet: chapter 00, example", not_implemented);
}

TEST_CASE("for_each_row: every row once and the first exception stops the pool") {
    std::vector<std::atomic<int>> seen(50);
    for_each_row(50, [&](int row) { ++seen[size_t(row)]; });
    for (const auto& count : seen) CHECK(count.load() == 1);
    CHECK_THROWS_AS(for_each_row(50, [](int row) { if (row == 7) throw std::runtime_error("row 7"); }),
                    std::runtime_error);
}

namespace {

// A scene with two spheres, one plane and one triangle: objects 0 1 | 2 | 3.
scene<double> one_of_each() {
    scene<double> s;
    s.materials.resize(4);
    s.spheres = {{{0, 0, 0}, 1, 0}, {{5, 0, 0}, 1, 1}};
    s.planes = {{{0, -1, 0}, {0, 1, 0}, 2}};
    s.triangles = {{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, 3}};
    return s;
}

// Stand-ins for the chapters' tests: each "hits" at t = 10 * kind + index,
// so the answer names the shape the dispatch picked.
std::optional<hit_record<double>> fake_hit(double t) {
    hit_record<double> h;
    h.t = t;
    return h;
}

}  // namespace

TEST_CASE("object_dispatch: spheres then planes then triangles each to its own test") {
    const scene<double> s = one_of_each();
    const auto sphere_test = [&](const sphere<double>& x, const ray<double>&, const interval<double>&) {
        return fake_hit(10 + double(&x - s.spheres.data()));
    };
    const auto plane_test = [](const plane<double>&, const ray<double>&, const interval<double>&) { return fake_hit(20); };
    const auto triangle_test = [](const triangle<double>&, const ray<double>&, const interval<double>&) {
        return fake_hit(30);
    };
    const object_dispatch dispatch(s, sphere_test, plane_test, triangle_test);
    const ray<double> r{{0, 0, 5}, {0, 0, -1}};
    const interval<double> range;
    CHECK(dispatch.count() == 4);
    CHECK(dispatch.shape_hit(0, r, range)->t == 10);
    CHECK(dispatch.shape_hit(1, r, range)->t == 11);
    CHECK(dispatch.shape_hit(2, r, range)->t == 20);
    CHECK(dispatch.shape_hit(3, r, range)->t == 30);
    CHECK(dispatch.shape_hit(3, r, range)->object == -1);  // the loop sets it, not the dispatch
    hit_record<double> h;
    CHECK(dispatch.object_hit(2, r, range, h));  // chapter 08's form: the object is set
    CHECK(h.t == 20);
    CHECK(h.object == 2);
    CHECK_THROWS_AS(dispatch.shape_hit(4, r, range), std::out_of_range);
    CHECK_THROWS_AS(dispatch.shape_hit(-1, r, range), std::out_of_range);
}

TEST_CASE("object_dispatch: a kind without a test must be absent from the scene") {
    const scene<double> s = one_of_each();
    const auto sphere_test = [](const sphere<double>&, const ray<double>&, const interval<double>&) { return fake_hit(1); };
    CHECK_THROWS_AS(object_dispatch(s, sphere_test), std::invalid_argument);
    scene<double> spheres_only = s;
    spheres_only.planes.clear();
    spheres_only.triangles.clear();
    const object_dispatch dispatch(spheres_only, sphere_test);
    CHECK(dispatch.count() == 2);
    CHECK(dispatch.shape_hit(1, ray<double>{}, interval<double>{})->t == 1);
}

TEST_CASE("material_at: the checker pattern alternates in unit squares of x and z") {
    material m;
    m.diffuse = color(1, 1, 1);
    m.checker = true;
    m.checker_color = color(0, 0, 0);
    CHECK(material_at(m, vec3<double>(0.5, 0.0, 0.5)).diffuse == color(1, 1, 1));
    CHECK(material_at(m, vec3<double>(1.5, 0.0, 0.5)).diffuse == color(0, 0, 0));
    CHECK(material_at(m, vec3<double>(-0.5, 0.0, 0.5)).diffuse == color(0, 0, 0));
    CHECK(material_at(m, vec3<float>(1.5f, -1e-7f, 1.5f)).diffuse == color(1, 1, 1));  // y does not matter
    CHECK(material_at(m, vec3<double>(1e300, 0, 0.5)).diffuse == color(1, 1, 1));      // huge: still defined
    m.checker = false;
    CHECK(material_at(m, vec3<double>(1.5, 0.0, 0.5)).diffuse == color(1, 1, 1));
}

// The SPD scenes' ground is the plane z = -0.5 (z up). With the squares
// picked by floor(x) + floor(z) whatever the plane, z is constant on it and
// the pattern came out as stripes: along y nothing changed. The checker must
// follow the plane's own axes.
TEST_CASE("material_at: the checker of a z-up plane follows the plane's axes, not stripes of x and z") {
    scene<double> s;
    material m;
    m.diffuse = color(1, 1, 1);
    m.checker = true;
    m.checker_color = color(0, 0, 0);
    s.materials = {m};
    s.planes.push_back({vec3d(0, 0, -0.5), vec3d(0, 0, 3), 0});  // z up, a normal of length 3
    hit_record<double> h;
    h.object = 0;
    auto at = [&](double x, double y, double z) {
        h.point = vec3d(x, y, z);
        return material_at(s, h).diffuse;
    };
    CHECK(at(0.5, 0.5, -0.5) == color(1, 1, 1));
    CHECK(at(1.5, 0.5, -0.5) == color(0, 0, 0));  // one square along x
    CHECK(at(0.5, 1.5, -0.5) == color(0, 0, 0));  // one square along y: the stripes had the same colour here
    CHECK(at(1.5, 1.5, -0.5) == color(1, 1, 1));
    CHECK(at(1.5, 1.5, -0.5 + 1e-9) == color(1, 1, 1));  // off the plane by rounding: the same square
    CHECK(at(1.5, 1.5, -0.5 - 1e-9) == color(1, 1, 1));
    // A tilted plane: squares of side 1 measured in the plane itself.
    const checker_axes a = checker_axes_of(vec3d(0, 1, 1));
    CHECK(std::fabs(dot(a.u, a.v)) < 1e-15);
    CHECK(std::fabs(dot(a.u, vec3d(0, 1, 1))) < 1e-15);
    CHECK(std::fabs(dot(a.v, vec3d(0, 1, 1))) < 1e-15);
    CHECK(std::fabs(length(a.u) - 1) < 1e-15);
    CHECK(std::fabs(length(a.v) - 1) < 1e-15);
    // A y-up ground keeps the x-z squares of every chapter's picture, bit for bit.
    const checker_axes g = checker_axes_of(vec3d(0, 2, 0));
    CHECK((g.u == vec3d(1, 0, 0) && g.v == vec3d(0, 0, 1)));
}

TEST_CASE("material_at: a hit names its material by its object and a bad object index says what is wrong") {
    scene<double> s = one_of_each();
    for (int i = 0; i < 4; ++i) s.materials[size_t(i)].diffuse = color(float(i));
    hit_record<double> h;
    h.object = 2;
    CHECK(material_at(s, h).diffuse == color(2));
    h.object = -1;
    CHECK_THROWS_WITH_AS(material_at(s, h), doctest::Contains("must set hit.object"), std::out_of_range);
}

TEST_CASE("chapter scenes: built in and named after their file and they parse") {
    const chapter_scene ch03 = chapter_scene_file("ch03");
    CHECK(ch03.source == "scenes/ch03-overlapping-spheres.json");
    CHECK(parse_scene(ch03.text, ch03.source).world.spheres.size() == 5);
    CHECK_THROWS_AS(chapter_scene_file("ch99"), std::invalid_argument);
}

namespace {
// A noisy picture: every pixel the mean of `samples` draws of a value whose
// expectation is the smooth image `level` (times `bias`), as a path tracer's
// pixel is. Fixed seeds: the same pictures on every run.
rt::image noisy_picture(unsigned seed, float bias, int samples = 8) {
    std::mt19937 gen(seed);
    std::exponential_distribution<float> draw(1.0f);  // mean 1, heavy right tail like fireflies
    rt::image img(96, 80);
    for (int row = 0; row < img.height; ++row)
        for (int col = 0; col < img.width; ++col) {
            const float level = 0.05f + 0.4f * float(col) / float(img.width) + 0.2f * float(row % 17) / 17.0f;
            rt::color sum(0.0f);
            for (int k = 0; k < samples; ++k) sum += rt::color(draw(gen), draw(gen), draw(gen)) * level * bias;
            img.at(col, row) = sum / float(samples);
        }
    return img;
}
}  // namespace

TEST_CASE("compare_noisy_images: two draws of one expectation match, a biased one does not") {
    const rt::noisy_tolerance tol;
    const rt::image reference = noisy_picture(1000, 1.0f);
    for (unsigned seed = 1; seed <= 20; ++seed) {
        const rt::noisy_compare_result r = rt::compare_noisy_images(noisy_picture(seed, 1.0f), reference, tol);
        INFO("seed " << seed << ": " << r.summary(tol));
        CHECK(r.within());
    }
    for (float bias : {0.9f, 1.1f}) {
        const rt::noisy_compare_result r = rt::compare_noisy_images(noisy_picture(7, bias), reference, tol);
        INFO("expectation times " << bias << ": " << r.summary(tol));
        CHECK_FALSE(r.within());
    }
    // A bias in one tile only: found by that tile, not by the whole picture's mean.
    rt::image local = noisy_picture(8, 1.0f);
    for (int row = 32; row < 48; ++row)
        for (int col = 48; col < 64; ++col) local.at(col, row) *= 1.5f;
    const rt::noisy_compare_result r = rt::compare_noisy_images(local, reference, tol);
    INFO(r.summary(tol));
    CHECK(r.tiles_past >= 1);
    CHECK_FALSE(r.within());
    INFO("identical pictures match; a constant offset (no noise to explain it) does not");
    CHECK(rt::compare_noisy_images(reference, reference, tol).within());
    CHECK(std::fabs(rt::two_sided_normal_threshold(0.05) - 1.959964) < 1e-5);
}

TEST_CASE("big_vector holds what is written, in huge pages or not, and advise_huge_pages takes any range") {
    // 12 MB: above big_allocator's 8 MB, so the block is advised before the
    // first write; each element written once, as the build and the
    // renderer's arrays are.
    big_vector<std::uint64_t> v(size_t(3) << 19);
    for (size_t i = 0; i < v.size(); ++i) v[i] = i * 2654435761u;
    bool same = true;
    for (size_t i = 0; i < v.size(); ++i) same = same && v[i] == i * 2654435761u;
    CHECK(same);
    v.resize(v.size() + 5, 7);  // growing with a value writes it, as std::vector does
    CHECK(v.back() == 7);
    // Ranges that hold no whole page, unaligned ones, and an empty one: the
    // advice is rounded inwards and the memory is left as it was.
    std::vector<char> bytes(3 * 4096 + 5, 'x');
    for (size_t from : {size_t(0), size_t(1), size_t(4095)})
        for (size_t n : {size_t(0), size_t(1), size_t(4096), size_t(2 * 4096 + 3)}) advise_huge_pages(bytes.data() + from, n);
    CHECK(std::count(bytes.begin(), bytes.end(), 'x') == std::ptrdiff_t(bytes.size()));
}

TEST_CASE("big_vector starts every block on a cache line, and a block of 8 MB or more on a 2 MB page") {
    // malloc's blocks start 16 bytes into a line: a pair of 32-byte tree
    // nodes laid out as one line would then straddle two.
    auto offset = [](const void* p, std::uintptr_t to) { return reinterpret_cast<std::uintptr_t>(p) % to; };
    for (size_t n : {size_t(1), size_t(3), size_t(1000), size_t(100000)}) {
        big_vector<float> small(n);
        INFO(n << " floats");
        CHECK(offset(small.data(), 64) == 0);
    }
    big_vector<std::uint64_t> big(size_t(3) << 19);  // 12 MB
    CHECK(offset(big.data(), std::uintptr_t(2) << 20) == 0);
    big.resize(big.size() * 2);  // a new block, freed with the alignment it was allocated with
    CHECK(offset(big.data(), std::uintptr_t(2) << 20) == 0);
}
