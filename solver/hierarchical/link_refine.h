// Link refinement of hierarchical radiosity: the initial links and the refinement rounds
// that replace links over the error threshold by their children's (see hierarchical.h for
// the oracle). Internal to solver/hierarchical.
#pragma once

#include <cstdint>

#include "solver/hierarchical/hierarchical_state.h"

namespace radflux {

// The top cluster's link with itself, or without clusters every ordered pair of faces.
LinkSet InitialLinks(const Context& c, const ElementTree& tree, const NodeState& state,
                     uint64_t& rays);

// One refinement round: every link over threshold (and every cluster's link with itself) is
// replaced by its children's links, one level down; new elements get their state
// (AddNodes). Returns true when any link was.
bool RefineRound(const Context& c, ElementTree& tree, LinkSet& links, NodeState& state,
                 uint64_t& rays);

}  // namespace radflux
