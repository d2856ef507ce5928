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

    // Line and column of the value at path (of the document when unknown).
    std::pair<int, int> position(const std::string& path) const { return line_and_column(text_, value_at(path)); }

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

// The scene files being read, outermost first: a file placed by one of them
// (an instance's "scene") is read with the same chain, so a file that places
// itself, directly or through others, is found.
struct file_chain {
    std::vector<std::string> files;  // canonical paths
    std::vector<std::string> shown;  // as written, for messages
};

scene_description parse_in_chain(const std::string& text, const std::string& source, file_chain& chain);

// The keys that say what an object holds, in "objects" and in an instance.
const std::vector<std::string> definition_keys = {"spheres", "planes", "triangles", "meshes", "instances", "generate",
                                                  "scene"};

// Instances nested deeper than this are refused: the renderers walk them by
// recursion, and no scene needs more (the level-12 sphereflake is 13 deep).
constexpr int max_nesting = 64;

// Checks one JSON document against the scene format and builds the scene.
class reader {
public:
    reader(const std::string& text, const std::string& source, const json& doc, file_chain& chain)
        : source_(source), doc_(doc), where_(text, source), chain_(chain) {}

    scene_description read() {
        scene_description d;
        d.source = source_;
        if (!doc_.is_object()) fail("", "expected the scene to be a JSON object { ... }, got " + describe(doc_, ""));
        check_keys(doc_, "", {"description", "camera", "background", "ambient", "materials", "spheres", "planes",
                              "triangles", "meshes", "lights", "generate", "objects", "instances"});
        if (auto* j = member(doc_, "description"); j && !j->is_string())
            fail("description", "expected a string, got " + describe(*j, "description"));
        d.camera = read_camera(required(doc_, "", "camera", "an object describing the camera"), "camera");
        if (auto* j = member(doc_, "background")) d.world.background = read_color(*j, "background");
        if (auto* j = member(doc_, "ambient")) d.world.ambient = read_color(*j, "ambient");
        read_materials(d);
        own_materials_ = int(d.world.materials.size());
        object_definition top;
        read_shapes(d, doc_, "", top);
        read_list(doc_, "", "lights", [&](const json& j, const std::string& p) {
            check_keys(j, p, {"position", "intensity", "radius"});
            point_light light;
            light.position = read_point(required(j, p, "position", "a point [x, y, z]"), p + ".position");
            if (auto* i = member(j, "intensity")) light.intensity = read_color(*i, p + ".intensity");
            if (auto* r = member(j, "radius"))
                light.radius = read_number_in(*r, p + ".radius", 0, false, max_coordinate,
                                              "a radius >= 0 (0 for a point light, above 0 for a sphere light, chapter 11)");
            d.world.lights.push_back(light);
        });
        read_named_objects(d);
        read_list(doc_, "", "instances", [&](const json& j, const std::string& p) { read_instance(d, j, p, top); });
        if (auto* g = member(doc_, "generate")) read_generate(d, *g, "generate", top);  // last: may pass max_objects
        d.world.spheres = std::move(top.spheres);
        d.world.planes = std::move(top.planes);
        d.world.triangles = std::move(top.triangles);
        d.instances = std::move(top.instances);
        check_nesting(d);
        return d;
    }

private:
    const std::string& source_;
    const json& doc_;
    locator where_;
    file_chain& chain_;
    int own_materials_ = 0;             // this file's materials; those of files it places follow
    size_t written_ = 0;                // shapes written in the file (generated ones are not limited)
    std::map<std::string, int> named_;  // "objects" read so far: name -> index in scene_description::objects
    std::vector<std::string> resolving_;  // the named objects being read, outermost first (to find a cycle)
    std::map<std::string, int> files_;  // scene files placed so far: canonical path -> object

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

