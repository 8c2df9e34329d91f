// Quantising a wide node's child boxes (bvh_quantise.cpp). Internal to
// src/accel: the collapse calls it, the tests check it.
#pragma once

#include "accel/bvh.h"

namespace sombra {

// Sets node.origin, node.scale, node.bounds and node.used for children[0,
// size) (1 ≤ size ≤ kBvhWidth, finite boxes with lo ≤ hi) so that
// child_box(node, i) contains children[i] for each i, each plane at most
// one grid step (and rounding) outside the true bound; slots from `size` on
// are left unused. child and count are not touched.
void quantise_children(const BvhChildBox* children, int size, BvhWideNode& node);

}  // namespace sombra
