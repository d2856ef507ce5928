// heatmap.hpp — a count per pixel drawn as a false-colour picture with its scale.
//
// Chapter 08's program and rt-render (--heatmap) count, for each pixel's
// primary ray, how many boxes the tree opened and how many objects it asked;
// this file only draws such counts. Several maps of one run are drawn side by
// side on ONE scale, so equal colours mean equal counts in every panel. The
// scale is logarithmic (counts from 0 to tens of thousands must all be seen:
// a tree asks a handful of objects where brute force asks every one), and a
// colour bar with its numbers is drawn under the panels.
#pragma once

#include "image.hpp"

#include <string>
#include <utility>
#include <vector>

namespace rt {

// One count per pixel, row-major, row 0 at the top.
struct count_map {
    std::string name;  // what is counted, for the legend line ("tree: boxes opened")
    int width = 0;
    int height = 0;
    std::vector<long> counts;

    count_map(std::string what, int w, int h) : name(std::move(what)), width(w), height(h), counts(size_t(w) * size_t(h), 0) {}
    long& at(int col, int row) { return counts[size_t(row) * size_t(width) + size_t(col)]; }
    long max() const;
    double mean() const;
};

// The panels side by side (all the same size), a gap between them, and under
// them the colour bar from 0 to the largest count of all, with the powers of
// ten marked and numbered.
image draw_heatmap(const std::vector<count_map>& panels);

// One line per panel: "name: min A, mean B, max C per pixel", for stdout.
std::string heatmap_legend(const std::vector<count_map>& panels);

}  // namespace rt
