// scene_file.cpp — the scene-file reader: JSON syntax from nlohmann-json,
// then a check of every field with an error that says where it is.
//
// nlohmann-json tells where a *syntax* error is, but once a file has parsed
// it no longer knows where each value came from. So a small scanner (the
// `locator` below) walks the same text once and notes the byte offset of
// every key and value under a path such as "spheres[1].radius". That is the
// one way a position is found: every error after the syntax check is raised
// with its field's path, and reported at that field's line and column.
#include "scene_file.hpp"

#include "obj_mesh.hpp"
#include "spd.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

namespace rt {

using json = nlohmann::json;

namespace {

// A message stays readable whatever the file holds (a 100 KB key, a string
// of a million characters): each part is cut to a sensible length.
std::string capped(std::string text, size_t most) {
    if (text.size() <= most) return text;
    const size_t cut = text.size() - most;
    text.resize(most);
    return text + "... (" + std::to_string(cut) + " more characters)";
}

}  // namespace

scene_error::scene_error(std::string file, int line, int column, std::string field, std::string problem)
    : std::runtime_error([&] {
          file = capped(std::move(file), 300);
          field = capped(std::move(field), 200);
          problem = capped(std::move(problem), 600);
          std::string where = file;
          if (line > 0) where += ":" + std::to_string(line) + ":" + std::to_string(column);
          return where + ": " + (field.empty() ? "" : field + ": ") + problem;
      }()),
      file_(std::move(file)),
      field_(std::move(field)),
      problem_(std::move(problem)),
      line_(line),
      column_(column) {}

namespace {

// 1-based line and column of a byte offset.
std::pair<int, int> line_and_column(const std::string& text, size_t offset) {
    offset = std::min(offset, text.size());
    int line = 1;
    size_t line_start = 0;
    for (size_t i = 0; i < offset; ++i)
        if (text[i] == '\n') {
            ++line;
            line_start = i + 1;
        }
    return {line, int(offset - line_start) + 1};
}

// Where each key and value of an already-validated JSON text starts.
class locator {
public:
    locator(const std::string& text, const std::string& source) : text_(text), source_(source) {
        skip_space();
        value("", 0);
    }

    // The error for the field at path, reported where its value starts (or
    // its key, for a problem with the key itself) - the one way every error
    // after the syntax check finds its line and column.
    [[noreturn]] void fail(const std::string& path, const std::string& problem) const {
        fail_at(value_at(path), path, problem);
    }
    [[noreturn]] void fail_at_key(const std::string& path, const std::string& problem) const {
        auto it = keys_.find(path);
        fail_at(it == keys_.end() ? value_at(path) : it->second, path, problem);
    }

    // Throws the error for the first number too large for a double, if any.
    void fail_at_overflowing_number() const {
        std::string first;
        for (const auto& [path, at] : values_) {
            if (at >= text_.size()) continue;  // a value recorded at the end of a cut-off text (found by the fuzzer)
            const char c = text_[at];
            const bool number = c == '-' || (c >= '0' && c <= '9');
            if (number && std::isinf(std::strtod(token_at(path, text_.size()).c_str(), nullptr)) &&
                (first.empty() || at < values_.at(first)))
                first = path;
        }
        if (!first.empty()) fail(first, "expected a finite number, got " + token_at(first) + " (too large even for a double)");
    }
    // The value's text as written, e.g. "1e999" for a number too large
    // (cut at `most` characters).
    std::string token_at(const std::string& path, size_t most = 40) const {
        size_t start = value_at(path), end = start;
        while (end < text_.size() && !std::strchr(",]} \t\r\n/", text_[end])) ++end;
        return text_.substr(start, std::min(end - start, most));
    }

private:
    // Scene files are shallow; a limit keeps the recursion bounded on any input.
    static constexpr int max_depth = 64;

    const std::string& text_;
    const std::string& source_;
    size_t pos_ = 0;
    std::map<std::string, size_t> values_, keys_;

    size_t value_at(const std::string& path) const {  // of the whole document when unknown
        auto it = values_.find(path);
        return it == values_.end() ? 0 : it->second;
    }