    // A colour that is a fraction of the light arriving (a diffuse or checker
    // colour, a mirror's share): more than all of it would make every bounce
    // brighter than the last (chapters 09 and 12 follow light over many).
    color read_reflectance(const json& j, const std::string& path) const {
        const color c = read_color(j, path);
        for (int k = 0; k < 3; ++k)
            if (!(c[k] <= 1.0f))
                fail(path + "[" + std::to_string(k) + "]",
                     "expected a fraction from 0 to 1, got " + where_.token_at(path + "[" + std::to_string(k) + "]"));
        return c;
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
                                                              "(chapter 11): an orthographic camera has no lens");
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
            check_keys(j, p, {"name", "diffuse", "specular", "shininess", "checker", "mirror", "ior", "emission"});
            material m;
            std::string name;
            if (auto* n = member(j, "name")) {
                if (!n->is_string()) fail(p + ".name", "expected a string, got " + describe(*n, p + ".name"));
                name = n->get<std::string>();
                if (std::find(d.material_names.begin(), d.material_names.end(), name) != d.material_names.end())
                    fail(p + ".name", "two materials are named \"" + name + "\"; names must be unique");
            }
            if (auto* c = member(j, "diffuse")) m.diffuse = read_reflectance(*c, p + ".diffuse");
            if (auto* c = member(j, "specular")) m.specular = read_color(*c, p + ".specular");
            if (auto* s = member(j, "shininess"))
                m.shininess = float(read_number_in(*s, p + ".shininess", 0, false, 10000, "a number from 0 to 10000"));
            if (auto* c = member(j, "checker")) {
                m.checker = true;
                m.checker_color = read_reflectance(*c, p + ".checker");
            }
            if (auto* c = member(j, "mirror")) m.mirror = read_reflectance(*c, p + ".mirror");
            if (auto* c = member(j, "emission")) m.emission = read_color(*c, p + ".emission");
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
        int count = own_materials_;
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

    // parent[key], a list, each element read by read_one(element, its path).
    template <class F>
    void read_list(const json& parent, const std::string& parent_path, const std::string& key, F&& read_one) const {
        const json* list = member(parent, key);
        if (!list) return;
        const std::string path = child(parent_path, key);
        if (!list->is_array()) fail(path, "expected an array [ {...}, ... ], got " + describe(*list, path));
        for (size_t i = 0; i < list->size(); ++i) read_one((*list)[i], path + "[" + std::to_string(i) + "]");
    }

    // Counts shapes written in the file, refusing more than max_objects.
    void count_written(size_t n, const std::string& path) {
        written_ += n;
        if (written_ > max_objects) fail(path, "more than 10 million objects in the scene");
    }

    // The shapes an object (or the scene itself) writes out: spheres,
    // planes, triangles and meshes of j, into target.
    void read_shapes(scene_description& d, const json& j, const std::string& path, object_definition& target) {
        read_list(j, path, "spheres", [&](const json& x, const std::string& p) { read_sphere(d, x, p, target); });
        read_list(j, path, "planes", [&](const json& x, const std::string& p) { read_plane(d, x, p, target); });
        read_list(j, path, "triangles", [&](const json& x, const std::string& p) { read_triangle(d, x, p, target); });
        read_list(j, path, "meshes", [&](const json& x, const std::string& p) { read_mesh(d, x, p, target); });
    }

    // What an object in "objects" or an instance written in place holds:
    // shapes, instances, a generated database, another scene file.
    void read_definition(scene_description& d, const json& j, const std::string& path, object_definition& target) {
        read_shapes(d, j, path, target);
        read_list(j, path, "instances", [&](const json& x, const std::string& p) { read_instance(d, x, p, target); });
        if (auto* g = member(j, "generate")) read_generate(d, *g, child(path, "generate"), target);
        if (auto* f = member(j, "scene")) target.instances.push_back(identity_placement(file_object(d, *f, child(path, "scene")), path));
    }

    instance_placement identity_placement(int object, const std::string& path) const {
        return {object, affine_transform{}, affine_transform{}, source_ + ": " + path};
    }

    // A new object: its slot is taken first, so that the objects it places
    // (read while it is read) come after it and its index stays put.
    template <class F>
    int new_object(scene_description& d, const std::string& name, F&& fill) {
        const int index = int(d.objects.size());
        d.objects.emplace_back();
        object_definition body;
        body.name = name;
        fill(body);
        d.objects[size_t(index)] = std::move(body);
        return index;
    }

