// scene_fuzz.cpp — libFuzzer target for the scene-file reader.
//
// The promise under test: on ANY input, parse_scene either returns a scene
// or throws scene_error; it never crashes, hangs, reads out of bounds or
// throws anything else. And a scene it accepts can really be used: both
// cameras build in float and double, and every number is finite in float.
// AddressSanitizer and UndefinedBehaviorSanitizer turn a silent memory or
// arithmetic bug into a reported crash.
//
// Build and run by hand (the ctest scenes.fuzz does this for 20 seconds):
//   clang++ -std=c++17 -g -O1 -fsanitize=fuzzer,address,undefined -I. \
//       tests/fuzz/scene_fuzz.cpp common/scene_file.cpp -o scene_fuzzer
//   mkdir -p fuzz-work && ./scene_fuzzer -dict=tests/fuzz/scene.dict fuzz-work tests/fuzz/corpus
#include "common/scene_file.hpp"

#include <cstdint>
#include <cstdlib>
#include <string>

namespace {

void check(bool ok) {
    if (!ok) std::abort();  // libFuzzer reports the input that got here
}

template <class T>
void check_usable(const rt::scene_description& d) {
    rt::scene_camera<T> camera(d.camera, 7, 5);  // throws std::invalid_argument if degenerate: a crash here
    rt::ray<T> r = camera.primary_ray(3, 2);
    check(rt::is_finite(r.origin) && rt::is_finite(r.direction));
    rt::scene<T> s = rt::convert_scene<T>(d.world);
    for (const auto& x : s.spheres) check(rt::is_finite(x.center) && x.radius > T(0) && std::isfinite(x.radius));
    for (const auto& x : s.planes) check(rt::is_finite(x.point) && rt::is_finite(x.normal));
    for (const auto& x : s.triangles) check(rt::is_finite(x.a) && rt::is_finite(x.b) && rt::is_finite(x.c));
    const int materials = int(s.materials.size());
    check(materials > 0);
    for (const auto& x : s.spheres) check(x.material >= 0 && x.material < materials);
    for (const auto& x : s.planes) check(x.material >= 0 && x.material < materials);
    for (const auto& x : s.triangles) check(x.material >= 0 && x.material < materials);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string text(reinterpret_cast<const char*>(data), size);
    try {
        const rt::scene_description d = rt::parse_scene(text, "fuzz.json");
        check_usable<float>(d);
        check_usable<double>(d);
    } catch (const rt::scene_error& e) {
        // A refusal must say where: a message that is not empty and starts with the file name.
        check(std::string(e.what()).rfind("fuzz.json", 0) == 0);
    }
    return 0;
}