    [[noreturn]] void fail_at(size_t offset, const std::string& field, const std::string& problem) const {
        auto [line, column] = line_and_column(text_, offset);
        throw scene_error(source_, line, column, field, problem);
    }

    char peek() const { return pos_ < text_.size() ? text_[pos_] : '\0'; }

    void skip_space() {
        while (pos_ < text_.size()) {
            char c = text_[pos_];
            if (c == ' ' || c == '\t' || c == '\n' || c == '\r') {
                ++pos_;
            } else if (c == '/' && pos_ + 1 < text_.size() && text_[pos_ + 1] == '/') {
                // Ends where nlohmann-json ends it: at a line break.
                while (pos_ < text_.size() && text_[pos_] != '\n' && text_[pos_] != '\r') ++pos_;
            } else if (c == '/' && pos_ + 1 < text_.size() && text_[pos_ + 1] == '*') {
                size_t end = text_.find("*/", pos_ + 2);
                pos_ = end == std::string::npos ? text_.size() : end + 2;
            } else {
                break;
            }
        }
    }

    // Returns the decoded string starting at pos_ (which is at its quote).
    std::string string_token() {
        size_t start = pos_++;
        while (pos_ < text_.size() && text_[pos_] != '"') pos_ += text_[pos_] == '\\' ? 2 : 1;
        ++pos_;
        try {
            return json::parse(text_.substr(start, pos_ - start)).get<std::string>();
        } catch (const json::exception&) {
            return {};  // cannot happen for text nlohmann accepted; never fatal
        }
    }

    void value(const std::string& path, int depth) {
        if (depth > max_depth) fail_at(pos_, path, "nested more than " + std::to_string(max_depth) + " levels deep");
        values_[path] = pos_;
        char c = peek();
        if (c == '{') {
            ++pos_;
            skip_space();
            std::map<std::string, bool> seen;
            while (pos_ < text_.size() && peek() != '}') {
                size_t key_pos = pos_;
                if (peek() != '"') break;  // cannot happen after nlohmann accepted the text; never loop
                std::string key = string_token();
                std::string child = path.empty() ? key : path + "." + key;
                if (seen[key]) fail_at(key_pos, child, "this key appears twice in the same object");
                seen[key] = true;
                keys_[child] = key_pos;
                skip_space();
                ++pos_;  // ':'
                skip_space();
                value(child, depth + 1);
                skip_space();
                if (peek() == ',') ++pos_;
                skip_space();
            }
            ++pos_;
        } else if (c == '[') {
            ++pos_;
            skip_space();
            for (size_t i = 0; pos_ < text_.size() && peek() != ']'; ++i) {
                const size_t before = pos_;
                value(path + "[" + std::to_string(i) + "]", depth + 1);
                if (pos_ == before) break;  // no progress: cannot happen for valid JSON; never loop
                skip_space();
                if (peek() == ',') ++pos_;
                skip_space();
            }
            ++pos_;
        } else if (c == '"') {
            string_token();
        } else {
            while (pos_ < text_.size() && !std::strchr(",]} \t\r\n/", text_[pos_])) ++pos_;
        }
    }
};

// Levenshtein distance, to suggest the key a typo meant.
size_t edit_distance(const std::string& a, const std::string& b) {
    std::vector<size_t> row(b.size() + 1);
    for (size_t j = 0; j <= b.size(); ++j) row[j] = j;
    for (size_t i = 1; i <= a.size(); ++i) {
        size_t diagonal = row[0];
        row[0] = i;
        for (size_t j = 1; j <= b.size(); ++j) {
            size_t up = row[j];
            row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
            diagonal = up;
        }
    }
    return row[b.size()];
}

std::string join(const std::vector<std::string>& words) {
    std::string out;
    for (const auto& w : words) out += (out.empty() ? "" : ", ") + w;
    return out;
}

std::string format_vector(const vec3d& v) {
    std::ostringstream s;
    s << "[" << v.x << ", " << v.y << ", " << v.z << "]";
    return s.str();
}

// Checks one JSON document against the scene format and builds the scene.
class reader {
public:
    reader(const std::string& text, const std::string& source, const json& doc)
        : source_(source), doc_(doc), where_(text, source) {}

