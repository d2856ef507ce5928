// checker.hpp — given code, not an exercise: the diffuse colour of a
// material at a point, for materials with a checker pattern.
//
// The pattern is shared by every chapter program and the renderer, so it
// lives with the materials: rt::material_at in common/scene.hpp (unit
// squares of the x-z plane, picked with floor() of x and z only). This
// header keeps chapter 06's spelling, ch06::material_at(m, point).
#pragma once

#include "common/scene.hpp"

namespace rt::ch06 {

using rt::material_at;

}  // namespace rt::ch06
