// sah_build.cpp — reference solution for chapter 08: the binned SAH build.
#include "08-acceleration/bvh.hpp"

#include <algorithm>
#include <limits>
#include <stdexcept>

namespace rt::ch08 {

namespace {

template <class T>
struct bin {
    aabb<T> box;
    int count = 0;
};

// The best split found for one node: which axis, and which plane (the split
// puts bins 0 .. plane on the left), with its cost.
template <class T>
struct split_choice {
    int axis = -1;
    int plane = -1;
    T cost = infinity<T>;
};

template <class T>
class sah_builder {
public:
    sah_builder(const std::vector<aabb<T>>& boxes, const build_options& options)
        : boxes_(boxes), options_(options), bins_(size_t(options.bins)), right_area_(size_t(options.bins)),
          right_count_(size_t(options.bins)) {
        // Each box's centre, computed once: the builder looks at it on every level.
        centres_.reserve(boxes.size());
        for (const aabb<T>& b : boxes) centres_.push_back(b.centroid());
    }

    bvh<T> build() {
        const int n = int(boxes_.size());
        if (n == 0) return std::move(tree_);
        tree_.order.resize(size_t(n));
        for (int i = 0; i < n; ++i) tree_.order[size_t(i)] = i;
        tree_.nodes.reserve(size_t(2 * n - 1));
        tree_.nodes.push_back(make_node(0, n));
        // An explicit list of nodes still to split, so a degenerate scene (a
        // deep, list-like tree) cannot overflow the call stack.
        std::vector<int> todo{0};
        while (!todo.empty()) {
            const int index = todo.back();
            todo.pop_back();
            if (split(index)) {
                todo.push_back(tree_.nodes[size_t(index)].first);
                todo.push_back(tree_.nodes[size_t(index)].first + 1);
            }
        }
        return std::move(tree_);
    }

private:
    bvh_node<T> make_node(int first, int count) const {
        bvh_node<T> node;
        node.first = first;
        node.count = count;
        for (int k = first; k < first + count; ++k) node.box.grow(box_of(k));
        return node;
    }

    const aabb<T>& box_of(int position) const { return boxes_[size_t(tree_.order[size_t(position)])]; }

    // The bin of a centre coordinate. (centre - lo) / extent is in [0, 1]
    // for every extent > 0, even a tiny one (bins / extent could overflow).
    int bin_of(T centre, T lo, T extent) const {
        const int b = int(T(options_.bins) * ((centre - lo) / extent));
        return std::min(options_.bins - 1, std::max(0, b));
    }

    const vec3<T>& centre_of(int position) const { return centres_[size_t(tree_.order[size_t(position)])]; }

    // The cheapest binned split of the node's objects, over the three axes.
    split_choice<T> best_split(const bvh_node<T>& node, const aabb<T>& centres) {
        split_choice<T> best;
        const int bins = options_.bins;
        std::vector<bin<T>>& b = bins_;
        std::vector<T>& right_area = right_area_;
        std::vector<int>& right_count = right_count_;
        for (int axis = 0; axis < 3; ++axis) {
            const T lo = centres.lo[axis], extent = centres.hi[axis] - centres.lo[axis];
            if (!(extent > T(0))) continue;  // every centre in one plane: nothing to cut along this axis
            std::fill(b.begin(), b.end(), bin<T>{});
            for (int k = node.first; k < node.first + node.count; ++k) {
                bin<T>& into = b[size_t(bin_of(centre_of(k)[axis], lo, extent))];
                into.box.grow(box_of(k));
                ++into.count;
            }
            // Sweep from the right to know, for each plane, what lies right of it...
            aabb<T> acc;
            int count = 0;
            for (int i = bins - 1; i > 0; --i) {
                acc.grow(b[size_t(i)].box);
                count += b[size_t(i)].count;
                right_area[size_t(i)] = acc.half_area();
                right_count[size_t(i)] = count;
            }
            // ...then from the left: plane p separates bins 0..p from p+1..bins-1.
            acc = aabb<T>{};
            count = 0;
            for (int p = 0; p < bins - 1; ++p) {
                acc.grow(b[size_t(p)].box);
                count += b[size_t(p)].count;
                const int rc = right_count[size_t(p + 1)];
                if (count == 0 || rc == 0) continue;
                const T cost = sah_traversal_cost<T> * node.box.half_area() +
                               sah_intersection_cost<T> * (acc.half_area() * T(count) + right_area[size_t(p + 1)] * T(rc));
                if (cost < best.cost) best = {axis, p, cost};
            }
        }
        return best;
    }

    // Splits node `index` in two, or leaves it a leaf; true when split.
    bool split(int index) {
        const bvh_node<T> node = tree_.nodes[size_t(index)];
        if (node.count <= 1) return false;
        aabb<T> centres;
        for (int k = node.first; k < node.first + node.count; ++k) centres.grow(centre_of(k));

        const split_choice<T> choice = best_split(node, centres);
        const T leaf_cost = sah_intersection_cost<T> * T(node.count) * node.box.half_area();
        const bool must_split = node.count > options_.max_leaf_size;
        if (!must_split && !(choice.cost < leaf_cost)) return false;

        auto begin = tree_.order.begin() + node.first, end = begin + node.count;
        int left_count = node.count / 2;  // no candidate: every centre is the same point, cut in halves
        if (choice.axis >= 0) {
            const int axis = choice.axis;
            const T lo = centres.lo[axis], extent = centres.hi[axis] - centres.lo[axis];
            const auto middle = std::partition(begin, end, [&](int object) {
                return bin_of(centres_[size_t(object)][axis], lo, extent) <= choice.plane;
            });
            left_count = int(middle - begin);
        }
        const int left = int(tree_.nodes.size());
        tree_.nodes.push_back(make_node(node.first, left_count));
        tree_.nodes.push_back(make_node(node.first + left_count, node.count - left_count));
        tree_.nodes[size_t(index)].first = left;
        tree_.nodes[size_t(index)].count = 0;
        return true;
    }

    const std::vector<aabb<T>>& boxes_;
    build_options options_;
    std::vector<vec3<T>> centres_;
    // Scratch space of best_split, allocated once for the whole build.
    std::vector<bin<T>> bins_;
    std::vector<T> right_area_;
    std::vector<int> right_count_;
    bvh<T> tree_;
};

}  // namespace

template <class T>
bvh<T> build_sah(const std::vector<aabb<T>>& boxes, const build_options& options) {
    if (options.max_leaf_size < 1) throw std::invalid_argument("build_sah: max_leaf_size must be at least 1");
    if (options.bins < 2) throw std::invalid_argument("build_sah: bins must be at least 2");
    return sah_builder<T>(boxes, options).build();
}

template bvh<float> build_sah(const std::vector<aabb<float>>&, const build_options&);
template bvh<double> build_sah(const std::vector<aabb<double>>&, const build_options&);

}  // namespace rt::ch08
