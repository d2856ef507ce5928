// chapter_scenes.hpp — the chapters' own scene files, built into the programs.
//
// Chapters 03 on draw the scene in scenes/chNN-*.json: a scene is data, so
// no chapter program builds one in C++. The files are compiled into the
// library (common/CMakeLists.txt writes them into a generated source file),
// so a chapter program renders its picture wherever it runs, even where it
// cannot read the source tree (the autograder's sandbox).
#pragma once

#include <string>

namespace rt {

struct chapter_scene {
    std::string source;  // "scenes/ch03-overlapping-spheres.json", for messages
    std::string text;    // the file's contents
};

// The scene file of chapter `id` ("ch03"): the one scenes/ file named
// "<id>-*.json". Throws std::invalid_argument when there is none.
chapter_scene chapter_scene_file(const std::string& id);

}  // namespace rt
