// exact_bits.hpp — how values travel between the judge and the runner (tools/grader/README.md, "Who decides").
//
// The judge (the tests, without any student code) and the runner (the student's exercise code, without
// any test) talk over one socket. Every value is sent as its exact bits, so a test sees the very float or
// double the student's code returned: no rounding through text, no "close enough" in transit.
//
// A value is written with put(w, x) and read back with get(r, x); one overload per kind of value below.
// A struct is described once by a fields() overload listing its members, and then travels like any value.
// Reading never trusts the bytes: a short message, a length larger than the message, or a bool that is
// neither 0 nor 1 throws protocol_error (the runner may hold hostile code).
#pragma once

#include "common/camera.hpp"
#include "common/hit_record.hpp"
#include "common/interval.hpp"
#include "common/math.hpp"
#include "common/ray.hpp"
#include "common/scene.hpp"
#include "common/shapes.hpp"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <tuple>
#include <type_traits>
#include <utility>
#include <vector>

namespace rt::rpc {

// The other side sent something that is not a message of this protocol.
struct protocol_error : std::runtime_error {
    using std::runtime_error::runtime_error;
};

class writer {
public:
    void raw(const void* data, std::size_t size) { bytes_.append(static_cast<const char*>(data), size); }
    const std::string& bytes() const { return bytes_; }

private:
    std::string bytes_;
};

class reader {
public:
    explicit reader(const std::string& bytes) : at_(bytes.data()), end_(bytes.data() + bytes.size()) {}
    void raw(void* data, std::size_t size) {
        if (size > remaining()) throw protocol_error("a message ended in the middle of a value");
        std::memcpy(data, at_, size);
        at_ += size;
    }
    std::size_t remaining() const { return static_cast<std::size_t>(end_ - at_); }

private:
    const char* at_;
    const char* end_;
};

// --- numbers: their bytes, so the bits arrive unchanged -------------------------------------------
template <class T, std::enable_if_t<std::is_arithmetic_v<T> && !std::is_same_v<T, bool>, int> = 0>
void put(writer& w, T value) {
    w.raw(&value, sizeof value);
}
template <class T, std::enable_if_t<std::is_arithmetic_v<T> && !std::is_same_v<T, bool>, int> = 0>
void get(reader& r, T& value) {
    r.raw(&value, sizeof value);
}

inline void put(writer& w, bool value) { put(w, std::uint8_t(value ? 1 : 0)); }
inline void get(reader& r, bool& value) {
    std::uint8_t byte = 0;
    get(r, byte);
    if (byte > 1) throw protocol_error("a bool that is neither true nor false");
    value = byte == 1;
}

inline void put(writer& w, const std::string& s) {
    put(w, std::uint32_t(s.size()));
    w.raw(s.data(), s.size());
}
inline void get(reader& r, std::string& s) {
    std::uint32_t size = 0;
    get(r, size);
    if (size > r.remaining()) throw protocol_error("a string longer than its message");
    s.resize(size);
    r.raw(s.data(), size);
}

template <class T>
void put(writer& w, const vec3<T>& v) {
    put(w, v.x), put(w, v.y), put(w, v.z);
}
template <class T>
void get(reader& r, vec3<T>& v) {
    get(r, v.x), get(r, v.y), get(r, v.z);
}

template <class T>
void put(writer& w, const glm::vec<2, T, glm::defaultp>& v) {
    put(w, v.x), put(w, v.y);
}
template <class T>
void get(reader& r, glm::vec<2, T, glm::defaultp>& v) {
    get(r, v.x), get(r, v.y);
}

// --- the course's structs: each lists its members once ----------------------------------------------
template <class T, class F> void fields(interval<T>& x, F&& f) { f(x.min, x.max); }
template <class T, class F> void fields(ray<T>& x, F&& f) { f(x.origin, x.direction); }
template <class T, class F> void fields(sphere<T>& x, F&& f) { f(x.center, x.radius, x.material); }
template <class T, class F> void fields(plane<T>& x, F&& f) { f(x.point, x.normal, x.material); }
template <class T, class F> void fields(triangle<T>& x, F&& f) { f(x.a, x.b, x.c, x.material); }
template <class T, class F> void fields(hit_record<T>& x, F&& f) { f(x.t, x.point, x.normal, x.object); }
template <class F> void fields(material& x, F&& f) {
    f(x.diffuse, x.specular, x.shininess, x.checker, x.checker_color, x.mirror, x.ior);
}
template <class T, class F> void fields(camera_frame<T>& x, F&& f) { f(x.eye, x.u, x.v, x.w); }
template <class T, class F> void fields(pinhole_camera<T>& x, F&& f) { f(x.frame, x.width, x.height, x.half_height); }
template <class F> void fields(point_light& x, F&& f) { f(x.position, x.intensity, x.radius); }
template <class T, class F> void fields(scene<T>& x, F&& f) {
    f(x.spheres, x.planes, x.triangles, x.materials, x.lights, x.ambient, x.background);
}

// Any callable does for the detection below (C++17 allows no lambda there).
struct any_members {
    template <class... M>
    void operator()(M&...) const {}
};
template <class S, class = void>
struct has_fields : std::false_type {};
template <class S>
struct has_fields<S, std::void_t<decltype(fields(std::declval<S&>(), any_members{}))>> : std::true_type {};

template <class S, std::enable_if_t<has_fields<S>::value, int> = 0>
void put(writer& w, const S& s) {
    fields(const_cast<S&>(s), [&w](auto&... member) { (put(w, member), ...); });
}
template <class S, std::enable_if_t<has_fields<S>::value, int> = 0>
void get(reader& r, S& s) {
    fields(s, [&r](auto&... member) { (get(r, member), ...); });
}

// --- containers ---------------------------------------------------------------------------------------
template <class T>
void put(writer& w, const std::optional<T>& x) {
    put(w, x.has_value());
    if (x) put(w, *x);
}
template <class T>
void get(reader& r, std::optional<T>& x) {
    bool present = false;
    get(r, present);
    x.reset();
    if (present) get(r, x.emplace());
}

template <class T>
void put(writer& w, const std::vector<T>& v) {
    put(w, std::uint32_t(v.size()));
    for (const T& x : v) put(w, x);
}
template <class T>
void get(reader& r, std::vector<T>& v) {
    std::uint32_t size = 0;
    get(r, size);
    if (size > r.remaining()) throw protocol_error("a list longer than its message");  // every item has >= 1 byte
    // Item by item, not assign(size): an item may be 60 bytes in memory and far fewer on the wire, so a
    // runner's forged length must not make the judge (root, outside the sandbox) allocate for items the
    // message does not hold. The vector grows only as items are actually read.
    v.clear();
    v.reserve(std::min<std::size_t>(size, r.remaining() / sizeof(T) + 1));
    for (std::uint32_t k = 0; k < size; ++k) {
        T x{};
        get(r, x);
        v.push_back(std::move(x));
    }
}

// --- callbacks ------------------------------------------------------------------------------------------
// An object callback (chapter 03's intersector, chapter 08's leaf test) travels as a number: the judge
// keeps what answers it and the runner's code asks the judge for every call (served_by_judge.hpp).
using erased_callback = std::function<void(reader& arguments, writer& result)>;
std::uint32_t judge_keep_callback(erased_callback f);                          // judge side (judge_side.cpp)
std::string runner_call_back(std::uint32_t id, const std::string& arguments);  // runner side (runner_main.cpp)

// A std::function argument has no put(): it never crosses as code. The judge's stub sends what the
// test's callback stands for: a number for an object callback, the answers for chapter 06's occlusion
// test (served.hpp, served_by_judge.hpp).

}  // namespace rt::rpc
