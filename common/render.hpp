// render.hpp — the loop over pixels, run on every core.
//
// render(width, height, shade) calls shade(col, row) once per pixel and
// collects the colours into an image. Rows are handed out one at a time to
// a small pool of threads (one per hardware thread), which keeps both cores
// of a laptop busy even when some rows are much more expensive than others.
// An exception thrown by shade (for example a stub's "not implemented yet")
// stops the render and is rethrown to the caller, unchanged.
//
// for_each_row is that pool on its own, for renderers that fill the image
// their own way (tools/render's tiles): the project's one thread pool.
#pragma once

#include "image.hpp"

#include <functional>

namespace rt {

using pixel_shader = std::function<color(int col, int row)>;

// Renders an image; prints a progress line on stderr when stderr is a
// terminal and the render has taken longer than a second.
image render(int width, int height, const pixel_shader& shade);

// How many threads render() uses (at least 1).
int render_threads();

// Calls body(row) once for every row in [0, rows), rows handed out one at a
// time to render_threads() threads (the caller's thread is one of them).
// The first exception body throws stops the others and is rethrown here.
void for_each_row(int rows, const std::function<void(int row)>& body);

}  // namespace rt
