// obj_mesh.hpp — triangle meshes from Wavefront OBJ files.
//
// The parsing is tinyobjloader's (Debian libtinyobjloader-dev); this file
// adds what a ray tracer needs on top: polygons split into triangles (a fan
// from the first corner: OBJ polygons are meant to be convex), every index
// checked, every coordinate finite and within the scene limits, and an
// error that names the file and the line for any of these.
//
// Triangles of zero area (common in scanned meshes: two corners equal) are
// left out and counted, since no ray can hit them and the course's triangle
// test divides by their area.
//
// Data only: nothing here intersects anything.
#pragma once

#include "shapes.hpp"

#include <stdexcept>
#include <string>
#include <vector>

namespace rt {

struct obj_mesh {
    std::vector<triangle<double>> triangles;  // material 0; the caller assigns its own
    size_t vertices = 0;                      // `v` statements read
    size_t faces = 0;                         // `f` statements read (before fan triangulation)
    size_t degenerate = 0;                    // zero-area triangles left out
};

// "FILE:LINE: PROBLEM" (LINE 0 when the error has no line, e.g. unreadable file).
class obj_error : public std::runtime_error {
public:
    obj_error(const std::string& file, int line, const std::string& problem);
    int line() const { return line_; }

private:
    int line_;
};

// Reads an OBJ file. Coordinates must be finite and at most max_coordinate
// in magnitude (the scene-file limit). Throws obj_error.
obj_mesh load_obj_mesh(const std::string& path, double max_coordinate = 1e15);

// The same from text already in memory; `source` names it in errors.
obj_mesh parse_obj_mesh(const std::string& text, const std::string& source, double max_coordinate = 1e15);

}  // namespace rt
