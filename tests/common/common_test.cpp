// Tests of the shared core: the conventions every chapter relies on.
#include "common/camera.hpp"
#include "common/error_metrics.hpp"
#include "common/image.hpp"
#include "common/image_compare.hpp"
#include "common/interval.hpp"
#include "common/ray.hpp"
#include "common/render.hpp"
#include "common/stub.hpp"

#include "test_support.hpp"

#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <string>

using namespace rt;

TEST_CASE_TEMPLATE("interval: the rule is tmin < t < tmax and NaN never passes", T, RT_SCALARS) {
    interval<T> range{T(1), T(2)};
    CHECK(range.contains(T(1.5)));
    CHECK_FALSE(range.contains(T(1)));
    CHECK_FALSE(range.contains(T(2)));
    CHECK_FALSE(range.contains(std::numeric_limits<T>::quiet_NaN()));
    CHECK_FALSE(interval<T>{}.contains(infinity<T>));
    CHECK(interval<T>::in_front_of_image_plane().contains(T(1.0001)));
    CHECK_FALSE(interval<T>::in_front_of_image_plane().contains(T(1)));
}

TEST_CASE_TEMPLATE("ray: at(t) walks along the direction", T, RT_SCALARS) {
    ray<T> r{{1, 2, 3}, {0, 0, -2}};
    CHECK(r.at(T(0)) == vec3<T>(1, 2, 3));
    CHECK(r.at(T(1.5)) == vec3<T>(1, 2, 0));
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
