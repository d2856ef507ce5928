// bvh_build.cpp — binned SAH build of the renderer's tree (see bvh_build.hpp).
//
// The surface area heuristic: a ray that hits a box hits a child box inside
// it with probability (child area / box area), so splitting n objects into
// (nL, nR) costs about   1 + (area_L * nL + area_R * nR) / area
// object tests per ray, against n for a leaf. Candidate splits are the
// boundaries between 16 equal bins of the objects' centres along the
// widest axis; one pass counts each bin's objects and grows its box, a
// sweep from each side then prices all 15 splits.
#include "bvh_build.hpp"

#include "common/render.hpp"
#include "common/timing.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <mutex>

namespace rt::render_tool {

namespace {

constexpr int bins = 16;
constexpr size_t min_leaf = 4;
constexpr size_t max_sah_depth = 100;
constexpr size_t parallel_bin_threshold = size_t(1) << 18;  // bigger nodes bin in parallel chunks
constexpr size_t task_size = size_t(1) << 17;                // smaller subtrees are one task each

// The build moves these, in order, rather than indices: 32 bytes each.
struct record {
    bvh_box box;
    std::uint32_t id, pad;
};

bvh_box empty_box() {
    const float inf = std::numeric_limits<float>::infinity();
    return {{inf, inf, inf}, {-inf, -inf, -inf}};
}
void grow(bvh_box& b, const bvh_box& o) {
    for (int a = 0; a < 3; ++a) b.lo[a] = std::min(b.lo[a], o.lo[a]), b.hi[a] = std::max(b.hi[a], o.hi[a]);
}
void grow(bvh_box& b, const float p[3]) {
    for (int a = 0; a < 3; ++a) b.lo[a] = std::min(b.lo[a], p[a]), b.hi[a] = std::max(b.hi[a], p[a]);
}
double area(const bvh_box& b) {
    const double x = double(b.hi[0]) - b.lo[0], y = double(b.hi[1]) - b.lo[1], z = double(b.hi[2]) - b.lo[2];
    return x < 0 ? 0 : 2 * (x * y + y * z + z * x);
}
void centre(const record& r, float c[3]) {
    for (int a = 0; a < 3; ++a) c[a] = 0.5f * (r.box.lo[a] + r.box.hi[a]);
}

// What one pass over a range learns: per bin, its objects' box, their
// centres' box and their number.
struct bin_stats {
    std::array<bvh_box, bins> box, centres;
    std::array<size_t, bins> count{};
    bin_stats() { box.fill(empty_box()), centres.fill(empty_box()); }
    void merge(const bin_stats& o) {
        for (int i = 0; i < bins; ++i) grow(box[i], o.box[i]), grow(centres[i], o.centres[i]), count[i] += o.count[i];
    }
};

// Which bin a record's centre falls in, along `axis`.
struct binner {
    int axis;
    float low, scale;
    int of(float centre) const { return std::clamp(int((centre - low) * scale), 0, bins - 1); }
    int operator()(const record& r) const { return of(0.5f * (r.box.lo[axis] + r.box.hi[axis])); }
};

// Four floats, gcc's vector extension (SSE, part of every x86-64): a
// record's low corner and its high corner each load as one, so the pass
// below grows a bin's box and its centres' box with four instructions
// instead of twelve; it is the build's hottest loop (every record, every
// level). Lane 3 holds whatever follows in the record and is never read.
// The selects are std::min's and std::max's (b < a ? b : a), so the bins,
// and the tree, are the same bit for bit as with the scalar grow().
typedef float f4 __attribute__((vector_size(16)));
struct f4_bin {
    f4 lo, hi, centre_lo, centre_hi;
};

void bin_range(const record* r, size_t n, const binner& which, bin_stats& s) {
    const float inf = std::numeric_limits<float>::infinity();
    const f4 up = {inf, inf, inf, inf}, down = -up;
    std::array<f4_bin, bins> acc;
    acc.fill(f4_bin{up, down, up, down});
    for (size_t i = 0; i < n; ++i) {
        f4 lo, hi;
        std::memcpy(&lo, r[i].box.lo, sizeof lo);  // lo[0..2], hi[0]
        std::memcpy(&hi, r[i].box.hi, sizeof hi);  // hi[0..2], id
        const f4 c = 0.5f * (lo + hi);             // lanes 0..2: centre(), bit for bit
        const auto b = size_t(which.of(c[which.axis]));
        f4_bin& a = acc[b];
        a.lo = lo < a.lo ? lo : a.lo, a.hi = a.hi < hi ? hi : a.hi;
        a.centre_lo = c < a.centre_lo ? c : a.centre_lo, a.centre_hi = a.centre_hi < c ? c : a.centre_hi;
        ++s.count[b];
    }
    for (size_t b = 0; b < size_t(bins); ++b)
        for (int k = 0; k < 3; ++k) {
            s.box[b].lo[k] = std::min(s.box[b].lo[k], acc[b].lo[k]), s.box[b].hi[k] = std::max(s.box[b].hi[k], acc[b].hi[k]);
            s.centres[b].lo[k] = std::min(s.centres[b].lo[k], acc[b].centre_lo[k]);
            s.centres[b].hi[k] = std::max(s.centres[b].hi[k], acc[b].centre_hi[k]);
        }
}

// The same, split into chunks over the thread pool for big ranges.
bin_stats bin_all(const record* r, size_t n, const binner& which) {
    bin_stats total;
    if (n < parallel_bin_threshold) {
        bin_range(r, n, which, total);
        return total;
    }
    const int chunks = 4 * render_threads();
    std::vector<bin_stats> part(static_cast<size_t>(chunks));
    for_each_row(chunks, [&](int c) {
        const size_t from = n * size_t(c) / size_t(chunks), to = n * size_t(c + 1) / size_t(chunks);
        bin_range(r + from, to - from, which, part[size_t(c)]);
    });
    for (const auto& p : part) total.merge(p);
    return total;
}

// std::partition on every core, for the big nodes at the top of the tree
// (below parallel_bin_threshold, one core partitions). Each thread
// partitions its own chunk; then the chunks are joined left to right: with
// the objects that go left so far in [begin, left_end), the chunk's own
// left part L2 in [start, mid) and the right part R1 of what came before
// in [left_end, start), swapping the shorter of R1 and L2 with the far end
// of the other puts every left object before every right one (neither
// side keeps its order, which a partition never promises). The swaps too
// are split over the threads.
template <class Pred>
record* parallel_partition(record* r, size_t n, Pred goes_left) {
    if (n < parallel_bin_threshold) return std::partition(r, r + n, goes_left);
    const int chunks = render_threads();
    std::vector<size_t> mid(static_cast<size_t>(chunks));
    auto chunk_start = [&](int c) { return n * size_t(c) / size_t(chunks); };
    for_each_row(chunks, [&](int c) {
        mid[size_t(c)] = size_t(std::partition(r + chunk_start(c), r + chunk_start(c + 1), goes_left) - r);
    });
    size_t left_end = mid[0];
    for (int c = 1; c < chunks; ++c) {
        const size_t start = chunk_start(c), k = std::min(start - left_end, mid[size_t(c)] - start);
        record* a = r + left_end;
        record* b = r + mid[size_t(c)] - k;
        const int parts = 4 * chunks;
        for_each_row(parts, [&](int q) {
            const size_t from = k * size_t(q) / size_t(parts), to = k * size_t(q + 1) / size_t(parts);
            std::swap_ranges(a + from, a + to, b + from);
        });
        left_end += mid[size_t(c)] - start;
    }
    return r + left_end;
}

// The box and the centres' box of a range (used at the root, and after a
// split that had to fall back to halving by count).
void bounds_of(const record* r, size_t n, bvh_box& box, bvh_box& centres) {
    box = empty_box(), centres = empty_box();
    for (size_t i = 0; i < n; ++i) {
        float c[3];
        centre(r[i], c);
        grow(box, r[i].box), grow(centres, c);
    }
}

struct job {
    size_t begin, end;
    bvh_box box, centres;
    std::uint32_t slot;  // the node this range becomes
    size_t depth;
};

class builder {
public:
    builder(std::vector<record>& records, int max_leaf) : rec_(records), max_leaf_(size_t(max_leaf)) {}