    // "objects": {"name": {...}, ...}: every one is read (so a mistake in an
    // object nothing places yet is still found), each once, however often placed.
    void read_named_objects(scene_description& d) {
        const json* objects = member(doc_, "objects");
        if (!objects) return;
        if (!objects->is_object())
            fail("objects", "expected an object {\"name\": {...}, ...} of named objects, got " + describe(*objects, "objects"));
        for (auto it = objects->begin(); it != objects->end(); ++it) named_object(d, it.key(), "objects." + it.key());
    }

    int named_object(scene_description& d, const std::string& name, const std::string& asked_at) {
        if (auto it = named_.find(name); it != named_.end()) return it->second;
        const json* objects = member(doc_, "objects");
        if (!objects || !objects->is_object() || !objects->contains(name)) {
            std::vector<std::string> names;
            if (objects && objects->is_object())
                for (auto it = objects->begin(); it != objects->end(); ++it) names.push_back("\"" + it.key() + "\"");
            fail(asked_at, "no object is named \"" + name + "\" (" +
                               (names.empty() ? std::string("the file has no \"objects\"") : "the names are " + join(names)) + ")");
        }
        if (std::find(resolving_.begin(), resolving_.end(), name) != resolving_.end()) {
            std::string cycle;
            for (auto it = std::find(resolving_.begin(), resolving_.end(), name); it != resolving_.end(); ++it)
                cycle += "\"" + *it + "\" -> ";
            fail(asked_at, "the object \"" + name + "\" places itself (" + cycle + "\"" + name +
                               "\"): an object cannot be one of its own parts");
        }
        const std::string path = "objects." + name;
        const json& j = (*objects)[name];
        check_keys(j, path, definition_keys);
        resolving_.push_back(name);
        const int index = new_object(d, path, [&](object_definition& body) { read_definition(d, j, path, body); });
        resolving_.pop_back();
        named_[name] = index;
        return index;
    }

    // An instance: {"object": NAME} or an object written in place (any of
    // definition_keys), with an optional "transform"; placed into target.
    void read_instance(scene_description& d, const json& j, const std::string& p, object_definition& target) {
        std::vector<std::string> keys = definition_keys;
        keys.push_back("object");
        keys.push_back("transform");
        check_keys(j, p, keys);
        std::vector<std::string> written;
        for (const auto& k : definition_keys)
            if (member(j, k)) written.push_back(k);
        const json* name = member(j, "object");
        if (name && !written.empty())
            where_.fail_at_key(child(p, written[0]),
                               "an instance places either a named object (\"object\") or one written in place "
                               "(shapes, \"instances\", \"generate\", \"scene\"), not both");
        if (!name && written.empty())
            fail(p, "missing what to place: \"object\" (a name from \"objects\"), or shapes, \"instances\", "
                    "\"generate\" or \"scene\" written in place");
        int object;
        if (name) {
            if (!name->is_string())
                fail(p + ".object", "expected the name of an object in \"objects\", got " + describe(*name, p + ".object"));
            object = named_object(d, name->get<std::string>(), p + ".object");
        } else if (written.size() == 1 && written[0] == "scene") {
            object = file_object(d, *member(j, "scene"), p + ".scene");  // the file's object itself: one level less
        } else {
            object = new_object(d, source_ + ": " + p, [&](object_definition& body) { read_definition(d, j, p, body); });
        }
        place(object, member(j, "transform"), p, target);
    }

    // Places object into target, by the transform at p.transform (identity without one).
    void place(int object, const json* transform, const std::string& p, object_definition& target) const {
        const affine_transform t = transform ? read_transform(*transform, p + ".transform") : affine_transform{};
        target.instances.push_back({object, t, inverted(t), source_ + ": " + p});
    }