    scene_description read() {
        scene_description d;
        d.source = source_;
        if (!doc_.is_object()) fail("", "expected the scene to be a JSON object { ... }, got " + describe(doc_, ""));
        check_keys(doc_, "", {"description", "camera", "background", "ambient", "materials", "spheres", "planes",
                              "triangles", "meshes", "lights", "generate"});
        if (auto* j = member(doc_, "description"); j && !j->is_string())
            fail("description", "expected a string, got " + describe(*j, "description"));
        d.camera = read_camera(required(doc_, "", "camera", "an object describing the camera"), "camera");
        if (auto* j = member(doc_, "background")) d.world.background = read_color(*j, "background");
        if (auto* j = member(doc_, "ambient")) d.world.ambient = read_color(*j, "ambient");
        read_materials(d);
        read_list(d, "spheres", [&](const json& j, const std::string& p) { read_sphere(d, j, p); });
        read_list(d, "planes", [&](const json& j, const std::string& p) { read_plane(d, j, p); });
        read_list(d, "triangles", [&](const json& j, const std::string& p) { read_triangle(d, j, p); });
        read_list(d, "meshes", [&](const json& j, const std::string& p) { read_mesh(d, j, p); });
        read_list(d, "lights", [&](const json& j, const std::string& p) {
            check_keys(j, p, {"position", "intensity", "radius"});
            point_light light;
            light.position = read_point(required(j, p, "position", "a point [x, y, z]"), p + ".position");
            if (auto* i = member(j, "intensity")) light.intensity = read_color(*i, p + ".intensity");
            if (auto* r = member(j, "radius"))
                light.radius = read_number_in(*r, p + ".radius", 0, false, max_coordinate,
                                              "a radius >= 0 (0: a point light; > 0: a sphere light, chapter 11)");
            d.world.lights.push_back(light);
        });
        if (auto* g = member(doc_, "generate")) read_generate(d, *g);  // last: may pass max_objects
        return d;
    }

private:
    const std::string& source_;
    const json& doc_;
    locator where_;

    [[noreturn]] void fail(const std::string& field, const std::string& problem) const { where_.fail(field, problem); }

    static std::string child(const std::string& path, const std::string& key) {
        return path.empty() ? key : path + "." + key;
    }

    // A short description of what was found, for "expected X, got Y".
    std::string describe(const json& j, const std::string& path) const {
        switch (j.type()) {
            case json::value_t::null: return "null";
            case json::value_t::boolean: return j.get<bool>() ? "true" : "false";
            case json::value_t::string: {
                std::string s = j.get<std::string>();
                if (s.size() > 30) s = s.substr(0, 30) + "...";
                return "the string \"" + s + "\"";
            }
            case json::value_t::array: return "an array of " + std::to_string(j.size()) + " element(s)";
            case json::value_t::object: return "an object";
            default: return where_.token_at(path);  // a number, as written in the file
        }
    }

    static const json* member(const json& object, const std::string& key) {
        auto it = object.find(key);
        return it == object.end() ? nullptr : &*it;
    }

    const json& required(const json& object, const std::string& path, const std::string& key,
                         const std::string& what) const {
        if (auto* j = member(object, key)) return *j;
        fail(path, "missing field \"" + key + "\" (" + what + ")");
    }

    void check_keys(const json& j, const std::string& path, const std::vector<std::string>& allowed) const {
        if (!j.is_object()) fail(path, "expected an object { ... }, got " + describe(j, path));
        for (auto it = j.begin(); it != j.end(); ++it) {
            if (std::find(allowed.begin(), allowed.end(), it.key()) != allowed.end()) continue;
            std::string best;
            size_t best_distance = 3;  // suggest only close matches
            for (const auto& a : allowed)
                if (size_t dist = edit_distance(it.key(), a); dist < best_distance) best_distance = dist, best = a;
            std::string problem = "unknown key \"" + it.key() + "\"";
            if (!best.empty()) problem += " (did you mean \"" + best + "\"?)";
            problem += "; the keys allowed here are: " + join(allowed);
            std::string field = child(path, it.key());
            where_.fail_at_key(field, problem);
        }
    }

