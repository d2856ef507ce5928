// spawn_study.cpp — chapter 09's measurements (README, "Measured"): a
// program, not a test. It prints three tables, float and double in one run:
//
//  1. Where a secondary ray starts: on the stiff surface points of the tests
//     (tests/public/ch09_cases.hpp), how often each offset rule starts a ray
//     on the wrong side of the exact surface (a self-intersection: a
//     reflected ray inside, a refracted one outside), and how often it
//     starts beyond a thin shell (a second surface 1e-3 of the object's
//     size away: a pane, a coating, a bubble's wall). The rules:
//       none         the computed point itself
//       fixed 1e-4   1e-4 along the normal, on the ray's side
//       128 ulp      chapter 06's shadow_ray_origin: 128 epsilon max(1, |x|, |y|, |z|)
//       error bound  your offset_ray_origin with the point's bound (surface_error.hpp)
//  2. Schlick against exact Fresnel: the largest difference, where it
//     happens, and the cost of each in ns per call (your two functions).
//  3. k = 1 - eta^2 (1 - cos^2), the transmitted cos^2, near the critical
//     angle, where it cancels: the largest relative error of four ways to
//     compute it, against __float128, by how close k is to 0.
//
//   ch09-spawn-study [--points N]     N surface points per family (default 2000)
#include "06-shading/shading.hpp"
#include "07-precision/error_free.hpp"
#include "09-reflection/optics.hpp"
#include "09-reflection/spawn.hpp"

#include "ch09_cases.hpp"

#include "common/stub.hpp"
#include "common/timing.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <string>
#include <vector>

