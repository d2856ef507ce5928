// registry.cpp — the tables, and the explicit float and double instantiations.
#include "registry.hpp"

#include <stdexcept>

namespace rt::formulations {

// Every formulation is compiled for both precisions here (house rule: all
// numerical code is instantiated for float and double); the compensated one,
// chapter 07's solution, in chapter07_reference.cpp.
#define RT_INSTANTIATE(T)                                                                                 \
    template std::optional<T> sphere_plain<T>(const ray<T>&, const sphere<T>&, const interval<T>&);          \
    template std::optional<T> sphere_half_b<T>(const ray<T>&, const sphere<T>&, const interval<T>&);         \
    template std::optional<T> sphere_geometric<T>(const ray<T>&, const sphere<T>&, const interval<T>&);      \
    template std::optional<T> sphere_rtg_discriminant<T>(const ray<T>&, const sphere<T>&, const interval<T>&); \
    template std::optional<T> sphere_rtg_stable<T>(const ray<T>&, const sphere<T>&, const interval<T>&);     \
    template std::optional<T> sphere_mixed<T>(const ray<T>&, const sphere<T>&, const interval<T>&);          \
    template std::optional<plane_hit<T>> plane_direct<T>(const ray<T>&, const plane<T>&, const interval<T>&); \
    template std::optional<plane_hit<T>> plane_snapped<T>(const ray<T>&, const plane<T>&, const interval<T>&); \
    template std::optional<T> triangle_half_planes<T>(const ray<T>&, const triangle<T>&, const interval<T>&); \
    template std::optional<T> triangle_moller_trumbore<T>(const ray<T>&, const triangle<T>&, const interval<T>&); \
    template std::optional<T> triangle_watertight<T>(const ray<T>&, const triangle<T>&, const interval<T>&);
RT_INSTANTIATE(float)
RT_INSTANTIATE(double)
#undef RT_INSTANTIATE

namespace {
#define RT_ENTRY(Q, function, name, idea)                                                                     \
    {                                                                                                   \
        name, idea, &function<float>, &function<double>, &run_batch<Q<float>, &function<float>>,  \
            &run_batch<Q<double>, &function<double>>                                                    \
    }

template <class Entry>
const Entry& find(const std::vector<Entry>& table, const std::string& name) {
    for (const Entry& e : table)
        if (e.name == name) return e;
    throw std::out_of_range("no formulation named '" + name + "'");
}
}  // namespace

const std::vector<sphere_formulation>& sphere_formulations() {
    static const std::vector<sphere_formulation> table = {
        RT_ENTRY(sphere_query, sphere_plain, "plain", "textbook a, b, c and b^2 - 4ac"),
        RT_ENTRY(sphere_query, sphere_half_b, "half_b", "h = f.d, disc = h^2 - ac"),
        RT_ENTRY(sphere_query, sphere_geometric, "geometric", "unit direction, distance of the centre from the ray"),
        RT_ENTRY(sphere_query, sphere_rtg_discriminant, "rtg_discriminant", "Hearn-Baker discriminant a(r^2 - |f - (h/a)d|^2)"),
        RT_ENTRY(sphere_query, sphere_rtg_stable, "rtg_stable", "Hearn-Baker discriminant + stable root pair (RTG ch. 7)"),
        RT_ENTRY(sphere_query, sphere_compensated, "compensated", "chapter 07's solution: exact f, pairs for f x d, triple-precision c"),
        RT_ENTRY(sphere_query, sphere_mixed, "mixed", "float data in double, double data in double-double"),
    };
    return table;
}

const std::vector<plane_formulation>& plane_formulations() {
    static const std::vector<plane_formulation> table = {
        RT_ENTRY(plane_query, plane_direct, "direct", "t = (q - o).n / d.n, point o + t d"),
        RT_ENTRY(plane_query, plane_snapped, "snapped", "same t, point projected back onto the plane"),
    };
    return table;
}

const std::vector<triangle_formulation>& triangle_formulations() {
    static const std::vector<triangle_formulation> table = {
        RT_ENTRY(triangle_query, triangle_half_planes, "half_planes", "plane hit, then three edge half-planes"),
        RT_ENTRY(triangle_query, triangle_moller_trumbore, "moller_trumbore", "Cramer's rule for t, u, v"),
        RT_ENTRY(triangle_query, triangle_watertight, "watertight", "Woop-Benthin-Wald shear, shared edge functions"),
    };
    return table;
}
#undef RT_ENTRY

const sphere_formulation& sphere_formulation_named(const std::string& name) { return find(sphere_formulations(), name); }
const triangle_formulation& triangle_formulation_named(const std::string& name) {
    return find(triangle_formulations(), name);
}
const plane_formulation& plane_formulation_named(const std::string& name) { return find(plane_formulations(), name); }

}  // namespace rt::formulations