    double read_number(const json& j, const std::string& path) const {
        if (!j.is_number()) fail(path, "expected a number, got " + describe(j, path));
        double x = j.get<double>();
        if (!std::isfinite(x)) fail(path, "expected a finite number, got " + describe(j, path));
        return x;
    }

    // A number with a stated range; `what` says the range in words.
    double read_number_in(const json& j, const std::string& path, double low, bool low_open, double high,
                          const std::string& what) const {
        double x = read_number(j, path);
        bool ok = (low_open ? x > low : x >= low) && x <= high;
        if (!ok) fail(path, "expected " + what + ", got " + describe(j, path));
        return x;
    }

    long long read_integer(const json& j, const std::string& path, long long low, long long high,
                           const std::string& what) const {
        if (!j.is_number_integer()) fail(path, "expected " + what + ", got " + describe(j, path));
        long long x = j.is_number_unsigned() ? (j.get<unsigned long long>() > (unsigned long long)high
                                                    ? high + 1
                                                    : (long long)j.get<unsigned long long>())
                                             : j.get<long long>();
        if (x < low || x > high) fail(path, "expected " + what + ", got " + describe(j, path));
        return x;
    }

    vec3d read_triple(const json& j, const std::string& path, const std::string& what) const {
        if (!j.is_array() || j.size() != 3) fail(path, "expected " + what + ", got " + describe(j, path));
        vec3d v;
        for (int i = 0; i < 3; ++i) {
            std::string p = path + "[" + std::to_string(i) + "]";
            const json& x = j[size_t(i)];
            if (!x.is_number()) fail(p, "expected a number (part of " + what + "), got " + describe(x, p));
            v[i] = read_number(x, p);
        }
        return v;
    }

    vec3d read_point(const json& j, const std::string& path) const {
        vec3d v = read_triple(j, path, "a point [x, y, z]");
        for (int i = 0; i < 3; ++i)
            if (!(std::fabs(v[i]) <= max_coordinate))
                fail(path + "[" + std::to_string(i) + "]",
                     "expected a coordinate of magnitude at most 1e15 (so the scene also works in float), got " +
                         where_.token_at(path + "[" + std::to_string(i) + "]"));
        return v;
    }

    vec3d read_direction(const json& j, const std::string& path) const {
        vec3d v = read_point(j, path);
        if (!(length(v) > 0)) fail(path, "expected a non-zero direction vector, got [0, 0, 0]");
        return v;
    }

    color read_color(const json& j, const std::string& path) const {
        vec3d v = read_triple(j, path, "a colour [r, g, b]");
        for (int i = 0; i < 3; ++i)
            if (!(v[i] >= 0 && v[i] <= 1e15))
                fail(path + "[" + std::to_string(i) + "]",
                     "expected a colour component >= 0 (and at most 1e15), got " +
                         where_.token_at(path + "[" + std::to_string(i) + "]"));
        return color(float(v.x), float(v.y), float(v.z));
    }

