// obj_mesh.cpp — OBJ files through tinyobjloader, checked (see obj_mesh.hpp).
#include "obj_mesh.hpp"

#include <tiny_obj_loader.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace rt {

obj_error::obj_error(const std::string& file, int line, const std::string& problem)
    : std::runtime_error(file + (line > 0 ? ":" + std::to_string(line) : std::string()) + ": " + problem),
      line_(line) {}

namespace {

// The 1-based line of the n-th (0-based) statement starting with `keyword`
// ("v" or "f"), for errors: tinyobjloader keeps no line numbers. Counts
// physical lines; a statement continued with a backslash counts as one.
int line_of_statement(const std::string& text, const std::string& keyword, size_t n) {
    std::istringstream in(text);
    std::string line;
    size_t seen = 0;
    for (int number = 1; std::getline(in, line); ++number) {
        size_t start = line.find_first_not_of(" \t");
        if (start == std::string::npos || line.compare(start, keyword.size(), keyword) != 0) continue;
        size_t after = start + keyword.size();
        if (after < line.size() && line[after] != ' ' && line[after] != '\t') continue;  // "vn", "vt"
        if (seen++ == n) return number;
    }
    return 0;
}

// Is `word` a decimal number, all of it, and finite? tinyobjloader reads
// "nan", "inf" or any other word as 0 without a word; so only digits, signs,
// a point and an exponent are let through, and strtod must take them all.
bool finite_number(const std::string& word) {
    if (word.find_first_not_of("0123456789+-.eE") != std::string::npos) return false;
    char* end = nullptr;
    const double x = std::strtod(word.c_str(), &end);
    return end == word.c_str() + word.size() && std::isfinite(x);
}

// Is `part` (one number of a face corner, "7" or "-2" of "7/3/-2") an
// integer that fits an int? tinyobjloader's own reading of a longer one
// overflows, and the wrapped number can land on a vertex that exists.
bool index_that_fits(const std::string& part) {
    const size_t digits = part.size() - (part[0] == '-' || part[0] == '+' ? 1 : 0);
    if (digits == 0 || digits > 9) return false;  // 9 digits: below 2^31
    return part.find_first_not_of("0123456789", part.size() - digits) == std::string::npos;
}

// Each number of one face corner ("i", "i/j", "i//k", "i/j/k").
void check_corner(const std::string& corner, const std::string& source, int line) {
    std::istringstream parts(corner);
    std::string part;
    for (int slot = 0; std::getline(parts, part, '/'); ++slot)
        if ((slot == 0 || !part.empty()) && !index_that_fits(part))
            throw obj_error(source, line,
                            "expected a vertex index (a whole number of at most 9 digits, from 1, or negative to count "
                            "from the end), got `" + corner + "`");
}

// What tinyobjloader would let through or misread, found first, here, with
// the line: a face of fewer than three corners (dropped without a word,
// which would also shift the face-to-line numbering used above), a corner
// index that is not a whole number that fits an int, and a vertex
// coordinate that is not a finite number.
void check_statements(const std::string& text, const std::string& source) {
    std::istringstream in(text);
    std::string line;
    for (int number = 1; std::getline(in, line); ++number) {
        std::istringstream words(line);
        std::string keyword, word;
        if (!(words >> keyword) || (keyword != "f" && keyword != "v")) continue;
        int count = 0;
        for (; words >> word && word[0] != '#'; ++count) {
            if (keyword == "f") check_corner(word, source, number);
            if (keyword == "v" && !finite_number(word))
                throw obj_error(source, number, "expected a finite number for a vertex coordinate, got `" + word + "`");
        }
        if (keyword == "f" && count < 3)
            throw obj_error(source, number, "a face needs at least three corners, got " + std::to_string(count));
    }
}

// tinyobjloader's messages end in newlines and may hold several lines.
std::string first_line(const std::string& message) {
    std::string s = message.substr(0, message.find('\n'));
    return s.empty() ? "not a valid OBJ file" : s;
}

}  // namespace

obj_mesh parse_obj_mesh(const std::string& text, const std::string& source, double max_coordinate) {
    check_statements(text, source);
    tinyobj::ObjReaderConfig config;
    config.triangulate = false;  // one face per `f` line, so errors can name the line
    config.vertex_color = false;
    tinyobj::ObjReader reader;
    // From a string, with no material text: an OBJ file's `mtllib` is not
    // read (materials come from the scene file).
    if (!reader.ParseFromString(text, "", config)) throw obj_error(source, 0, first_line(reader.Error()));

    obj_mesh mesh;
    const auto& v = reader.GetAttrib().vertices;
    mesh.vertices = v.size() / 3;
    for (size_t i = 0; i < v.size(); ++i)
        if (!(std::fabs(v[i]) <= max_coordinate))
            throw obj_error(source, line_of_statement(text, "v", i / 3),
                            "expected a finite coordinate of magnitude at most " + std::to_string(max_coordinate) +
                                ", got " + std::to_string(v[i]));
    auto corner = [&](int index) { return vec3d(v[3 * size_t(index)], v[3 * size_t(index) + 1], v[3 * size_t(index) + 2]); };

    for (const auto& shape : reader.GetShapes()) {
        size_t next = 0;  // first index of the current face
        for (unsigned corners : shape.mesh.num_face_vertices) {
            int line = 0;
            auto where = [&] { return line ? line : line = line_of_statement(text, "f", mesh.faces); };
            if (corners < 3) throw obj_error(source, where(), "a face needs at least three corners");
            for (unsigned k = 0; k < corners; ++k) {
                int index = shape.mesh.indices[next + k].vertex_index;
                if (index < 0 || size_t(index) >= mesh.vertices)
                    throw obj_error(source, where(),
                                    "a vertex index out of range (the file has " + std::to_string(mesh.vertices) +
                                        " vertices before or after this line, numbered from 1)");
            }
            // A fan from the first corner.
            for (unsigned k = 1; k + 1 < corners; ++k) {
                triangle<double> t{corner(shape.mesh.indices[next].vertex_index),
                                   corner(shape.mesh.indices[next + k].vertex_index),
                                   corner(shape.mesh.indices[next + k + 1].vertex_index), 0};
                if (length(cross(t.b - t.a, t.c - t.a)) > 0)
                    mesh.triangles.push_back(t);
                else
                    ++mesh.degenerate;
            }
            next += corners;
            ++mesh.faces;
        }
    }
    if (mesh.triangles.empty())
        throw obj_error(source, 0, mesh.faces ? "every face has zero area" : "no faces (`f` lines) in the file");
    return mesh;
}

obj_mesh load_obj_mesh(const std::string& path, double max_coordinate) {
    std::error_code ec;  // not a folder, a device or a pipe: those may never end
    if (!std::filesystem::is_regular_file(path, ec))
        throw obj_error(path, 0, std::filesystem::exists(path, ec) ? "not a regular file" : "cannot open the file (no such file)");
    std::ifstream in(path, std::ios::binary);
    if (!in) throw obj_error(path, 0, "cannot open the file");
    std::ostringstream text;
    text << in.rdbuf();
    return parse_obj_mesh(text.str(), path, max_coordinate);
}

}  // namespace rt
