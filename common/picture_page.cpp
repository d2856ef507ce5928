#include "picture_page.hpp"

#include <map>
#include <stdexcept>

namespace rt {

namespace {

std::string escape_html(const std::string& text) {
    std::string out;
    for (char c : text) {
        switch (c) {
            case '&': out += "&amp;"; break;
            case '<': out += "&lt;"; break;
            case '>': out += "&gt;"; break;
            case '"': out += "&quot;"; break;
            case '\'': out += "&#x27;"; break;
            default: out += c;
        }
    }
    return out;
}

std::string base64(const std::vector<unsigned char>& bytes) {
    static const char digits[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    size_t i = 0;
    for (; i + 2 < bytes.size(); i += 3) {
        const unsigned v = unsigned(bytes[i]) << 16 | unsigned(bytes[i + 1]) << 8 | bytes[i + 2];
        for (int k = 18; k >= 0; k -= 6) out += digits[(v >> k) & 63];
    }
    if (i < bytes.size()) {  // one or two bytes left: pad to four digits with '='
        const unsigned v = unsigned(bytes[i]) << 16 | (i + 1 < bytes.size() ? unsigned(bytes[i + 1]) << 8 : 0u);
        out += digits[(v >> 18) & 63];
        out += digits[(v >> 12) & 63];
        out += i + 1 < bytes.size() ? digits[(v >> 6) & 63] : '=';
        out += '=';
    }
    return out;
}

std::string png_uri(const std::vector<unsigned char>& png) { return "data:image/png;base64," + base64(png); }

// A grey box saying why a picture is missing, as an SVG data: URI.
std::string missing_uri(const std::string& why) {
    const std::string svg = "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"400\" height=\"300\"><rect width=\"400\" "
                            "height=\"300\" fill=\"#ddd\"/><text x=\"200\" y=\"150\" text-anchor=\"middle\" "
                            "font-size=\"16\">" + escape_html(why) + "</text></svg>";
    return "data:image/svg+xml;base64," + base64(std::vector<unsigned char>(svg.begin(), svg.end()));
}

// text with every {{name}} replaced by values[name]: escaped, unless name is "content" (HTML).
std::string fill(const std::string& text, const std::map<std::string, std::string>& values) {
    std::string out;
    size_t at = 0;
    while (true) {
        const size_t open = text.find("{{", at);
        const size_t close = open == std::string::npos ? open : text.find("}}", open);
        if (close == std::string::npos) break;
        out += text.substr(at, open - at);
        const std::string name = text.substr(open + 2, close - open - 2);
        const auto found = values.find(name);
        const std::string value = found == values.end() ? "" : found->second;
        out += name == "content" ? value : escape_html(value);
        at = close + 2;
    }
    return out + text.substr(at);
}

}  // namespace

std::string picture_page_html(const picture_page& page) {
    const std::string& text = picture_page_template();
    const std::string start = "<!-- picture -->\n", end = "<!-- /picture -->\n";
    const size_t a = text.find(start), b = text.find(end);
    if (a == std::string::npos || b == std::string::npos || b < a)
        throw std::logic_error("common/picture_page.html has no picture block");
    const std::string outside = text.substr(0, a) + text.substr(b + end.size());
    const std::string block = text.substr(a + start.size(), b - a - start.size());
    const bool has_diff = !page.diff_png.empty();
    const std::string picture = fill(block, {{"id", page.id},
                                             {"caption", page.caption},
                                             {"reference", png_uri(page.reference_png)},
                                             {"render", png_uri(page.render_png)},
                                             {"diff", has_diff ? png_uri(page.diff_png)
                                                               : missing_uri("no difference image")},
                                             {"diff_label", has_diff ? "difference (red: past tolerance)"
                                                                     : "difference: none"}});
    return fill(outside, {{"title", page.title}, {"content", picture}});
}

}  // namespace rt