    camera_description read_camera(const json& j, const std::string& path) const {
        check_keys(j, path, {"type", "eye", "look_at", "up", "fov", "view_height", "width", "height", "aperture",
                             "focus_distance"});
        camera_description c;
        if (auto* t = member(j, "type")) {
            std::string p = path + ".type";
            if (!t->is_string() || (*t != "pinhole" && *t != "orthographic"))
                fail(p, "expected \"pinhole\" or \"orthographic\", got " + describe(*t, p));
            c.type = *t == "pinhole" ? camera_description::kind::pinhole : camera_description::kind::orthographic;
        }
        bool pinhole = c.type == camera_description::kind::pinhole;
        if (pinhole && member(j, "view_height"))
            where_.fail_at_key(path + ".view_height",
                               "view_height belongs to an orthographic camera; a pinhole camera uses fov");
        if (!pinhole && member(j, "fov"))
            where_.fail_at_key(path + ".fov",
                               "fov belongs to a pinhole camera; an orthographic camera uses view_height");
        for (const char* lens_key : {"aperture", "focus_distance"})
            if (!pinhole && member(j, lens_key))
                where_.fail_at_key(path + "." + lens_key, std::string(lens_key) +
                                                              " belongs to a pinhole camera with a thin lens "
                                                              "(chapter 11); an orthographic camera has no lens");
        c.eye = read_point(required(j, path, "eye", "the camera position [x, y, z]"), path + ".eye");
        c.look_at = read_point(required(j, path, "look_at", "the point the camera looks at [x, y, z]"),
                               path + ".look_at");
        if (auto* u = member(j, "up")) c.up = read_direction(*u, path + ".up");
        if (auto* f = member(j, "fov"))
            c.fov_degrees = read_number_in(*f, path + ".fov", 0, true, 179.999,
                                           "a vertical field of view in degrees, between 0 and 180");
        if (auto* h = member(j, "view_height"))
            c.view_height = read_number_in(*h, path + ".view_height", 0, true, max_coordinate,
                                           "a view height > 0");
        if (auto* a = member(j, "aperture"))
            c.aperture = read_number_in(*a, path + ".aperture", 0, false, max_coordinate,
                                        "a lens radius >= 0 (0: a pinhole)");
        if (auto* f = member(j, "focus_distance"))
            c.focus_distance = read_number_in(*f, path + ".focus_distance", 0, true, max_coordinate,
                                              "a distance > 0 to the plane in focus");
        if (auto* w = member(j, "width"))
            c.width = int(read_integer(*w, path + ".width", 1, max_image_side, "a whole number of pixels from 1 to 16384"));
        if (auto* h = member(j, "height"))
            c.height =
                int(read_integer(*h, path + ".height", 1, max_image_side, "a whole number of pixels from 1 to 16384"));

        // A degenerate camera has no frame: check in both precisions, since a
        // view direction that is fine in double can vanish when rounded to float.
        vec3d back = c.eye - c.look_at;
        if (!(length(convert<float>(back)) > 0) || !(length(back) > 0) ||
            !(length(convert<float>(c.eye) - convert<float>(c.look_at)) > 0))
            fail(path + ".look_at", "the camera looks at its own position " + format_vector(c.eye) +
                                        ": eye and look_at must be different points");
        if (!(length(cross(normalize(convert<float>(c.up)), convert<float>(normalize(back)))) > 1e-6f))
            fail(member(j, "up") ? path + ".up" : path,
                 "the up vector " + format_vector(c.up) +
                     " is parallel to the view direction (eye to look_at); choose an up vector across it");
        // Whatever the checks above miss, the cameras themselves find: build
        // them as the renderers will, in both precisions.
        check_camera_builds<float>(c, j, path, "float");
        check_camera_builds<double>(c, j, path, "double");
        return c;
    }

    // A camera that cannot be built in T (its frame or projection degenerates
    // there) is reported at the field that makes it so.
    template <class T>
    void check_camera_builds(const camera_description& c, const json& j, const std::string& path,
                             const char* precision) const {
        std::string field = member(j, "up") ? path + ".up" : path + ".look_at";
        try {
            camera_frame<T>::look_at(convert<T>(c.eye), convert<T>(c.look_at), convert<T>(c.up));
            const char* size = c.type == camera_description::kind::pinhole ? "fov" : "view_height";
            field = member(j, size) ? path + "." + size : path;
            scene_camera<T> built(c);
        } catch (const std::invalid_argument& e) {
            std::string problem = e.what();
            if (problem.rfind("camera: ", 0) == 0) problem.erase(0, 8);
            fail(field, problem + " when the camera is built in " + precision);
        }
    }

