// Boxes of triangles for the SAH kd-tree builder (sah_kd_builder.h): bounding boxes and the bounds
// of the part of a triangle inside a box, the "perfect splits" of Wald and Havran, "On building
// fast kd-Trees for Ray Tracing, and on doing that in O(N log N)", IEEE Symposium on Interactive Ray
// Tracing 2006, section 4.3.
#pragma once

#include <utility>

#include "accel/kd/kd_tree.h"
#include "scene/scene.h"

namespace vkray::accel::kd {

Box boundsOf(const Triangle& t);
Box intersection(const Box& a, const Box& b);
bool isEmpty(const Box& b);
bool contains(const Box& outer, const Box& inner);

// Bounds of the part of `tri` inside `box`: clipped in double, rounded outwards to float, within
// `box`; never smaller than that part (kd_clip.cpp).
Box clippedBounds(const Triangle& tri, const Box& box);
// clippedBounds(tri, below) and clippedBounds(tri, above), for the children of a split on `axis`,
// with the work they share done once.
std::pair<Box, Box> clippedBoundsOfSplit(const Triangle& tri, const Box& below, const Box& above, int axis);

}  // namespace vkray::accel::kd
