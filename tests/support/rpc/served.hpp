// served.hpp — callbacks the tests give an exercise, and the rules they check (tools/grader/README.md, "Who decides").
//
// Chapter 03's closest_hit and chapter 08's traversal call back "does the ray hit object i inside this
// range?". Under the grader the student's code runs in the runner and the tests in the judge. The judge
// keeps the test's callback and answers each call the runner sends with the object's own test (the
// test's "wall", the reference sphere or triangle), after checking the test's rules (served_wire.hpp
// says why nothing is answered from data in the runner).
//
// How the code under test uses the callback is decided from the calls the judge itself answered and
// from the exercise's answer, never from a log the runner keeps (the runner is the student's process).
// A call that breaks a rule of the test:
//   * beyond the test's call budget (an empty scene asks nothing; a pruned traversal asks few objects),
//   * about an object that does not exist, or about another ray than the call's,
//   * not the call the test expects next (chapter 03: objects 0, 1, 2, ... with tmax shrunk),
// is answered, from then on, with a FAULT RECORD: a hit just inside the asked range, so it is the
// nearest hit the code can keep, whose normal says which rule broke at which call (fault_in() reads it).
// Code that keeps the nearest hit hands it back, and the judge sees the fault in the answer.
#pragma once

#include "common/hit_record.hpp"
#include "common/interval.hpp"
#include "common/ray.hpp"

#include <cmath>
#include <cstring>
#include <functional>
#include <memory>
#include <stdexcept>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace rt::test {

// Which rule of the test a call broke.
enum class call_fault : int {
    over_budget = 1,      // more calls than the test allows
    no_such_object = 2,   // an index outside 0 .. count-1
    other_ray = 3,        // not the ray the exercise was given
    unexpected_call = 4,  // not the call the test expects next (object or range)
};

// What a fault record says: the first call that broke a rule (numbered from 0) and what it asked.
template <class T>
struct fault_note {
    call_fault fault{};
    int call = 0;
    int object = 0;
    interval<T> range{};
};

// One call a test expects, in order: object i about this range.
template <class T>
struct expected_call {
    int object = 0;
    interval<T> range{};
};

// A fault record carries -(2 + fault) in normal.z: a real normal (unit length, or a test wall's z = 1)
// never has z <= -3.
template <class T>
hit_record<T> fault_record(const fault_note<T>& note, T t) {
    hit_record<T> h;
    h.t = t;
    h.point = vec3<T>(note.range.min, note.range.max, T(0));
    h.normal = vec3<T>(T(note.call), T(note.object), -T(2 + int(note.fault)));
    return h;
}

template <class T>
std::optional<fault_note<T>> fault_in(const std::optional<hit_record<T>>& hit) {
    if (!hit) return std::nullopt;
    const T z = -hit->normal.z - T(2);
    if (!(z >= T(1) && z <= T(4) && z == std::floor(z))) return std::nullopt;
    // The answer is the student's: a number that is no int must not be converted to one.
    const auto as_int = [](T v) { return std::isfinite(v) && std::fabs(v) < T(1e9) ? int(v) : -1; };
    fault_note<T> note;
    note.fault = call_fault(int(z));
    note.call = as_int(hit->normal.x);
    note.object = as_int(hit->normal.y);
    note.range = {hit->point.x, hit->point.y};
    return note;
}

// The rule a fault broke, in the lecture's words (for a failure message).
template <class T>
std::string describe_fault(const fault_note<T>& note) {
    const std::string call = "call " + std::to_string(note.call + 1) + " (object " + std::to_string(note.object) + ")";
    switch (note.fault) {
        case call_fault::over_budget: return call + " was one more than the test allows";
        case call_fault::no_such_object: return call + " asked about an object that does not exist";
        case call_fault::other_ray: return call + " asked about another ray than the one given";
        case call_fault::unexpected_call: return call + " was not the call expected next";
    }
    return call;
}