    void read_materials(scene_description& d) const {
        const json* list = member(doc_, "materials");
        if (!list) {
            d.world.materials.push_back(material{});  // one default grey material for every shape
            d.material_names.push_back("");
            return;
        }
        if (!list->is_array() || list->empty())
            fail("materials", "expected a non-empty array of materials [ {...}, ... ], got " +
                                  describe(*list, "materials"));
        for (size_t i = 0; i < list->size(); ++i) {
            std::string p = "materials[" + std::to_string(i) + "]";
            const json& j = (*list)[i];
            check_keys(j, p, {"name", "diffuse", "specular", "shininess", "checker", "mirror", "ior"});
            material m;
            std::string name;
            if (auto* n = member(j, "name")) {
                if (!n->is_string()) fail(p + ".name", "expected a string, got " + describe(*n, p + ".name"));
                name = n->get<std::string>();
                if (std::find(d.material_names.begin(), d.material_names.end(), name) != d.material_names.end())
                    fail(p + ".name", "two materials are named \"" + name + "\"; names must be unique");
            }
            if (auto* c = member(j, "diffuse")) m.diffuse = read_color(*c, p + ".diffuse");
            if (auto* c = member(j, "specular")) m.specular = read_color(*c, p + ".specular");
            if (auto* s = member(j, "shininess"))
                m.shininess = float(read_number_in(*s, p + ".shininess", 0, false, 10000, "a number from 0 to 10000"));
            if (auto* c = member(j, "checker")) {
                m.checker = true;
                m.checker_color = read_color(*c, p + ".checker");
            }
            if (auto* c = member(j, "mirror")) {
                m.mirror = read_color(*c, p + ".mirror");
                // A mirror reflects a fraction of the light: more than all of it
                // would make every bounce brighter than the last.
                for (int k = 0; k < 3; ++k)
                    if (!(m.mirror[k] <= 1.0f))
                        fail(p + ".mirror[" + std::to_string(k) + "]",
                             "expected a fraction from 0 to 1, got " + where_.token_at(p + ".mirror[" + std::to_string(k) + "]"));
            }
            // An index below 1 would be a medium slower than vacuum; above 10 no
            // transparent material exists (diamond is 2.42).
            if (auto* n = member(j, "ior"))
                m.ior = float(read_number_in(*n, p + ".ior", 1, false, 10, "an index of refraction from 1 to 10"));
            d.world.materials.push_back(m);
            d.material_names.push_back(name);
        }
    }

    int read_material_ref(const scene_description& d, const json& object, const std::string& path) const {
        const json* j = member(object, "material");
        if (!j) return 0;
        std::string p = path + ".material";
        int count = int(d.world.materials.size());
        if (j->is_string()) {
            auto it = std::find(d.material_names.begin(), d.material_names.end(), j->get<std::string>());
            if (it == d.material_names.end() || j->get<std::string>().empty()) {
                std::vector<std::string> named;
                for (const auto& n : d.material_names)
                    if (!n.empty()) named.push_back("\"" + n + "\"");
                fail(p, "no material is named \"" + j->get<std::string>() + "\" (" +
                            (named.empty() ? std::string("no material has a name") : "the names are " + join(named)) +
                            ")");
            }
            return int(it - d.material_names.begin());
        }
        return int(read_integer(*j, p, 0, count - 1,
                                "a material name or an index from 0 to " + std::to_string(count - 1)));
    }

    template <class F>
    void read_list(scene_description& d, const std::string& key, F&& read_one) const {
        const json* list = member(doc_, key);
        if (!list) return;
        if (!list->is_array()) fail(key, "expected an array [ {...}, ... ], got " + describe(*list, key));
        for (size_t i = 0; i < list->size(); ++i) read_one((*list)[i], key + "[" + std::to_string(i) + "]");
        if (size_t(d.world.object_count()) > max_objects) fail(key, "more than 10 million objects in the scene");
    }

    void read_sphere(scene_description& d, const json& j, const std::string& p) const {
        check_keys(j, p, {"center", "radius", "material"});
        sphere<double> s;
        s.center = read_point(required(j, p, "center", "the centre [x, y, z]"), p + ".center");
        s.radius = read_number_in(required(j, p, "radius", "a number > 0"), p + ".radius", 0, true, max_coordinate,
                                  "a radius > 0 (and at most 1e15)");
        if (!(float(s.radius) > 0.0f))
            fail(p + ".radius", "the radius " + where_.token_at(p + ".radius") + " rounds to 0 in float");
        s.material = read_material_ref(d, j, p);
        d.world.spheres.push_back(s);
    }

