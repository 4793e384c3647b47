// How many cosine rays a Monte Carlo row casts: k (--rays) on average over the unknowns with
// rows, each in proportion to its area. A surface's mean B (and the power it reflects) is an
// area-weighted sum of its rows' estimates, whose variance for a fixed total of rays is least
// with rays in proportion to area; one k for every row spent most of the Cornell box's rays
// on the floor's small contact patches (53% of the rows, a tenth of the others' size) and
// left the ceiling's 136 rows the noisiest surface. An emitter's row is the exception: it
// casts kEmitterRowRays k whatever its area. That holds for equal noise per ray only; a lamp
// in its housing reflects light many times brighter than a wall's (the conference room's 406
// lamp faces, 0.4% of its area, reflect 16% of the room's power: 2.1 of 13.6 MW), and at 16
// rays a lamp that light swung the room's light by 0.7% (sd over seeds).
#pragma once

#include <cstdint>
#include <span>

namespace radflux {

// No row casts fewer rays than this (or k, when k is smaller): k / 4 alone gave the small
// patches of the hard-case closed room 4 rays at k = 16, too coarse a reading of where a
// row's light goes; at rho = 0.999 those rows put its energy balance 15.5% off.
inline constexpr int kLeastRowRays = 16;

// The rays of an emitter's row, in units of k.
inline constexpr int kEmitterRowRays = 4;

// The mean area of the unknowns with a row (has_row[u] != 0); 0 when none has one.
double MeanRowArea(std::span<const double> area, std::span<const uint8_t> has_row);

// The rays of a row of `area` (scene units^2, the opaque area of PatchAttributes): k * area /
// mean_area rounded, within [max(1, k / 4, min(k, kLeastRowRays)), 4 k]; k (at least 1) when
// mean_area is not a finite number > 0 or area / mean_area not one >= 0. The clamp keeps a
// sliver's row from a handful of rays and a huge face's from most of the budget. An emitter's
// row (`emits`): kEmitterRowRays k (at least 1).
uint32_t RowRayCount(int k, double area, double mean_area, bool emits);

// A row of `area` against the mean row's (RowRayCount's share): 1 when mean_area is not a
// finite number > 0 or the share not one >= 0.
double RowAreaShare(double area, double mean_area);

// The near-field factor of a row's light points (LightSampler: up to 16 times the points for a
// receiver near an emitter against its size) scaled by the row's area share, as its cosine
// rays are: ceil(factor * share) within [1, factor]. A surface's mean B (and the light it
// sends on) weighs a row's variance by its area squared, so the extra points are worth their
// cost in proportion to its area: RenderPark's corridor gave its 375 small ceiling patches
// beside the lamps' 2 cm gaps, and the slots above them (a tenth to a third of the mean row),
// 16 times the points, 60% of its rays, for no change of any object's error beyond its noise
// (8 seeds); its wall patches, 20 times the mean row, keep all of theirs.
int RowNearFieldFactor(int factor, double share);

// Whether F_ij, between unknown i of area_i and a hidden unknown j of area_j (rays as
// RowRayCount gives them), is better read from j's row by reciprocity, A_j F_ji / A_i, than
// from i's own hits: its variance there is (A_j / k_j) F_ij / A_i against F_ij / k_i, so when
// j has less area per ray (a wall of 100 m^2 and 256 rays against a lamp's strip of 0.16 m^2
// and 16; not a 0.01 m^2 part with 16 rays of its own, to which one ray of the strip's 16
// would give F = 1: office2's switch plate read +154% so on one seed of four). `i_emits`:
// whether i is an emitter (its rays are then RowRayCount's emitter count); a hidden unknown
// never emits.
bool ReadFromHiddenRow(int k, double area_i, bool i_emits, double area_j, double mean_area);

}  // namespace radflux
