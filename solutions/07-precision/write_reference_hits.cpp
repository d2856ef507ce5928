// write_reference_hits.cpp — the reference answers for chapter 07's picture
// (chapters/07-precision/reference_hits.bin), made from the reference
// solution: its intersect_sphere_robust in long double on every primary ray
// of the default picture's panels, in float and in double, rounded to the
// precision of the ray. The kit ships the numbers, so a student's --error
// measures against the solution and not against the student's own long
// double version. Instructor side: it links the solution.
//
//   ch07-reference-hits FILE          writes FILE
//   ch07-reference-hits --check FILE  exits 1 unless FILE holds exactly these answers
#include "07-precision/picture_scenes.hpp"
#include "07-precision/robust_sphere.hpp"

#include <cstdint>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <string>

namespace {

using namespace rt;
using namespace rt::ch07_picture;

// The chapter program's default size is 640 x 480: panels of 320 x 240.
const int panel_width = 320, panel_height = 240;

template <class T>
void put(std::string& out, T x) {
    out.append(reinterpret_cast<const char*>(&x), sizeof x);
}

template <class T>
void append_answers(std::string& out, which_scene sc) {
    const std::vector<sphere<T>> spheres = spheres_of<T>(sc);
    const interval<T> range = visible_range<T>(sc);
    const interval<long double> wide_range{static_cast<long double>(range.min), static_cast<long double>(range.max)};
    std::string records;
    std::uint32_t count = 0;
    for (int row = 0; row < panel_height; ++row)
        for (int col = 0; col < panel_width; ++col) {
            const ray<T> r = panel_ray<T>(sc, col, row, panel_width, panel_height);
            for (int i = 0; i < int(spheres.size()); ++i) {
                const sphere<T>& s = spheres[size_t(i)];
                const sphere<long double> ws{convert<long double>(s.center), static_cast<long double>(s.radius)};
                const ray<long double> wr{convert<long double>(r.origin), convert<long double>(r.direction)};
                auto hit = ch07::intersect_sphere_robust(ws, wr, wide_range);
                if (!hit) continue;
                put(records, std::uint32_t((row * panel_width + col) * 3 + i));
                put(records, static_cast<T>(hit->t));
                ++count;
            }
        }
    put(out, count);
    out += records;
}

std::string answers() {
    std::string out(reference_magic);
    put(out, std::uint32_t(panel_width));
    put(out, std::uint32_t(panel_height));
    for (which_scene sc : both_scenes) append_answers<float>(out, sc);
    for (which_scene sc : both_scenes) append_answers<double>(out, sc);
    return out;
}

}  // namespace

int main(int argc, char** argv) {
    const bool check = argc == 3 && std::string(argv[1]) == "--check";
    if (!(argc == 2 || check)) {
        std::fprintf(stderr, "usage: %s FILE | --check FILE\n", argv[0]);
        return 2;
    }
    const std::string path = argv[argc - 1];
    const std::string data = answers();
    if (check) {
        std::ifstream in(path, std::ios::binary);
        const std::string held((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        if (held != data) {
            std::fprintf(stderr,
                         "%s does not hold the reference solution's answers for chapter 07's picture (the scenes, "
                         "the cameras or the solution changed): write it again with `ch07-reference-hits %s`\n",
                         path.c_str(), path.c_str());
            return 1;
        }
        std::printf("%s: the reference solution's answers, %zu bytes\n", path.c_str(), data.size());
        return 0;
    }
    std::ofstream(path, std::ios::binary) << data;
    std::printf("%s: %zu bytes\n", path.c_str(), data.size());
    return 0;
}