    void read_plane(scene_description& d, const json& j, const std::string& p) const {
        check_keys(j, p, {"point", "normal", "material"});
        plane<double> s;
        s.point = read_point(required(j, p, "point", "a point on the plane [x, y, z]"), p + ".point");
        s.normal = read_direction(required(j, p, "normal", "the plane's normal [x, y, z], not zero"), p + ".normal");
        s.material = read_material_ref(d, j, p);
        d.world.planes.push_back(s);
    }

    void check_area(const vec3d& a, const vec3d& b, const vec3d& c, const std::string& p) const {
        if (!(length(cross(b - a, c - a)) > 0))
            fail(p, "the corners " + format_vector(a) + ", " + format_vector(b) + ", " + format_vector(c) +
                        " lie on one line: the triangle has zero area");
    }

    void read_triangle(scene_description& d, const json& j, const std::string& p) const {
        check_keys(j, p, {"a", "b", "c", "material"});
        triangle<double> t;
        t.a = read_point(required(j, p, "a", "the first corner [x, y, z]"), p + ".a");
        t.b = read_point(required(j, p, "b", "the second corner [x, y, z]"), p + ".b");
        t.c = read_point(required(j, p, "c", "the third corner [x, y, z]"), p + ".c");
        check_area(t.a, t.b, t.c, p);
        t.material = read_material_ref(d, j, p);
        d.world.triangles.push_back(t);
    }

    // "generate": {"name": "balls", "size": 4}: one of the Standard
    // Procedural Databases (common/spd.hpp), its materials 0, 1 being the
    // scene's first materials.
    void read_generate(scene_description& d, const json& j) const {
        check_keys(j, "generate", {"name", "size"});
        const json& n = required(j, "generate", "name", "\"balls\", \"tetra\" or \"mount\"");
        spd_database db;
        if (!n.is_string() || !spd_from_name(n.get<std::string>(), db))
            fail("generate.name", "expected \"balls\", \"tetra\" or \"mount\", got " + describe(n, "generate.name"));
        int max = spd_max_size(db), materials = spd_material_count(db);
        int size = int(read_integer(required(j, "generate", "size", "a size"), "generate.size", 1, max,
                                    "a size from 1 to " + std::to_string(max) + " for " + spd_name(db)));
        if (int(d.world.materials.size()) < materials)
            fail("generate", std::string(spd_name(db)) + " needs " + std::to_string(materials) + " materials in \"materials\"");
        std::vector<int> ids;
        for (int m = 0; m < materials; ++m) ids.push_back(m);
        spd_generate(db, size, d.world, ids);
    }

    void read_mesh(scene_description& d, const json& j, const std::string& p) const {
        check_keys(j, p, {"vertices", "faces", "material", "obj"});
        if (auto* obj = member(j, "obj")) return read_obj(d, j, *obj, p);
        const json& vs = required(j, p, "vertices", "an array of points [[x, y, z], ...]");
        if (!vs.is_array() || vs.empty())
            fail(p + ".vertices", "expected a non-empty array of points [[x, y, z], ...], got " +
                                      describe(vs, p + ".vertices"));
        std::vector<vec3d> vertices;
        for (size_t i = 0; i < vs.size(); ++i)
            vertices.push_back(read_point(vs[i], p + ".vertices[" + std::to_string(i) + "]"));
        const json& fs = required(j, p, "faces", "an array of corner-index triples [[0, 1, 2], ...]");
        if (!fs.is_array() || fs.empty())
            fail(p + ".faces", "expected a non-empty array of index triples [[0, 1, 2], ...], got " +
                                   describe(fs, p + ".faces"));
        int material = read_material_ref(d, j, p);
        long long last = (long long)vertices.size() - 1;
        for (size_t i = 0; i < fs.size(); ++i) {
            std::string fp = p + ".faces[" + std::to_string(i) + "]";
            const json& f = fs[i];
            if (!f.is_array() || f.size() != 3)
                fail(fp, "expected three vertex indices [i, j, k], got " + describe(f, fp));
            int idx[3];
            for (int k = 0; k < 3; ++k)
                idx[k] = int(read_integer(f[size_t(k)], fp + "[" + std::to_string(k) + "]", 0, last,
                                          "a vertex index from 0 to " + std::to_string(last)));
            triangle<double> t{vertices[size_t(idx[0])], vertices[size_t(idx[1])], vertices[size_t(idx[2])], material};
            check_area(t.a, t.b, t.c, fp);
            d.world.triangles.push_back(t);
            if (size_t(d.world.object_count()) > max_objects) fail(fp, "more than 10 million objects in the scene");
        }
        ++d.mesh_count;
    }

