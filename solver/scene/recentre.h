// Recentring: a scene far from the origin (a CAD or GIS export at x = 100 km) is moved near
// it in double precision before anything becomes float, so that it solves like the same
// room at the origin; outputs add Scene::origin back.
#pragma once

#include "solver/core/vec3.h"
#include "solver/scene/scene.h"

namespace radflux {

// The offset a scene with bounding box [lo, hi] is moved by: its box centre rounded to a
// multiple of the power of two q >= 4 x the box diagonal. Zero for a scene whose centre is
// within q/2 of the origin (every scene near the origin keeps its coordinates exactly), and
// the same room moved by a multiple of q gets an offset larger by exactly that multiple.
Vec3 RecentringOffset(const Vec3& lo, const Vec3& hi);

// Subtracts RecentringOffset of the scene's vertices from every position and adds it to
// scene.origin. Exact (Sterbenz) for coordinates within a factor 2 of the offset.
void RecentreScene(Scene& scene);

}  // namespace radflux
