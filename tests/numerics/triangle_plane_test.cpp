// The stiff triangle and plane cases of the formulation study, as tests.
#include "numerics_support.hpp"

using namespace rt;
using namespace rt::numerics_test;

namespace {
template <class T>
struct edge_setup {
    family<triangle_query<T>> fam = edge_triangle_family<T>(small_cases());
    std::vector<reference_answer> refs = references(fam);
};

template <class T>
const edge_setup<T>& edges() {
    static const edge_setup<T> setup;
    return setup;
}
}  // namespace

TEST_CASE_TEMPLATE("watertight triangle test leaks no ray through shared edges or corners", T, RT_SCALARS) {
    const auto& s = edges<T>();
    outcome o = run<T>(s.fam, s.refs, fm::triangle_formulation_named("watertight"));
    REQUIRE_MESSAGE(o.rays > 0, "the edge family must pair rays with the triangles around each edge");
    CHECK_MESSAGE(o.leaks == 0, "neighbouring triangles evaluate the edge function of their shared edge from the same "
                                "sheared vertices, so one of them must claim a ray through the edge; "
                                    << o.leaks << " of " << o.rays << " rays passed through the closed mesh");
}

TEST_CASE("Moeller-Trumbore and half-plane leaks through shared edges are counted (documented expected failure)") {
    std::size_t leaks = 0;
    for (std::string name : {"moller_trumbore", "half_planes"}) {
        outcome f = run<float>(edges<float>().fam, edges<float>().refs, fm::triangle_formulation_named(name));
        outcome d = run<double>(edges<double>().fam, edges<double>().refs, fm::triangle_formulation_named(name));
        MESSAGE(name << ": float leaks " << f.leaks << " of " << f.rays << " rays, double leaks " << d.leaks << " of "
                     << d.rays);
        leaks += f.leaks + d.leaks;
    }
    CHECK_MESSAGE(leaks > 0, "each triangle rounds its own barycentrics, so rays through shared edges were expected to "
                             "slip between neighbours; none did, so the study's claim needs checking");
}

TEST_CASE_TEMPLATE("snapped plane hit points lie within a few ULPs of the plane", T, RT_SCALARS) {
    for (const auto& fam : plane_families<T>(small_cases())) {
        auto refs = references(fam);
        outcome o = run<T>(fam, refs, fm::plane_formulation_named("snapped"));
        // Rounding each coordinate of a stored point moves it up to sqrt(3)/2
        // ULP off any plane; the rounded dot product of the projection adds
        // up to two more (the default study measures at most 3).
        CHECK_MESSAGE(o.off_plane_max <= 4.0, "family '" << fam.name << "': projecting o + t d back onto the plane "
                                                                        "leaves only the rounding of the point and of "
                                                                        "the projection; largest distance "
                                                         << o.off_plane_max << " ULPs");
    }
}

TEST_CASE_TEMPLATE("plane formulations classify parallel and nearly parallel rays correctly", T, RT_SCALARS) {
    for (const auto& fam : plane_families<T>(small_cases())) {
        auto refs = references(fam);
        for (const auto& entry : fm::plane_formulations()) {
            outcome o = run<T>(fam, refs, entry);
            CHECK_MESSAGE(o.misclassified() == 0, entry.name << " on '" << fam.name << "': a ray parallel to the plane "
                                                                "divides by d.n = 0 and the infinite or NaN t must "
                                                                "fail the range test; false hits "
                                                             << o.false_hits << ", false misses " << o.false_misses);
        }
    }
}

TEST_CASE_TEMPLATE("every triangle formulation misses degenerate triangles and rays in the plane", T, RT_SCALARS) {
    for (const auto& fam : triangle_families<T>(small_cases())) {
        if (fam.name != "tri stiff") continue;
        auto refs = references(fam);
        for (const auto& entry : fm::triangle_formulations()) {
            std::size_t wrong = 0, checked = 0;
            for (std::size_t i = 0; i < fam.queries.size(); ++i) {
                const std::string& group = fam.group_names[static_cast<std::size_t>(fam.group[i])];
                if (group != "degenerate" && group != "ray in the plane" && group != "invalid input") continue;
                const auto& q = fam.queries[i];
                ++checked;
                wrong += entry.template fn<T>()(q.r, q.shape, q.range).has_value() != refs[i].hit;
            }
            REQUIRE(checked > 0);
            CHECK_MESSAGE(wrong == 0, entry.name << " " << std::string(rt::test::scalar_name<T>())
                                                 << ": a triangle with collinear corners has no plane, a ray lying in "
                                                    "the triangle's plane meets it in a segment, not a point, and NaN "
                                                    "input describes no ray: all three are misses (a hit exactly at "
                                                    "tmax or at t = 0 is outside the open range); wrong answers "
                                                 << wrong << " of " << checked);
        }
    }
}