    // {"obj": "bunny.obj"}: a path relative to the scene file's folder.
    void read_obj(scene_description& d, const json& j, const json& obj, const std::string& p) const {
        if (!obj.is_string()) fail(p + ".obj", "expected the path of an OBJ file, got " + describe(obj, p + ".obj"));
        if (member(j, "vertices") || member(j, "faces"))
            fail(p + ".obj", "a mesh is either an OBJ file or vertices and faces, not both");
        std::filesystem::path file = std::filesystem::path(source_).parent_path() / obj.get<std::string>();
        int material = read_material_ref(d, j, p);
        try {
            obj_mesh mesh = load_obj_mesh(file.string(), max_coordinate);
            for (auto& t : mesh.triangles) t.material = material;
            d.world.triangles.insert(d.world.triangles.end(), mesh.triangles.begin(), mesh.triangles.end());
        } catch (const obj_error& e) {
            fail(p + ".obj", e.what());
        }
        if (size_t(d.world.object_count()) > max_objects) fail(p + ".obj", "more than 10 million objects in the scene");
        ++d.mesh_count;
    }
};

// "[json.exception.parse_error.101] parse error at line 1, column 5: syntax
// error while parsing value - ..." -> "syntax error while parsing value - ...".
std::string syntax_problem(const std::string& what) {
    size_t column = what.find("column ");
    size_t colon = column == std::string::npos ? std::string::npos : what.find(": ", column);
    std::string problem = colon == std::string::npos ? what : what.substr(colon + 2);
    return problem.empty() ? "syntax error" : problem;
}

}  // namespace

scene_description parse_scene(const std::string& text, const std::string& source) {
    // nlohmann-json stops reading at a NUL byte and ignores the rest, which
    // would let garbage after it pass unseen: a scene file is text.
    if (size_t nul = text.find('\0'); nul != std::string::npos) {
        auto [line, column] = line_and_column(text, nul);
        throw scene_error(source, line, column, "", "a NUL byte: a scene file must be text");
    }
    // A UTF-8 byte-order mark is not part of the scene; dropping it keeps
    // line 1's columns the ones an editor shows.
    const std::string& body = text.compare(0, 3, "\xEF\xBB\xBF") == 0 ? text.substr(3) : text;
    json doc;
    try {
        doc = json::parse(body, nullptr, /*allow_exceptions=*/true, /*ignore_comments=*/true);
    } catch (const json::parse_error& e) {
        auto [line, column] = line_and_column(body, e.byte > 0 ? size_t(e.byte - 1) : 0);
        throw scene_error(source, line, column, "", "not valid JSON: " + syntax_problem(e.what()));
    } catch (const json::out_of_range&) {
        // A number too large for a double (such as 1e400): nlohmann-json
        // stops there without saying where, so the locator finds it.
        const locator where(body, source);
        where.fail_at_overflowing_number();
        throw scene_error(source, 0, 0, "", "not valid JSON: a number too large for a double");
    }
    return reader(body, source, doc).read();
}

scene_description load_scene_file(const std::string& path) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec))
        throw scene_error(path, 0, 0, "", std::filesystem::exists(path, ec) ? "not a regular file" : "no such file");
    std::ifstream in(path, std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    if (!in) throw scene_error(path, 0, 0, "", "cannot read the file");
    return parse_scene(text.str(), path);
}

}  // namespace rt