namespace {

using namespace rt;
using quad = rt::test::quad;

template <class T>
const char* name_of() {
    return sizeof(T) == 4 ? "float" : "double";
}

// ---- 1. offset rules -------------------------------------------------------------------------

enum class rule { none, fixed, ulps, bound };
const rule rules[] = {rule::none, rule::fixed, rule::ulps, rule::bound};

const char* rule_name(rule r) {
    switch (r) {
        case rule::none: return "none";
        case rule::fixed: return "fixed 1e-4";
        case rule::ulps: return "128 ulp";
        case rule::bound: return "error bound";
    }
    return "?";
}

template <class T>
vec3<T> origin_by(rule r, const ch09::surface_point<T>& p, const vec3<T>& n, const vec3<T>& w) {
    switch (r) {
        case rule::none: return p.point;
        case rule::fixed: return p.point + (dot(w, n) < T(0) ? T(-1e-4) : T(1e-4)) * n;
        case rule::ulps: return ch06::shadow_ray_origin(p.point, n, w);
        case rule::bound: return ch09::offset_ray_origin(p, n, w);
    }
    return p.point;
}

template <class T>
void offset_table(int points) {
    const std::vector<rt::test::spawn_case<T>> cases = rt::test::stiff_spawn_cases<T>(20260, points);
    std::vector<std::string> families;
    for (const auto& c : cases)
        if (std::find(families.begin(), families.end(), c.family) == families.end()) families.push_back(c.family);
    for (const std::string& family : families) {
        long total = 0;
        std::map<rule, long> wrong_side, skipped;
        for (const auto& c : cases) {
            if (c.family != family) continue;
            const vec3<T> out = c.outward;
            const vec3<T> in_reflected = c.incoming - T(2) * dot(c.incoming, out) * out;
            struct leaving {
                vec3<T> facing, w;
                int side;
            };
            const leaving rays[] = {{out, in_reflected, +1}, {out, c.incoming, -1},
                                    {-out, -in_reflected, -1}, {-out, -c.incoming, +1}};
            const quad shell = quad(c.size) * quad(1e-3);
            for (const leaving& l : rays) {
                ++total;
                for (rule r : rules) {
                    const vec3<T> o = origin_by(r, c.surface, l.facing, l.w);
                    if (c.side(o) != l.side) ++wrong_side[r];
                    const quad along = rt::test::quad_dot(o - c.surface.point, out);
                    if (!(along < shell && along > -shell)) ++skipped[r];
                }
            }
        }
        std::printf("%-6s  %-36s %6ld", name_of<T>(), family.c_str(), total);
        for (rule r : rules) std::printf("  %7.3f%% %7.3f%%", 100.0 * double(wrong_side[r]) / double(total),
                                         100.0 * double(skipped[r]) / double(total));
        std::printf("\n");
    }
}

// ---- 2. Schlick against Fresnel --------------------------------------------------------------

// ns per call over `inputs`, median of 9 runs of many calls each.
template <class T, class F>
double ns_per_call(const std::vector<T>& inputs, T eta, F&& f) {
    volatile T sink = 0;
    std::vector<double> samples;
    for (int run = 0; run < 9; ++run) {
        stopwatch sw;
        T sum = 0;
        for (int rep = 0; rep < 50; ++rep)
            for (T c : inputs) sum += f(c, eta);
        samples.push_back(sw.nanoseconds() / (50.0 * double(inputs.size())));
        sink = sink + sum;
    }
    return summarize(samples).median;
}

template <class T>
void schlick_table() {
    std::vector<T> cosines;
    for (int i = 0; i <= 4096; ++i) cosines.push_back(T(i) / T(4096));
    for (double index : {1.33, 1.5, 2.42})
        for (bool entering : {true, false}) {
            const T eta = entering ? T(1 / index) : T(index);
            double worst = 0, worst_degrees = 0, worst_exact = 0;
            for (int i = 0; i <= 100000; ++i) {
                const T c = T(double(i) / 100000);
                const double exact = double(ch09::fresnel_dielectric(c, eta));
                const double err = std::fabs(double(ch09::schlick(c, eta)) - exact);
                if (err > worst) {
                    worst = err;
                    worst_degrees = std::acos(double(c)) * 180 / 3.14159265358979323846;
                    worst_exact = exact;
                }
            }
            const double r0 = ((1 - double(eta)) / (1 + double(eta))) * ((1 - double(eta)) / (1 + double(eta)));
            const double ns_exact = ns_per_call(cosines, eta, [](T c, T e) { return ch09::fresnel_dielectric(c, e); });
            const double ns_schlick = ns_per_call(cosines, eta, [](T c, T e) { return ch09::schlick(c, e); });
            std::printf("%-6s  %5.2f %-8s  R0 %.4f  largest |Schlick - exact| %.4f at %5.1f deg (exact R %.4f)"
                        "   exact %5.2f ns, Schlick %5.2f ns\n",
                        name_of<T>(), index, entering ? "entering" : "leaving", r0, worst, worst_degrees, worst_exact,
                        ns_exact, ns_schlick);
        }
}

// ---- 3. the transmitted cos^2 near the critical angle ------------------------------------------

template <class T>
T k_naive(T c, T eta) {
    return T(1) - eta * eta * (T(1) - c * c);
}
template <class T>
T k_factored(T c, T eta) {
    return T(1) - eta * eta * ((T(1) - c) * (T(1) + c));
}
template <class T>
T k_fma(T c, T eta) {
    const T e2 = eta * eta;
    return std::fma(e2, c * c, T(1) - e2);
}
// 1 - Q (1 - P) with Q = eta^2 and P = c^2 carried exactly as pairs
// (two_prod, chapter 07's error-free vocabulary): k = (1 - q) + q p + the
// small terms, with one rounding on the main part.
template <class T>
T k_compensated(T c, T eta) {
    const double_word<T> P = two_prod(c, c), Q = two_prod(eta, eta);
    const double_word<T> s = two_sum(T(1), -Q.hi);  // 1 - q, and what it rounded away
    const T main = std::fma(Q.hi, P.hi, s.hi);
    const T small = std::fma(Q.hi, P.lo, std::fma(Q.lo, P.hi - T(1), s.lo));
    return main + small;
}

template <class T>
quad k_exact(T c, T eta) {
    const quad e2 = quad(eta) * quad(eta), c2 = quad(c) * quad(c);
    return 1 - e2 * (1 - c2);
}

template <class T>
void cancellation_table() {
    struct form {
        const char* name;
        T (*f)(T, T);
    };
    const form forms[] = {{"1 - eta^2 (1 - c^2)", k_naive<T>},
                          {"1 - eta^2 (1 - c)(1 + c)", k_factored<T>},
                          {"fma(eta^2, c^2, 1 - eta^2)", k_fma<T>},
                          {"compensated (two_prod)", k_compensated<T>}};
    const double bands[] = {1e-1, 1e-3, 1e-5, 1e-7, 1e-9};
    for (double index : {1.5, 1.33}) {
        const T eta = T(index);
        // Cosines from the critical angle outwards: k = 1 - eta^2 sin^2 grows from 0.
        const double c_crit = std::sqrt(1 - 1 / (index * index));
        for (size_t b = 0; b + 1 < std::size(bands); ++b) {
            std::printf("%-6s  eta %.2f  k in [%.0e, %.0e)", name_of<T>(), index, bands[b + 1], bands[b]);
            for (const form& fm : forms) {
                double worst = 0;
                int seen = 0;
                for (int i = 0; i < 20000; ++i) {
                    // dk/dc = 2 eta^2 c: spread c across the band.
                    const double k_target = bands[b + 1] * std::pow(bands[b] / bands[b + 1], (i + 0.5) / 20000);
                    const T c = T(c_crit + k_target / (2 * index * index * c_crit));
                    const quad exact = k_exact(c, eta);
                    if (!(exact >= quad(bands[b + 1]) && exact < quad(bands[b]))) continue;
                    ++seen;
                    const quad rel = (quad(fm.f(c, eta)) - exact) / exact;
                    worst = std::max(worst, std::fabs(double(rel)));
                }
                if (seen == 0) std::printf("  %26s %9s", fm.name, "-");
                else std::printf("  %26s %9.2e", fm.name, worst / double(std::numeric_limits<T>::epsilon()));
            }
            std::printf("\n");
        }
    }
}

}  // namespace