    // "scene": "other.json": the other file's shapes, instances and
    // materials (its camera and lights are not used), read once however
    // often it is placed. Its path is relative to this file's folder.
    int file_object(scene_description& d, const json& name, const std::string& path) {
        if (!name.is_string()) fail(path, "expected the path of a scene file, got " + describe(name, path));
        const std::filesystem::path file = std::filesystem::path(source_).parent_path() / name.get<std::string>();
        std::error_code ec;
        std::string key = std::filesystem::weakly_canonical(file, ec).string();
        if (ec) key = file.lexically_normal().string();
        if (auto it = files_.find(key); it != files_.end()) return it->second;
        if (auto it = std::find(chain_.files.begin(), chain_.files.end(), key); it != chain_.files.end()) {
            std::string cycle;
            for (size_t i = size_t(it - chain_.files.begin()); i < chain_.shown.size(); ++i) cycle += chain_.shown[i] + " -> ";
            fail(path, "the scene file " + file.string() + " places itself (" + cycle + file.string() +
                           "): a scene cannot be one of its own parts");
        }
        scene_description placed;
        try {
            std::ifstream in(file, std::ios::binary);
            if (!std::filesystem::is_regular_file(file, ec) || !in)
                fail(path, "cannot read the scene file " + file.string() +
                               (std::filesystem::exists(file, ec) ? "" : ": no such file"));
            std::ostringstream text;
            text << in.rdbuf();
            chain_.files.push_back(key);
            chain_.shown.push_back(file.string());
            placed = parse_in_chain(text.str(), file.string(), chain_);
            chain_.files.pop_back();
            chain_.shown.pop_back();
        } catch (const scene_error& e) {
            if (e.file() == source_) throw;  // this file's own error (raised just above)
            // The placed file's own message, and where it was placed from.
            const auto [line, column] = where_.position(path);
            throw scene_error(e.file(), e.line(), e.column(), e.field(),
                              e.problem() + " (in the scene file placed at " + source_ + ":" + std::to_string(line) +
                                  ":" + std::to_string(column) + ")");
        }
        const int index = merge_placed_file(d, std::move(placed), file.string());
        files_[key] = index;
        return index;
    }

    // The placed file's materials follow this scene's; its objects follow
    // this scene's objects; its top level becomes one object.
    static int merge_placed_file(scene_description& d, scene_description placed, const std::string& name) {
        const int material_base = int(d.world.materials.size()), object_base = int(d.objects.size());
        for (const auto& m : placed.world.materials) {
            d.world.materials.push_back(m);
            d.material_names.push_back("");  // its names are its own: this file cannot refer to them
        }
        auto renumber = [&](object_definition& o) {
            for (auto& x : o.spheres) x.material += material_base;
            for (auto& x : o.planes) x.material += material_base;
            for (auto& x : o.triangles) x.material += material_base;
            for (auto& i : o.instances) i.object += object_base;
        };
        for (auto& o : placed.objects) {
            renumber(o);
            d.objects.push_back(std::move(o));
        }
        object_definition whole;
        whole.name = name;
        whole.spheres = std::move(placed.world.spheres);
        whole.planes = std::move(placed.world.planes);
        whole.triangles = std::move(placed.world.triangles);
        whole.instances = std::move(placed.instances);
        renumber(whole);
        d.objects.push_back(std::move(whole));
        d.mesh_count += placed.mesh_count;
        return int(d.objects.size()) - 1;
    }

    void check_nesting(const scene_description& d) const {
        const std::vector<int> depth = nesting_depths(d.objects);
        int deepest = 0;
        for (const auto& i : d.instances) deepest = std::max(deepest, 1 + depth[size_t(i.object)]);
        if (deepest > max_nesting)
            fail(member(doc_, "objects") ? "objects" : "instances",
                 "instances are nested " + std::to_string(deepest) + " deep; at most " + std::to_string(max_nesting) +
                     " levels are allowed");
    }

    // ---- transforms ----

    // A transform: {"translate": ..., "rotate": ..., "scale": ...} (scale
    // first, then rotate, then translate), {"matrix": [[...], [...], [...]]},
    // or a list of these applied first to last. Refused when singular.
    affine_transform read_transform(const json& j, const std::string& path) const {
        affine_transform t;
        if (j.is_array()) {
            if (j.empty()) fail(path, "expected a transform or a list of transforms, got an empty array");
            for (size_t i = 0; i < j.size(); ++i) t = then(t, read_one_transform(j[i], path + "[" + std::to_string(i) + "]"));
        } else {
            t = read_one_transform(j, path);
        }
        check_invertible(t, path);
        return t;
    }

