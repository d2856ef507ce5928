// cornell_box.hpp — the chapter's scene: scenes/ch12-cornell-box.json.
//
// A Cornell box lit by one sphere light (the file says what is where). The
// file is compiled into the program (common/chapter_scenes.hpp), so the
// picture and the tests see the same box wherever they run; editing the file
// and rebuilding changes both.
#pragma once

#include "path_scene.hpp"

#include "common/chapter_scenes.hpp"
#include "common/scene_file.hpp"

namespace rt::ch12 {

// The chapter's scene file, read and checked.
inline scene_description cornell_box_file() {
    const chapter_scene own = chapter_scene_file("ch12");
    return parse_scene(own.text, own.source);
}

// The box as the path tracer sees it: the lamp is sphere 0, the large white
// ball sphere 1 (on the left), the small one sphere 2.
template <class T>
path_scene<T> cornell_box() {
    return path_scene_of<T>(cornell_box_file());
}

}  // namespace rt::ch12