// The test's rules for one call of the exercise: the ray it was given, the objects that exist, how many
// calls it may make and, when checked, which calls in which order.
template <class T>
struct call_rules {
    ray<T> r{};
    int count = 0;                            // objects 0 .. count-1 exist
    long budget = -1;                         // calls answered; -1: no limit
    bool check_calls = false;                 // when true, exactly the calls in `expected`, in order
    std::vector<expected_call<T>> expected;
};

// The instructor's test of object i (a test's "wall", the reference sphere or triangle).
template <class T>
using object_test = std::function<std::optional<hit_record<T>>(int i, const ray<T>& r, const interval<T>& range)>;

// Answers one call of the exercise's callbacks after another (in the judge, or in the test's own
// process): with the object's own test while the rules hold, with a fault record from the first call
// that breaks one.
template <class T>
class object_server {
public:
    object_server(call_rules<T> rules, object_test<T> test) : rules_(std::move(rules)), test_(std::move(test)) {}

    const ray<T>& for_ray() const { return rules_.r; }

    std::optional<hit_record<T>> answer(int i, const ray<T>& r, const interval<T>& range) {
        const int call = calls_++;
        if (!fault_) {
            if (const auto broken = rule_broken(call, i, r, range)) fault_ = fault_note<T>{*broken, call, i, range};
        }
        if (fault_) return fault_answer(range);
        return test_(i, r, range);
    }

private:
    static bool same_bits(const ray<T>& a, const ray<T>& b) {
        return std::memcmp(&a.origin, &b.origin, sizeof a.origin) == 0 &&
               std::memcmp(&a.direction, &b.direction, sizeof a.direction) == 0;
    }
    static bool same_bits(const interval<T>& a, const interval<T>& b) {
        return std::memcmp(&a.min, &b.min, sizeof(T)) == 0 && std::memcmp(&a.max, &b.max, sizeof(T)) == 0;
    }

    std::optional<call_fault> rule_broken(int call, int i, const ray<T>& r, const interval<T>& range) const {
        if (rules_.budget >= 0 && call >= rules_.budget) return call_fault::over_budget;
        if (i < 0 || i >= rules_.count) return call_fault::no_such_object;
        if (!same_bits(r, rules_.r)) return call_fault::other_ray;
        if (rules_.check_calls) {
            if (std::size_t(call) >= rules_.expected.size()) return call_fault::unexpected_call;
            const expected_call<T>& e = rules_.expected[std::size_t(call)];
            if (e.object != i || !same_bits(e.range, range)) return call_fault::unexpected_call;
        }
        return std::nullopt;
    }

    // The fault record just inside the asked range, so it is the nearest hit there can be; none when the
    // range holds no number at all.
    std::optional<hit_record<T>> fault_answer(const interval<T>& range) const {
        const T t = std::nextafter(range.min, range.max);
        if (!range.contains(t)) return std::nullopt;
        return fault_record(*fault_, t);
    }

    call_rules<T> rules_;
    object_test<T> test_;
    int calls_ = 0;
    std::optional<fault_note<T>> fault_;
};

// The callable a test gives as its callback (chapter 03's object_intersector, chapter 08's
// leaf_intersector): objects 0 .. count-1, each tested by `test` (instructor code), with the test's
// rules. Under the grader the judge keeps it and answers the runner's calls through an object_server
// (served_wire.hpp); in the test's own process (a student's build) it answers through an object_server
// too, a new one whenever the ray changes (a new call of the exercise), so the tests behave the same in
// both places.
template <class T>
struct served_objects {
    int count = 0;
    object_test<T> test;
    long budget = -1;
    bool check_calls = false;
    std::vector<expected_call<T>> expected;
    std::optional<ray<T>> only_ray;  // when set, the one ray every call must ask about (else: the call's)
    std::shared_ptr<std::optional<object_server<T>>> here = std::make_shared<std::optional<object_server<T>>>();

    // The server of one call of the exercise, given ray r.
    object_server<T> server_for(const ray<T>& r) const {
        return object_server<T>(call_rules<T>{only_ray ? *only_ray : r, count, budget, check_calls, expected}, test);
    }