    // Builds j's subtree into `nodes` (j.slot already exists there). Ranges
    // below `defer_below` objects (other than the root) are not built but
    // appended to `deferred`.
    void build(const job& root, std::vector<bvh_node>& nodes, size_t defer_below, std::vector<job>& deferred) {
        std::vector<job> stack{root};
        while (!stack.empty()) {
            job j = stack.back();
            stack.pop_back();
            depth_ = std::max(depth_, j.depth);
            const size_t n = j.end - j.begin;
            if (n < defer_below && j.slot != root.slot) {
                deferred.push_back(j);
                continue;
            }
            nodes[j.slot].box = j.box;
            job left, right;
            if (!split(j, left, right)) {
                nodes[j.slot].first = std::uint32_t(j.begin);
                nodes[j.slot].count = std::uint32_t(n);
                ++leaves_;
                continue;
            }
            const auto first = std::uint32_t(nodes.size());
            nodes[j.slot].first = first;
            nodes[j.slot].count = 0;
            nodes.emplace_back();
            nodes.emplace_back();
            left.slot = first, right.slot = first + 1;
            left.depth = right.depth = j.depth + 1;
            stack.push_back(right);
            stack.push_back(left);
        }
    }

    size_t leaves_ = 0, depth_ = 0;

private:
    std::vector<record>& rec_;
    size_t max_leaf_;

