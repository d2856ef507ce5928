// same_on_every_thread_count.cpp — chapter 11's picture does not depend on the threads.
//
// Draws a small version of the chapter's scene, in both precisions and with
// every sequence, four ways: with the thread pool (common/render.hpp), twice;
// on one thread, row by row; on one thread, the rows and columns backwards.
// The four must be equal to the last bit: a pixel's samples come from its own
// stream, never from a generator the threads share. Exit status 0 when they are.
#include "picture.hpp"

#include "common/chapter_scenes.hpp"

#include <cstdio>
#include <cstring>

namespace {

using namespace rt;

template <class T>
bool same_every_way(const scene_description& d, ch11::sequence_kind kind) {
    const ch11::sampled_scene<T> scene(d, 48, 36);
    ch11::picture_settings s;
    s.samples = 4;
    s.sequence = kind;
    const image pooled = ch11::render_picture(scene, s);
    const image again = ch11::render_picture(scene, s);
    image forwards(scene.width(), scene.height()), backwards(scene.width(), scene.height());
    for (int row = 0; row < scene.height(); ++row)
        for (int col = 0; col < scene.width(); ++col) forwards.at(col, row) = scene.pixel(col, row, s);
    for (int row = scene.height() - 1; row >= 0; --row)
        for (int col = scene.width() - 1; col >= 0; --col) backwards.at(col, row) = scene.pixel(col, row, s);
    const size_t bytes = pooled.pixels.size() * sizeof(color);
    const bool same = std::memcmp(pooled.pixels.data(), again.pixels.data(), bytes) == 0 &&
                      std::memcmp(pooled.pixels.data(), forwards.pixels.data(), bytes) == 0 &&
                      std::memcmp(pooled.pixels.data(), backwards.pixels.data(), bytes) == 0;
    std::printf("%s, %s: %s (%d threads)\n", sizeof(T) == 4 ? "float" : "double", ch11::sequence_name(kind),
                same ? "the same picture every way" : "DIFFERENT pictures", render_threads());
    return same;
}

}  // namespace

int main() {
    const chapter_scene own = chapter_scene_file("ch11");
    const scene_description d = parse_scene(own.text, own.source);
    bool all = true;
    for (auto kind : {ch11::sequence_kind::random, ch11::sequence_kind::stratified, ch11::sequence_kind::halton}) {
        all = same_every_way<float>(d, kind) && all;
        all = same_every_way<double>(d, kind) && all;
    }
    return all ? 0 : 1;
}