    std::optional<hit_record<T>> operator()(int i, const ray<T>& r, const interval<T>& range) const {
        const ray<T>& wanted = only_ray ? *only_ray : r;
        if (!*here || std::memcmp(&(*here)->for_ray(), &wanted, sizeof wanted) != 0) here->emplace(server_for(r));
        return (*here)->answer(i, r, range);
    }

    // Chapter 08's form: true and the record (with hit.object = i) when hit.
    bool operator()(int i, const ray<T>& r, const interval<T>& range, hit_record<T>& hit) const {
        return fill(operator()(i, r, range), i, hit);
    }

    static bool fill(const std::optional<hit_record<T>>& answer, int i, hit_record<T>& hit) {
        if (!answer) return false;
        hit = *answer;
        hit.object = i;
        return true;
    }
};

// ---- chapter 06: the occlusion test -------------------------------------------------------------------
//
// shade() asks occluded(q.r, q.range) with q = shadow_ray(point, n, light) for each light above the
// surface (shading.hpp). The judge knows the point, the normal and the lights of the call, so it asks
// the student's own shadow_ray for every light (on both sides of the surface: which side shade() takes
// is the student's arithmetic) and keeps each query with the answer the test's occlusion test gives it.
// It answers the runner's questions from that list; any other question, or one beyond the test's
// budget, makes the judge throw std::logic_error out of shade() once the call is over (a bool answer
// has no room for a fault record, and an exception thrown in the runner could be caught there).

// One question shade() may ask and the test's answer to it.
template <class T>
struct shadow_answer {
    ray<T> r{};
    interval<T> range{};
    bool blocked = false;
};

template <class T>
struct occlusion_table {
    std::vector<shadow_answer<T>> answers;
    long budget = -1;  // questions answered; -1: no limit
};

inline const char* occlusion_over_budget =
    "shade asked the occlusion test more often than it should (a light below the surface, or at the point, "
    "needs no shadow ray)";
inline const char* occlusion_other_question =
    "shade asked the occlusion test about another ray or range than shadow_ray(point, n, light) gives for "
    "one of the lights";

template <class T>
class occlusion_server {
public:
    explicit occlusion_server(occlusion_table<T> table) : table_(std::move(table)) {}

    bool answer(const ray<T>& r, const interval<T>& range) {
        if (table_.budget >= 0 && calls_++ >= table_.budget) throw std::logic_error(occlusion_over_budget);
        for (const shadow_answer<T>& a : table_.answers)
            if (std::memcmp(&a.r, &r, sizeof r) == 0 && std::memcmp(&a.range.min, &range.min, sizeof(T)) == 0 &&
                std::memcmp(&a.range.max, &range.max, sizeof(T)) == 0)
                return a.blocked;
        throw std::logic_error(occlusion_other_question);
    }

private:
    occlusion_table<T> table_;
    long calls_ = 0;
};

// The callable a test gives shade() as its occlusion test: `blocked` is the test's own (instructor code,
// in the judge or in the test's own process). In the test's own process it is asked directly, with the
// same budget.
template <class T>
struct served_occlusion {
    std::function<bool(const ray<T>& r, const interval<T>& range)> blocked;
    long budget = -1;
    std::shared_ptr<long> calls = std::make_shared<long>(0);

    // The judge's table for the questions shade() may ask in this call.
    occlusion_table<T> table_for(const std::vector<std::pair<ray<T>, interval<T>>>& questions) const {
        occlusion_table<T> table;
        table.budget = budget;
        for (const auto& [r, range] : questions) table.answers.push_back({r, range, blocked(r, range)});
        return table;
    }

    bool operator()(const ray<T>& r, const interval<T>& range) const {
        if (budget >= 0 && (*calls)++ >= budget) throw std::logic_error(occlusion_over_budget);
        return blocked(r, range);
    }
};

// Nothing blocks, everything blocks: the two plain occlusion tests.
template <class T>
served_occlusion<T> nothing_blocks() {
    return {[](const ray<T>&, const interval<T>&) { return false; }};
}
template <class T>
served_occlusion<T> everything_blocks() {
    return {[](const ray<T>&, const interval<T>&) { return true; }};
}

}  // namespace rt::test
