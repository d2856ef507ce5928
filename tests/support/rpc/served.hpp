// served.hpp — callbacks the tests give an exercise, as data (tools/grader/README.md, "Who decides").
//
// Chapter 03's closest_hit and chapter 08's traversal call back "does the ray hit object i inside this
// range?". Under the grader the student's code runs in the runner and the tests in the judge. A test's
// callback is a TABLE the judge makes for the one ray of the call: every hit that object i's own test
// (the reference sphere, triangle, a test's "wall") gives along that ray, in increasing t. Asked about
// object i in an open range, the table answers the first of object i's hits inside the range: exactly
// what the object's test answers, because a shape test returns its smallest t inside the range, and the
// table holds all of them (see table_for below). The table stays in the judge: the runner sends each
// call's arguments and gets the answer back (served_wire.hpp says why).
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

// What the judge sends with one call: object i's hits along ray r, and the test's rules.
template <class T>
struct hit_table {
    ray<T> r{};
    int count = 0;                            // objects 0 .. count-1 exist
    std::vector<int> owner;                   // owner[k]: whose hit records[k] is (increasing; then t increasing)
    std::vector<hit_record<T>> records;       // as the object's own test returned them
    long budget = -1;                         // calls answered; -1: no limit
    bool check_calls = false;                 // when true, exactly the calls in `expected`, in order
    std::vector<expected_call<T>> expected;
};

// Answers calls from a table (in the judge, or in the test's own process), call after call.
template <class T>
class table_server {
public:
    explicit table_server(hit_table<T> table) : table_(std::move(table)) {}

    const ray<T>& for_ray() const { return table_.r; }

    std::optional<hit_record<T>> answer(int i, const ray<T>& r, const interval<T>& range) {
        const int call = calls_++;
        if (!fault_) {
            if (const auto broken = rule_broken(call, i, r, range)) fault_ = fault_note<T>{*broken, call, i, range};
        }
        if (fault_) return fault_answer(range);
        for (std::size_t k = first_of(i); k < table_.owner.size() && table_.owner[k] == i; ++k)
            if (range.contains(table_.records[k].t)) return table_.records[k];
        return std::nullopt;
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
        if (table_.budget >= 0 && call >= table_.budget) return call_fault::over_budget;
        if (i < 0 || i >= table_.count) return call_fault::no_such_object;
        if (!same_bits(r, table_.r)) return call_fault::other_ray;
        if (table_.check_calls) {
            if (std::size_t(call) >= table_.expected.size()) return call_fault::unexpected_call;
            const expected_call<T>& e = table_.expected[std::size_t(call)];
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

    std::size_t first_of(int i) const {
        std::size_t lo = 0, hi = table_.owner.size();
        while (lo < hi) {
            const std::size_t mid = (lo + hi) / 2;
            if (table_.owner[mid] < i) lo = mid + 1;
            else hi = mid;
        }
        return lo;
    }

    hit_table<T> table_;
    int calls_ = 0;
    std::optional<fault_note<T>> fault_;
};

// The callable a test gives as its callback (chapter 03's object_intersector, chapter 08's
// leaf_intersector): objects 0 .. count-1, each tested by `test` (instructor code: it runs in the judge,
// or in the test's own process), with the test's rules. In the judge, its table_for() answers the runner;
// in the test's own process (a student's build) it answers through the same table_server, one table per
// ray, so the tests behave the same in both places.
template <class T>
struct served_objects {
    using object_test = std::function<std::optional<hit_record<T>>(int i, const ray<T>& r, const interval<T>& range)>;

    int count = 0;
    object_test test;
    long budget = -1;
    bool check_calls = false;
    std::vector<expected_call<T>> expected;
    std::optional<ray<T>> only_ray;  // when set, the one ray every call must ask about (else: the call's)
    std::shared_ptr<std::optional<table_server<T>>> here = std::make_shared<std::optional<table_server<T>>>();

    // Every hit of every object along r. A shape test returns the smallest t inside the open range it
    // is given, so asking again above the last t found gives the next one; (-inf, inf) starts.
    hit_table<T> table_for(const ray<T>& r) const {
        hit_table<T> table;
        table.r = r;
        table.count = count;
        table.budget = budget;
        table.check_calls = check_calls;
        table.expected = expected;
        for (int i = 0; i < count; ++i) {
            T above = -infinity<T>;
            for (int k = 0; k < 4; ++k) {  // a shape of the course has at most 2 hits along a line
                const auto hit = test(i, r, interval<T>{above, infinity<T>});
                if (!hit || !(hit->t > above)) break;
                table.owner.push_back(i);
                table.records.push_back(*hit);
                above = hit->t;
            }
        }
        return table;
    }

    // In the test's own process: a new table whenever the ray changes (a new call of the exercise).
    std::optional<hit_record<T>> operator()(int i, const ray<T>& r, const interval<T>& range) const {
        const ray<T>& wanted = only_ray ? *only_ray : r;
        if (!*here || std::memcmp(&(*here)->for_ray(), &wanted, sizeof wanted) != 0) here->emplace(table_for(wanted));
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
