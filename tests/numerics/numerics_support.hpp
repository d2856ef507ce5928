// numerics_support.hpp — small helpers for the stiff-case tests.
//
// The tests run the study's own case families and measurement (tools/study),
// with fewer random queries, so a test asserts exactly what the study's
// table shows.
#pragma once

#include "measure.hpp"

#include "test_support.hpp"

#include <string>
#include <vector>

namespace rt::numerics_test {

using namespace rt::study;
namespace fm = rt::formulations;

// Enough queries per group to see the effects, few enough for a second.
inline case_options small_cases() {
    case_options o;
    o.per_group = 256;
    return o;
}

// One routine on one family, checked against the references.
template <class T, class Q, class Entry>
outcome run(const family<Q>& fam, const std::vector<reference_answer>& refs, const Entry& entry) {
    outcome o = evaluate<T>(fam, refs, entry.template fn<T>());
    o.formulation = entry.name;
    return o;
}

// Per group: reference hits, false hits and false misses of one routine.
struct group_count {
    std::size_t queries = 0, reference_hits = 0, false_hits = 0, false_misses = 0;
};

template <class T, class Q, class Fn>
std::vector<group_count> count_by_group(const family<Q>& fam, const std::vector<reference_answer>& refs, Fn fn) {
    std::vector<group_count> out(fam.group_names.size());
    for (std::size_t i = 0; i < fam.queries.size(); ++i) {
        const Q& q = fam.queries[i];
        bool hit = fn(q.r, q.shape, q.range).has_value();
        group_count& g = out[static_cast<std::size_t>(fam.group[i])];
        ++g.queries;
        g.reference_hits += refs[i].hit;
        g.false_hits += hit && !refs[i].hit;
        g.false_misses += !hit && refs[i].hit;
    }
    return out;
}

// "axis 1e+06" -> true when the group's name starts with the setup.
inline bool starts_with(const std::string& s, const std::string& prefix) { return s.rfind(prefix, 0) == 0; }

}  // namespace rt::numerics_test
