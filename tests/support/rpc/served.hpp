// served.hpp — callbacks the tests give an exercise, and the rules they check (README.md here).
//
// Chapter 03's closest_hit and chapter 08's traversal call back "does the ray hit object i inside this
// range?". Under the grader the student's code runs in the runner and the tests in the judge. The judge
// keeps the test's callback and answers each call the runner sends with the object's own test (the
// test's "wall", the reference sphere or triangle), after checking the test's rules (served_by_judge.hpp
// says why nothing is answered from data in the runner).
//
// How the code under test uses the callback is decided from the judge's own RECORD of the calls it
// answered (object_server), never from the exercise's answer and never from a log the runner keeps:
// both are the student's to choose. A call that breaks a rule of the test:
//   * beyond the test's call budget (an empty scene asks nothing; a pruned traversal asks few objects),
//   * about an object that does not exist, or about another ray than the call's,
//   * not the call the test expects next (chapter 03: objects 0, 1, 2, ... with tmax shrunk),
// is written in the record, and it and every later call of that exercise call are answered with a miss.
// Once the exercise's call is over, the judge throws broken_rule out of it (in the judge, where the
// student's code cannot catch it), whatever the answer was; a test that wants to say more about the
// rule reads the note the exception carries (call_with_rules). In the student's own build the same
// callables answer in-process and throw broken_rule at the call that broke the rule, so an honest
// exercise fails the same tests, with the same messages, in both places.
#pragma once

#include "common/hit_record.hpp"
#include "common/interval.hpp"
#include "common/ray.hpp"

#include <cstring>
#include <functional>
#include <memory>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace rt::test {

// Which rule of the test a call broke.
enum class call_fault : int {
    over_budget = 1,      // more calls than the test allows
    no_such_object = 2,   // an index outside 0 .. count-1
    other_ray = 3,        // not the ray the exercise was given
    unexpected_call = 4,  // not the call the test expects next (object or range)
    other_object_ray = 5, // chapter 10: not the object-space ray of an instance placing that model
};

// One call a test expects, in order: object i about this range.
template <class T>
struct expected_call {
    int object = 0;
    interval<T> range{};
};

// The judge's note of the first call that broke a rule: which rule, which call (numbered from 0), what
// it asked, and what the rule allowed.
template <class T>
struct fault_note {
    call_fault fault{};
    long call = 0;
    int object = 0;
    interval<T> range{};
    long budget = -1;                         // the test's budget (over_budget)
    int count = 0;                            // the objects that exist, 0 .. count-1 (no_such_object)
    std::optional<expected_call<T>> expected; // the call expected instead (unexpected_call; none: no more calls)
};

// The rule a note says was broken, in the lecture's words. With `values` the numbers of the call are
// in the message (public tests: they teach); without, only the rule (hidden tests show the concept, and
// the numbers of a call are chosen by the student's code: they could carry a hidden input out).
template <class T>
std::string describe_fault(const fault_note<T>& note, bool values) {
    std::ostringstream s;
    s << "a rule of this test's intersect callback was broken: ";
    if (!values) {
        switch (note.fault) {
            case call_fault::over_budget: s << "it was called more often than the test allows"; break;
            case call_fault::no_such_object: s << "it was asked about an object that does not exist"; break;
            case call_fault::other_ray: s << "it was asked about another ray than the one the exercise was given"; break;
            case call_fault::unexpected_call:
                s << "its calls were not the ones expected (each object once, in order 0, 1, 2, ..., with the "
                     "caller's tmin and the closest t so far as tmax)";
                break;
            case call_fault::other_object_ray:
                s << "a model was asked about a ray that is not transform_ray(to_object, r) of an instance placing it";
                break;
        }
        return s.str();
    }
    s << "call " << note.call + 1 << " asked about object " << note.object;
    switch (note.fault) {
        case call_fault::over_budget:
            if (note.budget == 0) s << ", but this test allows no call at all";
            else s << ", one call more than this test allows (" << note.budget << ")";
            break;
        case call_fault::no_such_object:
            if (note.count <= 0) s << ", but there are no objects";
            else s << ", but the objects are 0 .. " << note.count - 1;
            break;
        case call_fault::other_ray: s << " for another ray than the one the exercise was given: pass it on unchanged"; break;
        case call_fault::other_object_ray:
            s << " about a ray that is not transform_ray(inst.place.to_object, r) of any instance placing model "
              << note.object << ": take the world ray into the model's space with your transform_ray, bit for bit";
            break;
        case call_fault::unexpected_call:
            s << " with (tmin, tmax) = (" << note.range.min << ", " << note.range.max << ")";
            if (note.expected)
                s << ", but the call expected next is object " << note.expected->object << " with (tmin, tmax) = ("
                  << note.expected->range.min << ", " << note.expected->range.max << ")";
            else
                s << ", but every object had been asked already";
            break;
    }
    return s.str();
}

