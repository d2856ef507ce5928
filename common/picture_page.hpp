// picture_page.hpp — one picture as a page: the reference, a render and their difference side by
// side, with a slider between the first two (a chapter program's --compare writes it).
//
// The template is common/picture_page.html, compiled in; the grader's report.html
// (tools/grader/rtgrader/report.py) fills the same file, so both pages look alike. The page
// holds its pictures as data: URIs and loads nothing else: it reads the same offline, and can be
// mailed as one file.
#pragma once

#include <string>
#include <vector>

namespace rt {

struct picture_page {
    std::string title;     // the page's heading: "ch04 plane: your render against the reference"
    std::string id;        // "ch04"
    std::string caption;   // the comparison's verdict and figures
    std::vector<unsigned char> reference_png, render_png, diff_png;  // PNG files' bytes; diff may be empty
};

// The page's HTML (every text escaped).
std::string picture_page_html(const picture_page& page);

// The template's text (generated from common/picture_page.html).
const std::string& picture_page_template();

}  // namespace rt