    // Splits j by the SAH; false when a leaf is cheaper (and allowed).
    bool split(const job& j, job& left, job& right) {
        const size_t n = j.end - j.begin;
        // Below min_leaf objects a split never pays here: a packet's box
        // test costs about what its test of a few objects costs, and every
        // split adds two 32-byte nodes (48 million spheres in leaves of one
        // would need 3 GB of nodes).
        if (n <= min_leaf) return false;
        // The traversals keep a stack of 256 nodes: past depth 100 (not
        // reached on any scene tried: 48 million spheres give 49, and float's
        // range keeps even exponentially spaced objects near 30) a node is
        // halved by count, so the tree is never deeper than 100 + log2(N).
        if (j.depth >= max_sah_depth) return halve(j, left, right);
        int axis = 0;
        for (int a = 1; a < 3; ++a)
            if (j.centres.hi[a] - j.centres.lo[a] > j.centres.hi[axis] - j.centres.lo[axis]) axis = a;
        const float extent = j.centres.hi[axis] - j.centres.lo[axis];
        record* r = rec_.data() + j.begin;
        if (!(extent > 0)) {  // all centres in one point: no split tells them apart
            if (n <= max_leaf_) return false;
            return halve(j, left, right);
        }
        const binner which{axis, j.centres.lo[axis], float(bins) * 0.99999f / extent};
        const bin_stats s = bin_all(r, n, which);
        // Sweep: the box and count left of each boundary, then right of it.
        std::array<double, bins> left_cost{};
        bvh_box b = empty_box();
        size_t count = 0;
        for (int i = 0; i < bins - 1; ++i) {
            grow(b, s.box[size_t(i)]), count += s.count[size_t(i)];
            left_cost[size_t(i)] = area(b) * double(count);
        }
        double best = std::numeric_limits<double>::infinity();
        int best_split = -1;
        b = empty_box(), count = 0;
        for (int i = bins - 1; i > 0; --i) {
            grow(b, s.box[size_t(i)]), count += s.count[size_t(i)];
            const double cost = left_cost[size_t(i - 1)] + area(b) * double(count);
            if (count < n && count > 0 && cost < best) best = cost, best_split = i;
        }
        const double parent = area(j.box);
        const bool leaf_cheaper = !(parent > 0) || double(n) * parent <= parent + best;
        if (n <= max_leaf_ && (best_split < 0 || leaf_cheaper)) return false;
        if (best_split < 0) return halve(j, left, right);
        record* mid = parallel_partition(r, n, [&](const record& x) { return which(x) < best_split; });
        left = job{j.begin, j.begin + size_t(mid - r), empty_box(), empty_box(), 0, 0};
        right = job{left.end, j.end, empty_box(), empty_box(), 0, 0};
        for (int i = 0; i < bins; ++i) {
            job& side = i < best_split ? left : right;
            grow(side.box, s.box[size_t(i)]), grow(side.centres, s.centres[size_t(i)]);
        }
        return true;
    }

