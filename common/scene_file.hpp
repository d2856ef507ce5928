// scene_file.hpp — reading a scene from a JSON file, with errors that point
// at the mistake.
//
// A scene file describes everything a picture needs: the camera, the
// background, materials, shapes and lights. The format is JSON (parsed by
// nlohmann-json); // and /* */ comments are allowed. scenes/README.md
// documents every field; in short:
//
//   {
//     "camera": {"type": "pinhole", "eye": [0, 1, 4], "look_at": [0, 0, 0],
//                "up": [0, 1, 0], "fov": 45, "width": 400, "height": 300},
//     "background": [0.5, 0.7, 1.0],
//     "ambient": [0.05, 0.05, 0.05],
//     "materials": [{"name": "red", "diffuse": [0.9, 0.1, 0.1]}],
//     "spheres":   [{"center": [0, 0, 0], "radius": 1, "material": "red"}],
//     "planes":    [{"point": [0, -1, 0], "normal": [0, 1, 0]}],
//     "triangles": [{"a": [0, 0, 0], "b": [1, 0, 0], "c": [0, 1, 0]}],
//     "meshes":    [{"vertices": [[0,0,0], [1,0,0], [0,1,0]], "faces": [[0, 1, 2]]}],
//     "lights":    [{"position": [5, 5, 5], "intensity": [20, 20, 20]}],
//     "objects":   {"tree": {"meshes": [{"obj": "tree.obj"}]}},
//     "instances": [{"object": "tree", "transform": {"translate": [2, 0, 0], "scale": 0.5}},
//                   {"scene": "room.json", "transform": {"rotate": {"axis": [0, 1, 0], "degrees": 30}}}]
//   }
//
// Why so strict: a typo such as "raduis" would otherwise be ignored and the
// sphere silently given a default radius; a student then debugs their
// intersection code for a mistake that is in the scene. So every key is
// checked, and a bad file is rejected with an error that names the file,
// the line and column, the field, and what was expected:
//
//   scenes/bad.json:7:38: spheres[1].radius: expected a number > 0, got -2
//
// This file is data only: nothing here intersects or shades anything.
#pragma once

#include "camera.hpp"
#include "instances.hpp"
#include "interval.hpp"
#include "scene.hpp"

#include <stdexcept>
#include <string>
#include <vector>

namespace rt {

// What a scene file says about the camera, before it is built in a
// particular precision.
struct camera_description {
    enum class kind { pinhole, orthographic };
    kind type = kind::pinhole;
    vec3d eye{0, 0, 0};
    vec3d look_at{0, 0, -1};
    vec3d up{0, 1, 0};
    double fov_degrees = 45;   // pinhole: vertical field of view
    double view_height = 2;    // orthographic: height of the view rectangle
    double aperture = 0;       // pinhole: radius of a thin lens around the eye (chapter 11); 0 is a pinhole
    double focus_distance = 0; // pinhole with a lens: distance of the sharp plane; 0 means |look_at - eye|
    int width = 400, height = 300;
};

// A parsed scene file. Shapes are kept in double, as written; convert_scene
// gives the same scene in float for single-precision rendering.
//
// Instances (instances.hpp): `world` holds the shapes written at the top
// level, `instances` what the top level places, each an object of
// `objects` (in its own coordinates, with instances of its own). A scene
// without instances has both empty, and `world` is the whole scene.
struct scene_description {
    std::string source;                    // file name, for messages
    camera_description camera;
    scene<double> world;
    std::vector<std::string> material_names;  // parallel to world.materials ("" when unnamed or from a placed file)
    int mesh_count = 0;                    // meshes are stored as their triangles
    std::vector<object_definition> objects;   // what instances place (named, written in place, files, generated)
    std::vector<instance_placement> instances;  // the top level's instances
};

// The error for a bad scene file. what() is the whole message,
// "FILE:LINE:COLUMN: FIELD: PROBLEM"; the parts are kept for tests and tools.
class scene_error : public std::runtime_error {
public:
    scene_error(std::string file, int line, int column, std::string field, std::string problem);
    const std::string& file() const { return file_; }
    int line() const { return line_; }      // 1-based; 0 when the error has no place (e.g. unreadable file)
    int column() const { return column_; }  // 1-based, counted in bytes
    const std::string& field() const { return field_; }  // e.g. "spheres[1].radius"; "" for syntax errors
    const std::string& problem() const { return problem_; }

private:
    std::string file_, field_, problem_;
    int line_, column_;
};

// Limits the parser enforces so any file that passes can be rendered in
// float without overflow: every coordinate and size is at most
// max_coordinate in magnitude, so squares of differences (up to about
// 4e30) stay below float's largest value (3.4e38).
inline constexpr double max_coordinate = 1e15;
inline constexpr int max_image_side = 16384;
inline constexpr size_t max_objects = 10'000'000;

// Parses scene text; `source` names it in error messages. Throws scene_error.
scene_description parse_scene(const std::string& text, const std::string& source);

// Reads and parses a scene file. Throws scene_error (also when the file
// cannot be read).
scene_description load_scene_file(const std::string& path);

// The same scene in another precision (coordinates rounded to T).
template <class T>
scene<T> convert_scene(const scene<double>& s) {
    scene<T> out;
    for (const auto& x : s.spheres) out.spheres.push_back({convert<T>(x.center), T(x.radius), x.material});
    for (const auto& x : s.planes) out.planes.push_back({convert<T>(x.point), convert<T>(x.normal), x.material});
    for (const auto& x : s.triangles)
        out.triangles.push_back({convert<T>(x.a), convert<T>(x.b), convert<T>(x.c), x.material});
    out.materials = s.materials;
    out.lights = s.lights;
    out.ambient = s.ambient;
    out.background = s.background;
    return out;
}

// Either of the course's two cameras, chosen by the scene file.
template <class T>
struct scene_camera {
    camera_description::kind type = camera_description::kind::pinhole;
    pinhole_camera<T> pinhole;
    orthographic_camera<T> orthographic;

    // width and height override the file's resolution when positive.
    // Throws std::invalid_argument for a degenerate camera.
    explicit scene_camera(const camera_description& d, int width = 0, int height = 0) : type(d.type) {
        int w = width > 0 ? width : d.width, h = height > 0 ? height : d.height;
        auto frame = camera_frame<T>::look_at(convert<T>(d.eye), convert<T>(d.look_at), convert<T>(d.up));
        if (type == camera_description::kind::pinhole)
            pinhole = pinhole_camera<T>(frame, T(d.fov_degrees), w, h);
        else
            orthographic = orthographic_camera<T>(frame, T(d.view_height), w, h);
    }

    int width() const { return type == camera_description::kind::pinhole ? pinhole.width : orthographic.width; }
    int height() const { return type == camera_description::kind::pinhole ? pinhole.height : orthographic.height; }

    ray<T> primary_ray(int col, int row) const {
        return type == camera_description::kind::pinhole ? pinhole.primary_ray(col, row)
                                                         : orthographic.primary_ray(col, row);
    }

    // Where a primary ray's hits may lie: beyond the image plane, which is at
    // t = 1 for the pinhole camera and at t = 0 for the orthographic one.
    interval<T> primary_range() const {
        return type == camera_description::kind::pinhole ? interval<T>::in_front_of_image_plane()
                                                         : interval<T>{T(0), infinity<T>};
    }
};

}  // namespace rt