    affine_transform read_one_transform(const json& j, const std::string& path) const {
        check_keys(j, path, {"translate", "rotate", "scale", "matrix"});
        if (auto* m = member(j, "matrix")) {
            for (const char* other : {"translate", "rotate", "scale"})
                if (member(j, other))
                    where_.fail_at_key(child(path, other),
                                       "a matrix is a whole transform: give translate, rotate and scale as transforms "
                                       "of their own in a list [ {...}, {...} ], or fold them into the matrix");
            return read_matrix(*m, path + ".matrix");
        }
        if (j.empty()) fail(path, "expected \"translate\", \"rotate\", \"scale\" or \"matrix\", got an empty object");
        mat3d scale(1.0), rotation(1.0);
        vec3d offset(0.0);
        if (auto* s = member(j, "scale")) scale = read_scale(*s, path + ".scale");
        if (auto* r = member(j, "rotate")) rotation = read_rotation(*r, path + ".rotate");
        if (auto* t = member(j, "translate")) offset = read_point(*t, path + ".translate");
        return {rotation * scale, offset};
    }

    // [[a, b, c, tx], [d, e, f, ty], [g, h, i, tz]]: rows, the last column the translation.
    affine_transform read_matrix(const json& j, const std::string& path) const {
        const std::string what = "a 3x4 matrix [[a, b, c, tx], [d, e, f, ty], [g, h, i, tz]] (rows; the last column moves)";
        if (!j.is_array() || j.size() != 3) fail(path, "expected " + what + ", got " + describe(j, path));
        affine_transform t;
        for (size_t row = 0; row < 3; ++row) {
            const std::string rp = path + "[" + std::to_string(row) + "]";
            const json& r = j[row];
            if (!r.is_array() || r.size() != 4) fail(rp, "expected a row of 4 numbers (part of " + what + "), got " + describe(r, rp));
            for (size_t col = 0; col < 4; ++col) {
                const std::string ep = rp + "[" + std::to_string(col) + "]";
                const double x = read_number(r[col], ep);
                if (!(std::fabs(x) <= max_coordinate))
                    fail(ep, "expected a matrix entry of magnitude at most 1e15, got " + where_.token_at(ep));
                if (col < 3) t.linear[int(col)][int(row)] = x;  // GLM: [column][row]
                else t.offset[int(row)] = x;
            }
        }
        return t;
    }

    // A number (the same in every direction) or [sx, sy, sz], none zero.
    mat3d read_scale(const json& j, const std::string& path) const {
        vec3d s;
        if (j.is_number()) s = vec3d(read_number(j, path));
        else s = read_triple(j, path, "a scale: a number, or [sx, sy, sz]");
        for (int i = 0; i < 3; ++i) {
            const std::string at = j.is_number() ? path : path + "[" + std::to_string(i) + "]";
            if (!(s[i] != 0 && std::fabs(s[i]) <= max_coordinate && std::fabs(s[i]) >= 1 / max_coordinate))
                fail(at, "expected a scale factor of magnitude from 1e-15 to 1e15 (a zero scale would flatten the "
                         "object: the transform would be singular), got " + where_.token_at(at));
        }
        mat3d m(1.0);
        m[0][0] = s.x, m[1][1] = s.y, m[2][2] = s.z;
        return m;
    }

    // {"axis": [x, y, z], "degrees": a}: counter-clockwise by a seen from
    // where the axis points (right-handed), Rodrigues' formula.
    mat3d read_rotation(const json& j, const std::string& path) const {
        check_keys(j, path, {"axis", "degrees"});
        const vec3d axis = normalize(read_direction(required(j, path, "axis", "the axis [x, y, z]"), path + ".axis"));
        const double degrees = read_number_in(required(j, path, "degrees", "the angle in degrees"), path + ".degrees",
                                              -1e6, false, 1e6, "an angle in degrees from -1e6 to 1e6");
        const double radians = degrees * (std::acos(-1.0) / 180.0);
        const double c = std::cos(radians), s = std::sin(radians);
        mat3d k(0.0);  // the cross-product matrix of the axis: k * v = axis x v
        k[1][0] = -axis.z, k[2][0] = axis.y;  // GLM: k[column][row]
        k[0][1] = axis.z, k[2][1] = -axis.x;
        k[0][2] = -axis.y, k[1][2] = axis.x;
        return mat3d(1.0) + s * k + (1 - c) * (k * k);
    }

