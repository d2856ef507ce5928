// report.cpp — tables, CSV and the work-precision diagram.
#include "report.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <stdexcept>

namespace rt::study {
namespace {

std::string fmt(const char* format, double x) {
    char buf[64];
    std::snprintf(buf, sizeof buf, format, x);
    return buf;
}

std::string number(double x) {
    if (std::isinf(x)) return "inf";
    if (x == 0) return "0";
    return fmt(x >= 1e5 || x < 1e-2 ? "%.2g" : "%.3g", x);
}

std::string timing(const outcome& o) {
    if (o.ns.median == 0) return "-";
    return fmt("%.1f", o.ns.median) + " [" + fmt("%.1f", o.ns.min) + ", " + fmt("%.1f", o.ns.max) + "]";
}

std::string extra(const outcome& o) {
    std::string s;
    if (o.rays) s += "leaks " + std::to_string(o.leaks) + "/" + std::to_string(o.rays) + " rays";
    if (o.off_plane_max >= 0) s += "off-plane ULP " + number(o.off_plane_median) + " / " + number(o.off_plane_max);
    if (o.nan_hits || o.out_of_range)
        s += (s.empty() ? "" : "; ") + std::string("BROKEN: ") + std::to_string(o.nan_hits) + " NaN, " +
             std::to_string(o.out_of_range) + " out of range";
    return s.empty() ? "" : s;
}

std::ofstream open(const std::string& path) {
    std::ofstream f(path);
    if (!f) throw std::runtime_error("cannot write " + path);
    return f;
}

}  // namespace

void print_family_table(std::ostream& os, const std::string& family, const std::string& description,
                        const std::vector<outcome>& rows) {
    os << "\n### " << family << ": " << description << "\n\n";
    bool any_extra = false;
    for (const outcome& o : rows)
        if (o.family == family && !extra(o).empty()) any_extra = true;
    os << "| formulation | prec | ns/test median [min, max] | hits % | ULP med / p99 / max | rel. error med / p99 / max "
          "| false hits | false misses | wrong roots |"
       << (any_extra ? " notes |" : "") << "\n";
    os << "|---|---|---|---|---|---|---|---|---|" << (any_extra ? "---|" : "") << "\n";
    for (const outcome& o : rows) {
        if (o.family != family) continue;
        os << "| " << o.formulation << " | " << o.precision << " | ";
        if (o.failed) {
            os << o.failure << " | | | | | | |" << (any_extra ? " |" : "") << "\n";
            continue;
        }
        const error_summary& e = o.error;
        os << timing(o) << " | " << fmt("%.1f", 100 * o.hit_ratio()) << " | ";
        if (e.count)
            os << number(e.ulp_median) << " / " << number(e.ulp_p99) << " / " << number(e.ulp_max) << " | "
               << fmt("%.1e", e.rel_median) << " / " << fmt("%.1e", e.rel_p99) << " / " << fmt("%.1e", e.rel_max);
        else
            os << "- | -";
        os << " | " << o.false_hits << " | " << o.false_misses << " | " << o.wrong_roots << " |";
        if (any_extra) os << " " << extra(o) << " |";
        os << "\n";
    }
}

void print_group_table(std::ostream& os, const std::vector<std::string>& groups, std::size_t per_group,
                       const std::vector<outcome>& rows) {
    os << "\nMisclassified rays (false hits + false misses) out of " << per_group << " per group:\n\n";
    os << "| formulation | prec |";
    for (const std::string& g : groups) os << " " << g << " |";
    os << "\n|---|---|";
    for (std::size_t i = 0; i < groups.size(); ++i) os << "---|";
    os << "\n";
    for (const outcome& o : rows) {
        if (o.failed || o.misclassified_per_group.size() != groups.size()) continue;
        os << "| " << o.formulation << " | " << o.precision << " |";
        for (std::size_t n : o.misclassified_per_group) os << " " << n << " |";
        os << "\n";
    }
}

void print_group_error_table(std::ostream& os, const std::vector<std::string>& groups, const std::vector<outcome>& rows) {
    os << "\nLargest relative error of a hit on the right root, per group (- : no hit on the right root):\n\n"
          "| formulation | prec |";
    for (const std::string& g : groups) os << " " << g << " |";
    os << "\n|---|---|";
    for (std::size_t i = 0; i < groups.size(); ++i) os << "---|";
    os << "\n";
    for (const outcome& o : rows) {
        if (o.failed || o.rel_max_per_group.size() != groups.size()) continue;
        os << "| " << o.formulation << " | " << o.precision << " |";
        for (std::size_t g = 0; g < groups.size(); ++g)
            os << " " << (o.compared_per_group[g] ? fmt("%.1e", o.rel_max_per_group[g]) : "-") << " |";
        os << "\n";
    }
}

void print_summary_table(std::ostream& os, const std::vector<std::string>& families, const std::vector<outcome>& rows) {
    os << "\n| formulation | prec |";
    for (const std::string& f : families) os << " " << f << " |";
    os << "\n|---|---|";
    for (std::size_t i = 0; i < families.size(); ++i) os << "---|";
    os << "\n";
    std::vector<std::pair<std::string, std::string>> keys;
    for (const outcome& o : rows) {
        if (std::find(families.begin(), families.end(), o.family) == families.end()) continue;
        std::pair<std::string, std::string> k{o.formulation, o.precision};
        if (std::find(keys.begin(), keys.end(), k) == keys.end()) keys.push_back(k);
    }
    for (const auto& [name, precision] : keys) {
        os << "| " << name << " | " << precision << " |";
        for (const std::string& f : families) {
            const outcome* found = nullptr;
            for (const outcome& o : rows)
                if (o.family == f && o.formulation == name && o.precision == precision) found = &o;
            if (!found || found->failed) {
                os << " - |";
                continue;
            }
            os << " " << found->misclassified() << " / " << (found->error.count ? number(found->error.ulp_max) : "-")
               << " / " << fmt("%.0f", found->ns.median);
            if (found->rays) os << " (leaks " << found->leaks << ")";
            os << " |";
        }
        os << "\n";
    }
}

void write_csv(const std::string& path, const std::vector<outcome>& rows) {
    std::ofstream f = open(path);
    f << "family,formulation,precision,queries,hit_ratio,ns_median,ns_min,ns_max,ulp_median,ulp_p99,ulp_max,"
         "rel_median,rel_p99,rel_max,compared,false_hits,false_misses,wrong_roots,nan_hits,out_of_range,rays,leaks,"
         "off_plane_median_ulp,off_plane_max_ulp,failed\n";
    for (const outcome& o : rows) {
        const error_summary& e = o.error;
        f << o.family << "," << o.formulation << "," << o.precision << "," << o.queries << "," << o.hit_ratio() << ","
          << o.ns.median << "," << o.ns.min << "," << o.ns.max << "," << e.ulp_median << "," << e.ulp_p99 << ","
          << e.ulp_max << "," << e.rel_median << "," << e.rel_p99 << "," << e.rel_max << "," << e.count << ","
          << o.false_hits << "," << o.false_misses << "," << o.wrong_roots << "," << o.nan_hits << ","
          << o.out_of_range << "," << o.rays << "," << o.leaks << "," << o.off_plane_median << ","
          << o.off_plane_max << "," << (o.failed ? 1 : 0) << "\n";
    }
}

void write_group_csv(const std::string& path, const std::vector<std::string>& groups, const std::vector<outcome>& rows) {
    std::ofstream f = open(path);
    f << "group,formulation,precision,misclassified\n";
    for (const outcome& o : rows) {
        if (o.misclassified_per_group.size() != groups.size()) continue;
        for (std::size_t i = 0; i < groups.size(); ++i)
            f << groups[i] << "," << o.formulation << "," << o.precision << "," << o.misclassified_per_group[i] << "\n";
    }
}

namespace {

// One marker shape per formulation (its position in the table order), so
// that points are told apart by shape, not by one of many colours; the
// precision decides the fill: float filled, double hollow.
void marker(std::ostream& f, int shape, double x, double y, bool filled, const char* colour) {
    const std::string style = std::string("fill='") + (filled ? colour : "white") + "' stroke='" + colour +
                              "' stroke-width='1.6'";
    const double r = 5;
    switch (shape % 8) {
    case 0: f << "<circle cx='" << x << "' cy='" << y << "' r='" << r << "' " << style << "/>"; break;
    case 1: f << "<rect x='" << x - r << "' y='" << y - r << "' width='" << 2 * r << "' height='" << 2 * r << "' " << style << "/>"; break;
    case 2: f << "<polygon points='" << x << "," << y - r - 1 << " " << x + r + 1 << "," << y << " " << x << "," << y + r + 1 << " " << x - r - 1 << "," << y << "' " << style << "/>"; break;
    case 3: f << "<polygon points='" << x << "," << y - r - 1 << " " << x + r + 1 << "," << y + r << " " << x - r - 1 << "," << y + r << "' " << style << "/>"; break;
    case 4: f << "<polygon points='" << x << "," << y + r + 1 << " " << x + r + 1 << "," << y - r << " " << x - r - 1 << "," << y - r << "' " << style << "/>"; break;
    case 5: f << "<polygon points='" << x - r - 1 << "," << y << " " << x + r << "," << y - r - 1 << " " << x + r << "," << y + r + 1 << "' " << style << "/>"; break;
    case 6: f << "<polygon points='" << x + r + 1 << "," << y << " " << x - r << "," << y - r - 1 << " " << x - r << "," << y + r + 1 << "' " << style << "/>"; break;
    default:  // a hexagon
        f << "<polygon points='";
        for (int k = 0; k < 6; ++k)
            f << x + (r + 1) * std::cos(k * 1.0471975511965976) << "," << y + (r + 1) * std::sin(k * 1.0471975511965976) << " ";
        f << "' " << style << "/>";
    }
    f << "\n";
}

}  // namespace

void write_svg(const std::string& path, const std::vector<std::string>& families, const std::vector<outcome>& rows,
               const std::string& subtitle) {
    // Two panels per row; each panel is a plot and, beside it, a table of
    // its points (so no label is ever drawn on top of another point).
    const int columns = 2, plot_w = 260, plot_h = 230, table_w = 430, left = 55, row_h = 14;
    const int panel_w = left + plot_w + 20 + table_w, top = 80;
    const char* palette[] = {"#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#17becf", "#8c564b", "#000000"};
    std::vector<std::string> names;  // every formulation, in table order: its index picks shape and colour
    for (const outcome& o : rows)
        if (std::find(names.begin(), names.end(), o.formulation) == names.end()) names.push_back(o.formulation);
    auto index_of = [&](const std::string& n) { return static_cast<int>(std::find(names.begin(), names.end(), n) - names.begin()); };
    // Panel heights follow their tables (up to 16 rows).
    std::vector<int> panel_h(families.size());
    for (std::size_t p = 0; p < families.size(); ++p) {
        int n = 0;
        for (const outcome& o : rows) n += o.family == families[p];
        panel_h[p] = std::max(plot_h + 75, 40 + (n + 2) * row_h + 20);
    }
    std::vector<int> row_top;
    int y_cursor = top;
    for (std::size_t p = 0; p < families.size(); p += columns) {
        row_top.push_back(y_cursor);
        int h = panel_h[p];
        if (p + 1 < families.size()) h = std::max(h, panel_h[p + 1]);
        y_cursor += h;
    }
    const int width = columns * panel_w + 20, height = y_cursor + 20;
    // Axes: time 1..1000 ns, error 1e-18..1; values outside are drawn on the
    // edge, marked with an arrow, and said in the table ("clipped").
    const double ns_lo = 1, ns_hi = 1000, err_lo = 1e-18, err_hi = 1;
    auto x_of = [&](double ns) { return left + (std::log10(std::clamp(ns, ns_lo, ns_hi)) / 3.0) * plot_w; };
    auto y_of = [&](double err) { return 30 + (-std::log10(std::clamp(err, err_lo, err_hi)) / 18.0) * plot_h; };
    std::ofstream f = open(path);
    f << "<svg xmlns='http://www.w3.org/2000/svg' width='" << width << "' height='" << height
      << "' font-family='sans-serif' font-size='11'>\n<rect width='100%' height='100%' fill='white'/>\n";
    f << "<text x='10' y='22' font-size='16'>Work-precision: largest relative error against time, one panel per case "
         "family</text>\n";
    f << "<text x='10' y='40'>" << subtitle << "</text>\n";
    f << "<text x='10' y='56'>x: ns per test (median, log); y: largest relative error of a hit on the right root (log). "
         "Shape and colour: formulation (see each table); filled: float, hollow: double.</text>\n";
    f << "<text x='10' y='70'>Errors below 1e-18 (also exact answers, 0) sit on the floor and errors above 1 on the "
         "ceiling, with an arrow; the table gives the true value. Bad: misclassified rays (meshes: leaks).</text>\n";
    for (std::size_t p = 0; p < families.size(); ++p) {
        const int ox = 10 + static_cast<int>(p % columns) * panel_w, oy = row_top[p / columns];
        f << "<g transform='translate(" << ox << "," << oy << ")'>\n";
        f << "<rect x='" << left << "' y='30' width='" << plot_w << "' height='" << plot_h
          << "' fill='none' stroke='#999'/>\n";
        f << "<text x='" << left << "' y='20' font-size='13' font-weight='bold'>" << families[p] << "</text>\n";
        for (int e = 0; e <= 18; e += 3)
            f << "<text x='" << left - 4 << "' y='" << y_of(std::pow(10.0, -e)) + 4 << "' text-anchor='end'>1e-" << e
              << "</text>\n";
        for (double ns : {1.0, 10.0, 100.0, 1000.0})
            f << "<text x='" << x_of(ns) << "' y='" << 30 + plot_h + 14 << "' text-anchor='middle'>" << ns << "</text>\n";
        f << "<text x='" << left + plot_w / 2 << "' y='" << 30 + plot_h + 28 << "' text-anchor='middle' fill='#555'>ns per "
             "test</text>\n";
        // The table beside the plot.
        const int tx = left + plot_w + 20;
        int ty = 30;
        f << "<text x='" << tx << "' y='" << ty << "' font-weight='bold'><tspan x='" << tx + 18 << "'>formulation</tspan>"
          << "<tspan x='" << tx + 150 << "'>prec</tspan><tspan x='" << tx + 195 << "'>ns</tspan><tspan x='" << tx + 245
          << "'>max rel. error</tspan><tspan x='" << tx + 350 << "'>bad</tspan></text>\n";
        int clipped = 0;
        for (const outcome& o : rows) {
            if (o.family != families[p]) continue;
            ty += row_h;
            const int k = index_of(o.formulation);
            const char* colour = palette[k % 8];
            const bool has_point = !o.failed && o.ns.median > 0 && o.error.count > 0;
            std::string err = o.failed ? "failed" : (o.error.count == 0 ? "no hits" : fmt("%.2g", o.error.rel_max));
            const bool clip = has_point && (o.error.rel_max < err_lo || o.error.rel_max > err_hi || o.ns.median < ns_lo ||
                                            o.ns.median > ns_hi);
            if (clip) err += " (clipped)", ++clipped;
            std::size_t bad = o.rays ? o.leaks : o.misclassified();
            marker(f, k, tx + 6, ty - 4, o.precision == "float", colour);
            f << "<text x='" << tx + 18 << "' y='" << ty << "'>" << o.formulation << "<tspan x='" << tx + 150 << "'>"
              << o.precision << "</tspan><tspan x='" << tx + 195 << "'>" << (o.ns.median > 0 ? fmt("%.1f", o.ns.median) : "-")
              << "</tspan><tspan x='" << tx + 245 << "'>" << err << "</tspan><tspan x='" << tx + 350 << "'"
              << (bad ? " fill='red'" : "") << ">" << bad << "</tspan></text>\n";
            if (!has_point) continue;
            const double x = x_of(o.ns.median), y = y_of(o.error.rel_max);
            marker(f, k, x, y, o.precision == "float", colour);
            if (o.error.rel_max < err_lo)
                f << "<path d='M" << x << "," << y + 7 << " l0,8 m-3,-3 l3,3 l3,-3' stroke='#555' fill='none'/>\n";
            else if (o.error.rel_max > err_hi)
                f << "<path d='M" << x << "," << y - 7 << " l0,-8 m-3,3 l3,-3 l3,3' stroke='#555' fill='none'/>\n";
        }
        if (clipped)
            f << "<text x='" << left << "' y='" << 30 + plot_h + 44 << "' fill='#555'>" << clipped
              << " value(s) clipped to the axes (arrows); true values in the table</text>\n";
        f << "</g>\n";
    }
    f << "</svg>\n";
}

}  // namespace rt::study