    // Half the objects each side (any half: their centres coincide).
    bool halve(const job& j, job& left, job& right) {
        record* r = rec_.data() + j.begin;
        const size_t n = j.end - j.begin, half = n / 2;
        std::nth_element(r, r + half, r + n, [](const record& a, const record& b) { return a.id < b.id; });
        left = job{j.begin, j.begin + half, {}, {}, 0, 0};
        right = job{j.begin + half, j.end, {}, {}, 0, 0};
        bounds_of(rec_.data() + left.begin, half, left.box, left.centres);
        bounds_of(rec_.data() + right.begin, n - half, right.box, right.centres);
        return true;
    }
};

}  // namespace

bvh_tree build_bvh(const std::vector<bvh_box>& boxes, int max_leaf) {
    stopwatch clock;
    bvh_tree tree;
    if (boxes.empty()) return tree;
    // The records and the root's bounds, in chunks on every core.
    std::vector<record> rec(boxes.size());
    job root{0, rec.size(), empty_box(), empty_box(), 0, 0};
    {
        const int chunks = 4 * render_threads();
        std::mutex merge;
        for_each_row(chunks, [&](int c) {
            const size_t from = rec.size() * size_t(c) / size_t(chunks), to = rec.size() * size_t(c + 1) / size_t(chunks);
            for (size_t i = from; i < to; ++i) rec[i] = {boxes[i], std::uint32_t(i), 0};
            bvh_box b, k;
            bounds_of(rec.data() + from, to - from, b, k);
            const std::lock_guard<std::mutex> lock(merge);
            grow(root.box, b), grow(root.centres, k);
        });
    }
    tree.nodes.emplace_back();

    // The top of the tree, one node at a time with parallel binning; every
    // range below task_size is left for the second phase.
    builder top(rec, max_leaf);
    std::vector<job> tasks;
    top.build(root, tree.nodes, task_size, tasks);

    // The subtrees, one task each, into their own node lists; then spliced
    // in: a subtree's root replaces its slot, the rest are appended.
    std::vector<std::vector<bvh_node>> parts(tasks.size());
    std::vector<size_t> leaves(tasks.size()), depths(tasks.size());
    for_each_row(int(tasks.size()), [&](int t) {
        builder b(rec, max_leaf);
        std::vector<job> none;
        job j = tasks[size_t(t)];
        j.slot = 0;
        parts[size_t(t)].emplace_back();
        b.build(j, parts[size_t(t)], 0, none);
        leaves[size_t(t)] = b.leaves_, depths[size_t(t)] = tasks[size_t(t)].depth + b.depth_;
    });
    tree.leaves = top.leaves_, tree.depth = top.depth_;
    // Where each subtree's nodes go (its root replaces its slot, the rest
    // are appended: local node i >= 1 goes to base + i), then the copies,
    // one task each.
    std::vector<size_t> base(tasks.size());
    size_t total = tree.nodes.size();
    for (size_t t = 0; t < tasks.size(); ++t) {
        base[t] = total - 1;
        total += parts[t].size() - 1;
        tree.leaves += leaves[t], tree.depth = std::max(tree.depth, depths[t]);
    }
    tree.nodes.reserve(total);  // exactly: a tree of 48 million spheres has a gigabyte of nodes
    tree.nodes.resize(total);
    for_each_row(int(tasks.size()), [&](int ti) {
        const auto t = size_t(ti);
        std::vector<bvh_node>& part = parts[t];
        for (size_t i = 0; i < part.size(); ++i) {
            bvh_node n = part[i];
            if (n.count == 0) n.first += std::uint32_t(base[t]);
            tree.nodes[i == 0 ? tasks[t].slot : base[t] + i] = n;
        }
        std::vector<bvh_node>().swap(part);
    });
    tree.order.resize(rec.size());
    const int chunks = 4 * render_threads();
    for_each_row(chunks, [&](int c) {
        const size_t from = rec.size() * size_t(c) / size_t(chunks), to = rec.size() * size_t(c + 1) / size_t(chunks);
        for (size_t i = from; i < to; ++i) tree.order[i] = rec[i].id;
    });
    tree.build_seconds = clock.seconds();
    return tree;
}

namespace {

// Writes the wide node for binary inner node `b` (and, depth first, the
// wide nodes below it); returns its index. Children are numbered after
// their parent, so a ray's walk reads the array mostly forwards.
std::uint32_t collapse(const std::vector<bvh_node>& bin, std::uint32_t b, std::vector<bvh_wide_node>& out) {
    // Open the largest inner child until there are `wide` of them: the
    // largest box is the one most rays enter, so it is the one most worth
    // replacing by its children's tighter boxes.
    std::uint32_t slot[wide] = {bin[b].first, bin[b].first + 1};
    int n = 2;
    while (n < wide) {
        int best = -1;
        double best_area = -1;
        for (int i = 0; i < n; ++i) {
            const bvh_node& c = bin[slot[i]];
            if (c.count > 0) continue;
            const double a = area(c.box);
            if (a > best_area) best_area = a, best = i;
        }
        if (best < 0) break;
        const std::uint32_t opened = slot[best];
        slot[best] = bin[opened].first;
        slot[n++] = bin[opened].first + 1;
    }
    const auto index = std::uint32_t(out.size());
    out.emplace_back();
    std::uint32_t child[wide], count[wide];
    for (int i = 0; i < wide; ++i) {
        if (i >= n) {
            child[i] = 0, count[i] = bvh_wide_node::empty_slot;
            continue;
        }
        const bvh_node& c = bin[slot[i]];
        child[i] = c.count > 0 ? c.first : collapse(bin, slot[i], out);
        count[i] = c.count;
    }
    bvh_wide_node& w = out[index];  // after the recursion: `out` may have moved
    for (int i = 0; i < wide; ++i) {
        // An empty slot gets the inverted box (low +inf, high -inf), which no ray enters (fast_path.cpp).
        const bvh_box box = i < n ? bin[slot[i]].box : empty_box();
        for (int a = 0; a < 3; ++a) w.lo[a][i] = box.lo[a], w.hi[a][i] = box.hi[a];
        w.child[i] = child[i], w.count[i] = count[i];
    }
    return index;
}

}  // namespace

bvh_wide_tree collapse_to_wide(bvh_tree&& binary) {
    stopwatch clock;
    bvh_wide_tree tree;
    tree.order = std::move(binary.order);
    tree.leaves = binary.leaves, tree.depth = binary.depth;
    if (!binary.nodes.empty()) {
        const bvh_node& root = binary.nodes[0];
        if (root.count > 0) {  // a single leaf: a wide root with one child
            bvh_wide_node w{};
            for (int i = 0; i < wide; ++i) {
                const bvh_box box = i == 0 ? root.box : empty_box();
                for (int a = 0; a < 3; ++a) w.lo[a][i] = box.lo[a], w.hi[a][i] = box.hi[a];
                w.child[i] = 0, w.count[i] = bvh_wide_node::empty_slot;
            }
            w.child[0] = root.first, w.count[0] = root.count;
            tree.nodes.push_back(w);
        } else {
            // A wide node replaces at least two binary inner nodes (the
            // tree has leaves - 1 of them) unless its children are leaves.
            tree.nodes.reserve(binary.leaves / 2 + 1);
            collapse(binary.nodes, 0, tree.nodes);
        }
    }
    std::vector<bvh_node>().swap(binary.nodes);
    tree.build_seconds = binary.build_seconds + clock.seconds();
    return tree;
}

}  // namespace rt::render_tool