    // Invertible, and not so nearly singular that its inverse means nothing:
    // |det| against the product of the columns' lengths (Hadamard's bound,
    // equal to |det| for perpendicular columns, whatever their lengths).
    void check_invertible(const affine_transform& t, const std::string& path) const {
        const double det = glm::determinant(t.linear);
        const double bound = length(t.linear[0]) * length(t.linear[1]) * length(t.linear[2]);
        const affine_transform inverse = inverted(t);
        bool finite = is_finite(inverse.offset);
        for (int c = 0; c < 3; ++c) finite = finite && is_finite(inverse.linear[c]);
        if (!(std::fabs(det) > 1e-12 * bound) || !finite) {
            std::ostringstream what;
            what << "expected an invertible transform, got a singular matrix (determinant " << det
                 << "): it flattens the object onto a plane, a line or a point, so no ray can be moved into its space";
            fail(path, what.str());
        }
    }

    // A shape with a "transform" is placed as an instance of an object that
    // holds it alone (a sphere under a non-uniform scale is an ellipsoid).
    object_definition& holder(scene_description& d, const json& j, const std::string& p, object_definition& target,
                              object_definition& alone) const {
        (void)d, (void)p;
        return member(j, "transform") ? alone : target;
    }
    void place_alone(scene_description& d, const json& j, const std::string& p, object_definition& target,
                     object_definition&& alone) {
        if (!member(j, "transform")) return;
        alone.name = source_ + ": " + p;
        const int index = int(d.objects.size());
        d.objects.push_back(std::move(alone));
        place(index, member(j, "transform"), p, target);
    }

    void read_sphere(scene_description& d, const json& j, const std::string& p, object_definition& target) {
        check_keys(j, p, {"center", "radius", "material", "transform"});
        sphere<double> s;
        s.center = read_point(required(j, p, "center", "the centre [x, y, z]"), p + ".center");
        s.radius = read_number_in(required(j, p, "radius", "a number > 0"), p + ".radius", 0, true, max_coordinate,
                                  "a radius > 0 (and at most 1e15)");
        if (!(float(s.radius) > 0.0f))
            fail(p + ".radius", "the radius " + where_.token_at(p + ".radius") + " rounds to 0 in float");
        s.material = read_material_ref(d, j, p);
        count_written(1, p);
        object_definition alone;
        holder(d, j, p, target, alone).spheres.push_back(s);
        place_alone(d, j, p, target, std::move(alone));
    }

    void read_plane(scene_description& d, const json& j, const std::string& p, object_definition& target) {
        check_keys(j, p, {"point", "normal", "material"});
        plane<double> s;
        s.point = read_point(required(j, p, "point", "a point on the plane [x, y, z]"), p + ".point");
        s.normal = read_direction(required(j, p, "normal", "the plane's normal [x, y, z], not zero"), p + ".normal");
        s.material = read_material_ref(d, j, p);
        count_written(1, p);
        target.planes.push_back(s);
    }

    void check_area(const vec3d& a, const vec3d& b, const vec3d& c, const std::string& p) const {
        if (!(length(cross(b - a, c - a)) > 0))
            fail(p, "the corners " + format_vector(a) + ", " + format_vector(b) + ", " + format_vector(c) +
                        " lie on one line: the triangle has zero area");
    }

    void read_triangle(scene_description& d, const json& j, const std::string& p, object_definition& target) {
        check_keys(j, p, {"a", "b", "c", "material"});
        triangle<double> t;
        t.a = read_point(required(j, p, "a", "the first corner [x, y, z]"), p + ".a");
        t.b = read_point(required(j, p, "b", "the second corner [x, y, z]"), p + ".b");
        t.c = read_point(required(j, p, "c", "the third corner [x, y, z]"), p + ".c");
        check_area(t.a, t.b, t.c, p);
        t.material = read_material_ref(d, j, p);
        count_written(1, p);
        target.triangles.push_back(t);
    }