// Thrown out of the exercise's call when one of its calls broke a rule of the test. A std::logic_error,
// so a test that does not look for it fails with its message.
template <class T>
struct broken_rule : std::logic_error {
    broken_rule(const fault_note<T>& n, bool values) : std::logic_error(describe_fault(n, values)), note(n) {}
    fault_note<T> note;
};

// One call of an exercise that takes a served callback, and the record's word on it: `broken` is the
// first rule the call broke (the answer then does not count and is left empty). Any other exception
// goes on.
template <class T, class R>
struct ruled_call {
    R answer{};
    std::optional<fault_note<T>> broken;
};

template <class T, class Call>
ruled_call<T, std::invoke_result_t<Call&>> call_with_rules(Call&& call) {
    try {
        return {call(), std::nullopt};
    } catch (const broken_rule<T>& e) {
        return {{}, e.note};
    }
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
    // Chapter 10: when not empty, the (model, object-space ray) pairs a call may ask about (each
    // instance's model and transform_ray(to_object, r)), in place of the one ray `r`.
    std::vector<std::pair<int, ray<T>>> object_rays;
};

// The instructor's test of object i (a test's "wall", the reference sphere or triangle).
template <class T>
using object_test = std::function<std::optional<hit_record<T>>(int i, const ray<T>& r, const interval<T>& range)>;

// Answers the callback's calls of one call of the exercise (in the judge, or in the test's own process)
// and keeps the record: how many calls, and the first that broke a rule. While the rules hold a call
// gets the object's own test; from the first broken rule on, a miss (the verdict is already written).
template <class T>
class object_server {
public:
    object_server(call_rules<T> rules, object_test<T> test) : rules_(std::move(rules)), test_(std::move(test)) {}

    const ray<T>& for_ray() const { return rules_.r; }
    long calls() const { return calls_; }
    const std::optional<fault_note<T>>& broken() const { return broken_; }

    std::optional<hit_record<T>> answer(int i, const ray<T>& r, const interval<T>& range) {
        const long call = calls_++;
        if (!broken_) broken_ = rule_broken(call, i, r, range);
        if (broken_) return std::nullopt;
        return test_(i, r, range);
    }

    // Once the exercise's call is over: the record decides.
    void throw_if_broken(bool values) const {
        if (broken_) throw broken_rule<T>(*broken_, values);
    }

private:
    static bool same_bits(const ray<T>& a, const ray<T>& b) {
        return std::memcmp(&a.origin, &b.origin, sizeof a.origin) == 0 &&
               std::memcmp(&a.direction, &b.direction, sizeof a.direction) == 0;
    }
    static bool same_bits(const interval<T>& a, const interval<T>& b) {
        return std::memcmp(&a.min, &b.min, sizeof(T)) == 0 && std::memcmp(&a.max, &b.max, sizeof(T)) == 0;
    }