int main(int argc, char** argv) {
    int points = 2000;
    for (int i = 1; i < argc; ++i) {
        if (std::strcmp(argv[i], "--points") == 0 && i + 1 < argc) {
            points = std::atoi(argv[++i]);
            continue;
        }
        std::fprintf(stderr, "usage: ch09-spawn-study [--points N]\n");
        return 1;
    }
    if (points < 1) {
        std::fprintf(stderr, "ch09-spawn-study: --points expects a whole number >= 1\n");
        return 1;
    }
    try {
        std::printf("1. Offset rules on stiff surface points: %% of spawned rays on the wrong side of the exact surface "
                    "(self-intersection) / %% past a shell 1e-3 of the object's size away (skipped), 4 rays per point\n");
        std::printf("%-6s  %-36s %6s", "type", "family", "rays");
        for (rule r : rules) std::printf("  %-17s", rule_name(r));
        std::printf("\n");
        offset_table<float>(points);
        offset_table<double>(points);
        std::printf("\n2. Schlick against exact Fresnel (cosine grid of 100,001 points; ns: median of 9 runs over "
                    "4,097 cosines, in cache)\n");
        schlick_table<float>();
        schlick_table<double>();
        std::printf("\n3. k = 1 - eta^2 (1 - cos^2) near the critical angle: largest relative error, in epsilons of the "
                    "type, against __float128 from the same inputs\n");
        cancellation_table<float>();
        cancellation_table<double>();
    } catch (const not_implemented& e) {
        std::fprintf(stderr, "ch09-spawn-study: %s\n", e.what());
        return exit_not_implemented;
    }
    return 0;
}
