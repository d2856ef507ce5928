// The stiff sphere cases of the formulation study, as tests.
//
// Each test asserts one line of the study's table: where the textbook and
// the Ray Tracing Gems formulations lose rays (documented, expected
// failures, counted so they cannot hide) and where the compensated and
// mixed-precision formulations hold.
#include "numerics_support.hpp"

using namespace rt;
using namespace rt::numerics_test;

namespace {

// The far-sphere family and its references, built once per precision.
template <class T>
struct far_setup {
    family<sphere_query<T>> fam = far_sphere_family<T>(small_cases(), far_distances());
    std::vector<reference_answer> refs = references(fam);
};

template <class T>
const far_setup<T>& far() {
    static const far_setup<T> setup;
    return setup;
}

template <class T>
std::vector<family<sphere_query<T>>> all_sphere_families() {
    return sphere_families<T>(small_cases());
}

}  // namespace

TEST_CASE("plain float quadratic loses the far sphere beyond about 4096 radii (documented expected failure)") {
    const auto& s = far<float>();
    auto groups = count_by_group<float>(s.fam, s.refs, fm::sphere_formulation_named("plain").fn<float>());
    for (std::size_t g = 0; g < groups.size(); ++g) {
        const std::string& name = s.fam.group_names[g];
        if (!starts_with(name, "axis")) continue;
        const group_count& c = groups[g];
        std::size_t misses = c.queries - c.reference_hits;
        INFO("group " << name << ": " << c.false_hits << " false hits of " << misses << " misses, " << c.false_misses
                      << " false misses of " << c.reference_hits << " hits");
        if (name == "axis 100") {
            CHECK_MESSAGE(c.false_hits + c.false_misses <= c.queries / 20,
                          "at 100 radii c = f.f - r^2 still keeps most of its digits in float: only rays at the rim "
                          "may be misclassified");
        } else if (name != "axis 1000") {
            // Beyond 4096 radii f.f = D^2 > 2^24, whose ULP (2 or more) exceeds
            // r^2 = 1: c = f.f - r^2 keeps no correct digit, the sign of the
            // discriminant is rounding noise, and the sphere fills the view
            // (or vanishes) whatever the ray.
            double wrong_misses = misses ? double(c.false_hits) / double(misses) : 0;
            double wrong_hits = c.reference_hits ? double(c.false_misses) / double(c.reference_hits) : 0;
            CHECK_MESSAGE(std::max(wrong_misses, wrong_hits) > 0.8,
                          "the plain float quadratic was expected to lose the sphere beyond 4096 radii (c = f.f - r^2 "
                          "cancels completely); if it no longer does, the study's explanation needs updating");
        }
    }
}

TEST_CASE("plain double quadratic holds the far sphere up to 1e5 radii") {
    const auto& s = far<double>();
    auto groups = count_by_group<double>(s.fam, s.refs, fm::sphere_formulation_named("plain").fn<double>());
    for (std::size_t g = 0; g < groups.size(); ++g) {
        const std::string& name = s.fam.group_names[g];
        std::size_t bad = groups[g].false_hits + groups[g].false_misses;
        if (name.find("1e+06") != std::string::npos) {
            MESSAGE("plain double, " << name << ": " << bad << " rim rays misclassified of " << groups[g].queries);
            continue;
        }
        CHECK_MESSAGE(bad == 0, "plain double, " << name << ": double has 29 more bits than float, so c = f.f - r^2 "
                                                    "keeps enough digits up to 1e5 radii; misclassified "
                                                 << bad);
    }
}

TEST_CASE("Ray Tracing Gems float formulation misclassifies no ray up to 1e6 radii in the axis setup") {
    const auto& s = far<float>();
    for (std::string name : {"rtg_discriminant", "rtg_stable"}) {
        auto groups = count_by_group<float>(s.fam, s.refs, fm::sphere_formulation_named(name).fn<float>());
        for (std::size_t g = 0; g < groups.size(); ++g) {
            if (!starts_with(s.fam.group_names[g], "axis")) continue;
            CHECK_MESSAGE(groups[g].false_hits + groups[g].false_misses == 0,
                          name << " in " << s.fam.group_names[g]
                               << ": with the sphere at the origin and rays along -z, f - (f.d/a) d is exact in the "
                                  "perpendicular directions, so Hearn and Baker's discriminant must classify every "
                                  "ray; false hits "
                               << groups[g].false_hits << ", false misses " << groups[g].false_misses);
        }
    }
}

TEST_CASE("Ray Tracing Gems float formulation loses rays on a far sphere in a general direction (counted)") {
    const auto& s = far<float>();
    auto groups = count_by_group<float>(s.fam, s.refs, fm::sphere_formulation_named("rtg_stable").fn<float>());
    std::size_t near_losses = 0, far_losses = 0;
    for (std::size_t g = 0; g < groups.size(); ++g) {
        const std::string& name = s.fam.group_names[g];
        if (starts_with(name, "axis")) continue;
        std::size_t bad = groups[g].false_hits + groups[g].false_misses;
        MESSAGE("rtg_stable float, " << name << ": " << bad << " misclassified of " << groups[g].queries << " rays");
        if (name.size() > 4 && name.compare(name.size() - 4, 4, " 100") == 0) near_losses += bad;
        if (name.find("100000") != std::string::npos || name.find("1e+06") != std::string::npos) far_losses += bad;
    }
    CHECK_MESSAGE(near_losses == 0, "at 100 radii the perpendicular vector f - (f.d/a) d keeps enough digits in "
                                    "float; misclassified "
                                        << near_losses);
    CHECK_MESSAGE(far_losses > 0, "at 10^5 and 10^6 radii in a general direction f - (f.d/a) d cancels (|f| ~ 10^6, "
                                  "|l| ~ 1, float keeps 7 digits), so silhouette rays are expected to be misclassified; "
                                  "none were, so the study's claim needs checking");
}

