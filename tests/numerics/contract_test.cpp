// Every formulation keeps the contract on every case, however stiff:
// never a NaN as a hit, never a t outside (tmin, tmax), and a miss for
// input that describes no ray or no shape.
#include "numerics_support.hpp"

using namespace rt;
using namespace rt::numerics_test;

namespace {
template <class T, class Q, class Table>
void check_contract(const std::vector<family<Q>>& families, const Table& table) {
    for (const auto& fam : families) {
        auto refs = references(fam);
        for (const auto& entry : table) {
            outcome o = run<T>(fam, refs, entry);
            INFO(entry.name << " " << rt::test::scalar_name<T>() << " on family '" << fam.name << "'");
            CHECK_MESSAGE(o.nan_hits == 0, "a NaN t was returned as a hit " << o.nan_hits
                                                                             << " times: write the range test so that "
                                                                                "NaN fails it");
            CHECK_MESSAGE(o.out_of_range == 0, "a t outside the open range (tmin, tmax) was accepted "
                                                   << o.out_of_range << " times");
        }
    }
}

template <class T, class Q, class Table>
void check_invalid_input_misses(const family<Q>& fam, const Table& table, const std::string& group) {
    for (const auto& entry : table) {
        for (std::size_t i = 0; i < fam.queries.size(); ++i) {
            if (fam.group_names[static_cast<std::size_t>(fam.group[i])] != group) continue;
            const Q& q = fam.queries[i];
            bool hit = entry.template fn<T>()(q.r, q.shape, q.range).has_value();
            CHECK_MESSAGE(!hit, entry.name << " " << rt::test::scalar_name<T>() << ", case '" << group
                                           << "': NaN or infinite input describes no ray, so the answer is a miss");
        }
    }
}
}  // namespace

TEST_CASE_TEMPLATE("no sphere formulation returns NaN or a t outside the range", T, RT_SCALARS) {
    check_contract<T>(sphere_families<T>(small_cases()), fm::sphere_formulations());
}

TEST_CASE_TEMPLATE("no plane or triangle formulation returns NaN or a t outside the range", T, RT_SCALARS) {
    check_contract<T>(plane_families<T>(small_cases()), fm::plane_formulations());
    check_contract<T>(triangle_families<T>(small_cases()), fm::triangle_formulations());
}

TEST_CASE_TEMPLATE("every sphere formulation misses on NaN and infinite input", T, RT_SCALARS) {
    auto fam = special_sphere_family<T>();
    for (const char* group : {"NaN origin", "NaN direction", "NaN centre", "NaN radius", "NaN tmax", "infinite origin",
                              "infinite direction", "infinite radius", "zero direction",
                              "zero direction inside, range from -1"})
        check_invalid_input_misses<T>(fam, fm::sphere_formulations(), group);
}

TEST_CASE_TEMPLATE("every sphere formulation gets the range edges right", T, RT_SCALARS) {
    auto fam = special_sphere_family<T>();
    auto refs = references(fam);
    for (const auto& entry : fm::sphere_formulations()) {
        for (std::size_t i = 0; i < fam.queries.size(); ++i) {
            const std::string& name = fam.group_names[static_cast<std::size_t>(fam.group[i])];
            bool edge_case = name == "hit exactly at tmax" || name == "roots exactly at tmin and tmax" ||
                             name.rfind("origin on surface", 0) == 0 || name == "exact tangent" ||
                             name == "origin at centre" || name == "primary ray, image plane at t = 1";
            if (!edge_case) continue;
            const auto& q = fam.queries[i];
            auto t = entry.template fn<T>()(q.r, q.shape, q.range);
            CHECK_MESSAGE(t.has_value() == refs[i].hit,
                          entry.name << " " << rt::test::scalar_name<T>() << ", case '" << name
                                     << "': the range is open, tmin < t < tmax, so a root exactly at tmin or tmax "
                                        "(or t = 0 for an origin on the surface, even as -0) does not count; expected "
                                     << (refs[i].hit ? "a hit" : "a miss"));
            if (t && refs[i].hit)
                CHECK_MESSAGE(static_cast<long double>(*t) == refs[i].t,
                              entry.name << ", case '" << name << "': these roots are exact small integers; got "
                                         << *t << ", expected " << static_cast<double>(refs[i].t));
        }
    }
}
