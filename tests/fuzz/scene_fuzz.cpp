// scene_fuzz.cpp — libFuzzer target for the scene-file reader.
//
// The promise under test: on ANY input, parse_scene either returns a scene
// or throws scene_error; it never crashes, hangs, reads out of bounds or
// throws anything else. And a scene it accepts can really be used: both
// cameras build in float and double, and every number is finite in float.
// AddressSanitizer and UndefinedBehaviorSanitizer turn a silent memory or
// arithmetic bug into a reported crash.
//
// The same input is also given to the OBJ reader (common/obj_mesh.hpp),
// whose promise is the same: a mesh or an obj_error naming the source.
//
// Build and run by hand (the ctest scenes.fuzz does this for 20 seconds):
//   clang++ -std=c++17 -g -O1 -fsanitize=fuzzer,address,undefined -I. \
//       -DTINYOBJLOADER_USE_DOUBLE tests/fuzz/scene_fuzz.cpp common/scene_file.cpp common/spd.cpp \
//       common/obj_mesh.cpp -ltinyobjloader_double -o scene_fuzzer
//   mkdir -p fuzz-work && ./scene_fuzzer -dict=tests/fuzz/scene.dict fuzz-work tests/fuzz/corpus
#include "common/obj_mesh.hpp"
#include "common/scene_file.hpp"

#include <nlohmann/json.hpp>

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
    // Instances: every placement names an object, with finite transforms both ways.
    auto placement_ok = [&](const rt::instance_placement& i) {
        bool ok = i.object >= 0 && size_t(i.object) < d.objects.size() && rt::is_finite(i.from_parent.offset) &&
                  rt::is_finite(i.to_parent.offset);
        for (int c = 0; c < 3; ++c) ok = ok && rt::is_finite(i.from_parent.linear[c]) && rt::is_finite(i.to_parent.linear[c]);
        check(ok);
    };
    for (const auto& i : d.instances) placement_ok(i);
    for (const auto& o : d.objects) {
        for (const auto& i : o.instances) placement_ok(i);
        for (const auto& x : o.spheres) check(x.material >= 0 && x.material < materials);
        for (const auto& x : o.triangles) check(x.material >= 0 && x.material < materials);
    }
}

}  // namespace

// A generated scene above size 3 is big by design (balls 8: 48 million
// spheres, 2 GB): correct, but past the fuzzer's memory and time limits.
// A "generate" may sit at the top or in any object or instance.
bool has_big_generate(const nlohmann::json& j) {
    if (j.is_array()) {
        for (const auto& x : j)
            if (has_big_generate(x)) return true;
        return false;
    }
    if (!j.is_object()) return false;
    for (auto it = j.begin(); it != j.end(); ++it) {
        if (it.key() == "generate" && it->is_object()) {
            // A missing size is refused by the reader ("size" is required), so
            // only a size that is there can make the scene big. (operator[] of a
            // const json asserts on a missing key: look it up with find.)
            const auto size = it->find("size");
            if (size != it->end() && (!size->is_number() || size->get<double>() > 3)) return true;
        }
        if (has_big_generate(*it)) return true;
    }
    return false;
}

bool generates_a_big_scene(const std::string& text) {
    auto doc = nlohmann::json::parse(text, nullptr, /*allow_exceptions=*/false, /*ignore_comments=*/true);
    return has_big_generate(doc);
}

void fuzz_obj(const std::string& text) {
    try {
        rt::obj_mesh m = rt::parse_obj_mesh(text, "fuzz.obj");
        check(!m.triangles.empty());
        for (const auto& t : m.triangles) check(rt::is_finite(t.a) && rt::is_finite(t.b) && rt::is_finite(t.c));
    } catch (const rt::obj_error& e) {
        check(std::string(e.what()).rfind("fuzz.obj", 0) == 0);
    }
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string text(reinterpret_cast<const char*>(data), size);
    fuzz_obj(text);
    if (generates_a_big_scene(text)) return 0;
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
