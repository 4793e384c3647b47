// ClusterTree: a binary bounding-volume hierarchy over the root elements (input faces) of an
// ElementTree, the clusters of hierarchical radiosity (Smits, Arvo and Greenberg 1994). Each
// cluster stands for a contiguous range of `order`; its two children are clusters or single
// root elements. Built by median split of the face centroids along the longest axis of their
// bounds, ties broken by element index, so the same faces always give the same tree.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "solver/core/vec3.h"
#include "solver/mesh/adaptive_tree.h"

namespace radflux {

// Node ids shared by elements and clusters: an element index, or kClusterBit | cluster index.
inline constexpr uint32_t kClusterBit = 0x80000000u;
inline bool IsCluster(uint32_t node) { return (node & kClusterBit) != 0; }
inline uint32_t ClusterIndex(uint32_t node) { return node & ~kClusterBit; }

struct Cluster {
  uint32_t begin = 0, end = 0;         // its faces: order[begin, end), at least two
  std::array<uint32_t, 2> children{};  // node ids (clusters or root elements)
  uint32_t parent = kNoElement;        // cluster index; kNoElement for the top
  Vec3 center;                         // area-weighted centroid of its faces
  double radius = 0;                   // bounding sphere about `center`, scene units
  double area = 0;                     // total area of its faces, scene units^2
};

struct ClusterTree {
  std::vector<Cluster> clusters;       // clusters[0] is the top; parents precede children
  std::vector<uint32_t> order;         // root elements, each cluster's faces contiguous
  std::vector<uint32_t> face_cluster;  // per root element: the smallest cluster holding it

  // The hierarchy over tree.roots (which must be elements 0..roots-1); no clusters when
  // there are fewer than two roots.
  static ClusterTree Build(const ElementTree& tree);
};

// Radius of the sphere about e.centroid through e's farthest corner.
double ElementRadius(const Element& e);

}  // namespace radflux