    bool listed(int i, const ray<T>& r) const {
        for (const auto& [object, object_ray] : rules_.object_rays)
            if (object == i && same_bits(object_ray, r)) return true;
        return false;
    }

    std::optional<fault_note<T>> rule_broken(long call, int i, const ray<T>& r, const interval<T>& range) const {
        fault_note<T> note;
        note.call = call;
        note.object = i;
        note.range = range;
        note.budget = rules_.budget;
        note.count = rules_.count;
        if (rules_.budget >= 0 && call >= rules_.budget) {
            note.fault = call_fault::over_budget;
        } else if (i < 0 || i >= rules_.count) {
            note.fault = call_fault::no_such_object;
        } else if (!rules_.object_rays.empty() && !listed(i, r)) {
            note.fault = call_fault::other_object_ray;
        } else if (rules_.object_rays.empty() && !same_bits(r, rules_.r)) {
            note.fault = call_fault::other_ray;
        } else if (rules_.check_calls) {
            if (std::size_t(call) < rules_.expected.size()) {
                const expected_call<T>& e = rules_.expected[std::size_t(call)];
                if (e.object == i && same_bits(e.range, range)) return std::nullopt;
                note.expected = e;
            }
            note.fault = call_fault::unexpected_call;
        } else {
            return std::nullopt;
        }
        return note;
    }

    call_rules<T> rules_;
    object_test<T> test_;
    long calls_ = 0;
    std::optional<fault_note<T>> broken_;
};

// The callable a test gives as its callback (chapter 03's object_intersector, chapter 08's
// leaf_intersector): objects 0 .. count-1, each tested by `test` (instructor code), with the test's
// rules. Under the grader the judge keeps it and answers the runner's calls through an object_server
// (served_by_judge.hpp); in the test's own process (a student's build) it answers through an object_server
// too, a new one whenever the ray changes (a new call of the exercise), and throws broken_rule at the
// call that breaks a rule, so the tests behave the same in both places.
template <class T>
struct served_objects {
    int count = 0;
    object_test<T> test;
    long budget = -1;
    bool check_calls = false;
    std::vector<expected_call<T>> expected;
    std::optional<ray<T>> only_ray;  // when set, the one ray every call must ask about (else: the call's)
    // Chapter 10: when not empty, the (model, ray) pairs calls may ask about (call_rules::object_rays).
    // One served_objects then serves one call of the exercise: the test makes a new one per call.
    std::vector<std::pair<int, ray<T>>> object_rays;
    std::shared_ptr<std::optional<object_server<T>>> here = std::make_shared<std::optional<object_server<T>>>();

    // The server of one call of the exercise, given ray r.
    object_server<T> server_for(const ray<T>& r) const {
        return object_server<T>(
            call_rules<T>{only_ray ? *only_ray : r, count, budget, check_calls, expected, object_rays}, test);
    }

    std::optional<hit_record<T>> operator()(int i, const ray<T>& r, const interval<T>& range) const {
        const ray<T>& wanted = only_ray ? *only_ray : r;
        // The calls of one exercise call ask about many rays when object_rays is set: one server for them all.
        if (!*here || (object_rays.empty() && std::memcmp(&(*here)->for_ray(), &wanted, sizeof wanted) != 0))
            here->emplace(server_for(r));
        auto answer = (*here)->answer(i, r, range);
        if (const auto broken = (*here)->broken()) {
            here->reset();  // the exception ends this call of the exercise: the next call starts afresh
            throw broken_rule<T>(*broken, true);
        }
        return answer;
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
// the student's own shadow_ray for every light (on both sides of the surface: shade() uses the normal as
// given, but one that turns it round should fail on its colour, with a message that says so, not on an
// unexpected question) and keeps each query with the answer the test's occlusion test gives it.
// It answers the runner's questions from that list; any other question, or one beyond the test's
// budget, makes the judge throw std::logic_error out of shade() once the call is over (a bool answer
// says nothing of which rule broke, and an exception thrown in the runner could be caught there).

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