TEST_CASE("compensated and mixed float formulations misclassify no ray in any far-sphere family") {
    const auto& s = far<float>();
    for (std::string name : {"compensated", "mixed"}) {
        auto groups = count_by_group<float>(s.fam, s.refs, fm::sphere_formulation_named(name).fn<float>());
        for (std::size_t g = 0; g < groups.size(); ++g)
            CHECK_MESSAGE(groups[g].false_hits + groups[g].false_misses == 0,
                          name << " float, " << s.fam.group_names[g] << ": false hits " << groups[g].false_hits
                               << ", false misses " << groups[g].false_misses
                               << " (f = o - C, f x d and the discriminant are carried without cancellation, so the "
                                  "sign of the discriminant must be right)");
    }
}

TEST_CASE_TEMPLATE("compensated and mixed formulations stay within a few ULPs on every sphere family", T, RT_SCALARS) {
    for (const auto& fam : all_sphere_families<T>()) {
        auto refs = references(fam);
        for (std::string name : {"compensated", "mixed"}) {
            outcome o = run<T>(fam, refs, fm::sphere_formulation_named(name));
            INFO(name << " " << std::string(rt::test::scalar_name<T>()) << " on family '" << fam.name << "'");
            CHECK_MESSAGE(o.misclassified() == 0, "false hits " << o.false_hits << ", false misses " << o.false_misses);
            CHECK_MESSAGE(o.wrong_roots == 0, "wrong roots " << o.wrong_roots);
            CHECK_MESSAGE(o.error.ulp_max <= 4, "the stable root pair from an accurate c and discriminant is within a "
                                                "few ULPs; largest error "
                                                    << o.error.ulp_max << " ULPs");
        }
    }
}

TEST_CASE("ground sphere: Ray Tracing Gems float is off by about 1e-2 while compensated and mixed hold") {
    case_options o = small_cases();
    auto fam = ground_sphere_family<float>(o);
    auto refs = references(fam);
    outcome rtg = run<float>(fam, refs, fm::sphere_formulation_named("rtg_stable"));
    CHECK_MESSAGE(rtg.error.rel_max > 1e-3,
                  "seen from 0.01 above a sphere of radius 1e6, f = o - C rounds away the height and c = f.f - r^2 "
                  "cancels, so the near root c/q was expected to be far off in float; largest relative error "
                      << rtg.error.rel_max);
    for (std::string name : {"compensated", "mixed"}) {
        outcome good = run<float>(fam, refs, fm::sphere_formulation_named(name));
        CHECK_MESSAGE(good.error.rel_max < 1e-6, name << ": exact f and an accurate c give the near root to float "
                                                         "precision; largest relative error "
                                                      << good.error.rel_max);
    }
}

#if RT_NUMERICS_HAS_CH07
#include "07-precision/robust_sphere.hpp"

namespace {
template <class T>
std::optional<T> chapter07_t(const ray<T>& r, const sphere<T>& s, const interval<T>& range) {
    auto h = rt::ch07::intersect_sphere_robust(s, r, range);
    return h ? std::optional<T>(h->t) : std::nullopt;
}
}  // namespace

TEST_CASE_TEMPLATE("chapter 07's solution meets its header on every sphere family", T, RT_SCALARS) {
    for (const auto& fam : all_sphere_families<T>()) {
        auto refs = references(fam);
        outcome o = evaluate<T>(fam, refs, &chapter07_t<T>);
        INFO("chapter 07 " << std::string(rt::test::scalar_name<T>()) << " on family '" << fam.name << "'");
        CHECK_MESSAGE(o.misclassified() == 0, "false hits " << o.false_hits << ", false misses " << o.false_misses);
        CHECK_MESSAGE(o.wrong_roots == 0, "wrong roots " << o.wrong_roots);
        CHECK_MESSAGE(o.error.ulp_max <= 4, "the header promises 4 ULPs on exact-input hits; largest error "
                                                << o.error.ulp_max << " ULPs");
        CHECK_MESSAGE(o.nan_hits + o.out_of_range == 0, "NaN or out-of-range answers");
    }
}
#endif

TEST_CASE_TEMPLATE("compensated sphere: finite inputs whose o - C overflows (dyadic cases, exact roots)", T, RT_SCALARS) {
    // M = T's largest number. Each origin and centre is finite, but o - C is not. The near roots are
    // M, M and M/4: numbers of T (for M the largest, so a t' rounded above M/4 must come back as M).
    const T M = std::numeric_limits<T>::max(), h = M / 2;
    const auto& compensated = fm::sphere_formulation_named("compensated").fn<T>();
    const interval<T> ahead{T(0), infinity<T>};
    struct row {
        ray<T> r;
        sphere<T> s;
        T t;
    };
    for (const row& c : {row{ray<T>{{0, 0, -M}, {0, 0, 1}}, sphere<T>{{0, 0, M}, M}, M},
                         row{ray<T>{{-M, 0, 0}, {1, 0, 0}}, sphere<T>{{h, 0, 0}, h}, M},
                         row{ray<T>{{-M, 0, 0}, {4, 0, 0}}, sphere<T>{{h, 0, 0}, h}, M / 4}}) {
        const std::optional<T> t = compensated(c.r, c.s, ahead);
        REQUIRE_MESSAGE(t.has_value(), "a finite input whose o - C overflows was missed");
        CHECK(ulp_distance(*t, c.t) <= 4);
    }
}
