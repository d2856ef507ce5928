// measure.cpp — references for whole families, and the plane residual.
#include "measure.hpp"

namespace rt::study {

namespace {
template <class Q, class R>
std::vector<reference_answer> all_references(const family<Q>& f, R reference) {
    std::vector<reference_answer> out;
    out.reserve(f.queries.size());
    for (const Q& q : f.queries) out.push_back(reference(q.r, q.shape, q.range));
    return out;
}
}  // namespace

template <class T>
std::vector<reference_answer> references(const family<sphere_query<T>>& f) {
    return all_references(f, &sphere_reference<T>);
}
template <class T>
std::vector<reference_answer> references(const family<plane_query<T>>& f) {
    return all_references(f, &plane_reference<T>);
}
template <class T>
std::vector<reference_answer> references(const family<triangle_query<T>>& f) {
    return all_references(f, &triangle_reference<T>);
}

template std::vector<reference_answer> references<float>(const family<sphere_query<float>>&);
template std::vector<reference_answer> references<double>(const family<sphere_query<double>>&);
template std::vector<reference_answer> references<float>(const family<plane_query<float>>&);
template std::vector<reference_answer> references<double>(const family<plane_query<double>>&);
template std::vector<reference_answer> references<float>(const family<triangle_query<float>>&);
template std::vector<reference_answer> references<double>(const family<triangle_query<double>>&);

namespace detail {
double off_plane(const plane<float>& p, const std::optional<formulations::plane_hit<float>>& h) {
    return h ? off_plane_ulps(p, h->point) : -1;
}
double off_plane(const plane<double>& p, const std::optional<formulations::plane_hit<double>>& h) {
    return h ? off_plane_ulps(p, h->point) : -1;
}
}  // namespace detail

}  // namespace rt::study
