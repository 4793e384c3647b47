// Exposed area: the share of each unknown's area that is not shut inside a closed solid. A
// surface can run into a solid that does not rest on it (a wall behind a panel that stands
// off it, a chair's leg sunk into the floor, the back of a window recess that the glazing
// closes): from a point in there every direction meets the back of the solid's faces, so
// no light arrives and none leaves. A row's cosine rays from such points end on back sides
// and its light samples are shadowed, so the row sums short of what its exposed part sees:
// the unknown absorbs light it never gets. Scaling the row by 1 / exposure and the
// unknown's area by exposure (RowContext::exposure, PatchAttributes::area) makes B the
// radiosity of the exposed part, and A B the power it sends. In the conference room (4.5% of
// its area enclosed) the rows booked 19.0/17.3/16.9% of the light per band as lost on back
// sides or in the void, against 15.2/14.4/14.2% by particle tracing (bench/light_losses);
// with exposed areas 17.8/16.5/16.2%.
#pragma once

#include <cstdint>
#include <vector>

#include "solver/formfactor/row_builder.h"

namespace radflux {

// Probes at a point: a cosine ray; if it meets the back of an opaque patch, this many rays in
// all (the first included) must, for the point to count as enclosed (a partly transparent
// patch, an alpha cut-out, is a sheet, not a solid's wall). A point that merely sees a
// one-sided face from behind (a legitimate absorber) seldom has all of them do so.
inline constexpr int kExposureProbes = 4;
// Stratified points per unknown in a first look (an unknown none of whose points is enclosed
// keeps exposure 1 at that cost), and in the count that follows when one is.
inline constexpr int kExposureFirstPoints = 16;
inline constexpr int kExposurePoints = 256;

// Per unknown of `context`, the share of its area whose points are not enclosed, in (0, 1]:
// kExposurePoints stratified points (the unknown's shift of one shared set, seeded by its
// index alone, so a worker computes the same) when any of kExposureFirstPoints is enclosed,
// else 1. Emitters keep 1: what an enclosed part emits is lost in the solid as it is in
// reality, and a lamp whose rays leave into one-sided faces seen from behind (a room of
// outward tiles, bench/housing_vs_particles.py) reads as enclosed, which would take its
// emission away (+35% absorbed share there). Unknowns
// without a row, and those enclosed whole (nothing reaches them, their row is empty), keep 1
// too. Empty when every unknown has 1.
std::vector<float> UnknownExposure(const RowContext& context, int threads);

}  // namespace radflux