    // "generate": {"name": "balls", "size": 4, "instanced": true}: one of the
    // Standard Procedural Databases (common/spd.hpp), its materials 0, 1
    // being the scene's first materials; instanced: as instances of
    // instances (balls and tetra).
    void read_generate(scene_description& d, const json& j, const std::string& path, object_definition& target) const {
        check_keys(j, path, {"name", "size", "instanced"});
        const json& n = required(j, path, "name", "\"balls\", \"tetra\" or \"mount\"");
        spd_database db;
        if (!n.is_string() || !spd_from_name(n.get<std::string>(), db))
            fail(path + ".name", "expected \"balls\", \"tetra\" or \"mount\", got " + describe(n, path + ".name"));
        bool instanced = false;
        if (auto* i = member(j, "instanced")) {
            if (!i->is_boolean()) fail(path + ".instanced", "expected true or false, got " + describe(*i, path + ".instanced"));
            instanced = i->get<bool>();
            if (instanced && spd_max_instanced_size(db) == 0)
                fail(path + ".instanced", std::string(spd_name(db)) +
                                              " is not self-similar, so it has no instanced form (balls and tetra have)");
        }
        int max = instanced ? spd_max_instanced_size(db) : spd_max_size(db), materials = spd_material_count(db);
        int size = int(read_integer(required(j, path, "size", "a size"), path + ".size", 1, max,
                                    "a size from 1 to " + std::to_string(max) + " for " + spd_name(db) +
                                        (instanced ? " (instanced)" : "")));
        if (own_materials_ < materials)
            fail(path, std::string(spd_name(db)) + " needs " + std::to_string(materials) + " materials in \"materials\"");
        std::vector<int> ids;
        for (int m = 0; m < materials; ++m) ids.push_back(m);
        if (instanced) {
            spd_generate_instanced(db, size, target, d.objects, ids);
            return;
        }
        scene<double> shapes;
        spd_generate(db, size, shapes, ids);
        auto append = [](auto& to, auto& from) {
            if (to.empty()) to = std::move(from);
            else to.insert(to.end(), from.begin(), from.end());
        };
        append(target.spheres, shapes.spheres);
        append(target.planes, shapes.planes);
        append(target.triangles, shapes.triangles);
    }

    void read_mesh(scene_description& d, const json& j, const std::string& p, object_definition& target) {
        check_keys(j, p, {"vertices", "faces", "material", "obj", "transform"});
        object_definition alone;
        object_definition& into = holder(d, j, p, target, alone);
        if (auto* obj = member(j, "obj")) {
            read_obj(d, j, *obj, p, into);
        } else {
            read_mesh_lists(d, j, p, into);
        }
        ++d.mesh_count;
        place_alone(d, j, p, target, std::move(alone));
    }

    void read_mesh_lists(scene_description& d, const json& j, const std::string& p, object_definition& into) {
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
            into.triangles.push_back(t);
            count_written(1, fp);
        }
    }

    // {"obj": "bunny.obj"}: a path relative to the scene file's folder.
    void read_obj(scene_description& d, const json& j, const json& obj, const std::string& p, object_definition& into) {
        if (!obj.is_string()) fail(p + ".obj", "expected the path of an OBJ file, got " + describe(obj, p + ".obj"));
        if (member(j, "vertices") || member(j, "faces"))
            fail(p + ".obj", "a mesh is either an OBJ file or vertices and faces, not both");
        std::filesystem::path file = std::filesystem::path(source_).parent_path() / obj.get<std::string>();
        int material = read_material_ref(d, j, p);
        try {
            obj_mesh mesh = load_obj_mesh(file.string(), max_coordinate);
            for (auto& t : mesh.triangles) t.material = material;
            into.triangles.insert(into.triangles.end(), mesh.triangles.begin(), mesh.triangles.end());
            count_written(mesh.triangles.size(), p + ".obj");
        } catch (const obj_error& e) {
            fail(p + ".obj", e.what());
        }
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

namespace {

scene_description parse_in_chain(const std::string& text, const std::string& source, file_chain& chain) {
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
    return reader(body, source, doc, chain).read();
}

// The chain a file starts: itself, so that it cannot place itself.
file_chain chain_of(const std::string& source) {
    file_chain chain;
    std::error_code ec;
    const std::string key = std::filesystem::weakly_canonical(source, ec).string();
    chain.files.push_back(ec ? std::filesystem::path(source).lexically_normal().string() : key);
    chain.shown.push_back(source);
    return chain;
}

}  // namespace

scene_description parse_scene(const std::string& text, const std::string& source) {
    file_chain chain = chain_of(source);
    return parse_in_chain(text, source, chain);
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
