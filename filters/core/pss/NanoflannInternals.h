// SPDX-License-Identifier: BSD-3-Clause
// The one place where PointSetSurfaces reads nanoflann's internals (private to the core: not
// installed, included by PointIndex.cxx only).
//
// PointIndex needs three things nanoflann's public API does not give: the tree's permutation of
// the points (to store them in leaf order, so that a leaf is a contiguous index range), and the
// root node and root bounding box (to walk the leaves in a ball in index order, see
// PointIndex::leavesInBall). In nanoflann 1.3 and 1.4 these are the public but undocumented
// members vAcc, root_node and root_bbox of KDTreeBaseClass, and a node has child1, child2 and
// node_type.lr.{left,right} / node_type.sub.{divfeat,divlow,divhigh}. nanoflann 1.5 renamed
// the members (vAcc_, root_node_, root_bbox_) and changed SearchParams and radiusSearch's result
// type, so other versions stop here at compile time instead of failing somewhere inside
// PointIndex.cxx. Tested: 1.4.3 (Debian 12's libnanoflann-dev, NANOFLANN_VERSION 0x142).
#ifndef pss_NanoflannInternals_h
#define pss_NanoflannInternals_h

#include <nanoflann.hpp>

#include <cstddef>
#include <type_traits>
#include <utility>

#if !defined(NANOFLANN_VERSION) || NANOFLANN_VERSION < 0x130 || NANOFLANN_VERSION >= 0x150
#error "PointSetSurfaces reads nanoflann 1.3/1.4 internals (vAcc, root_node, root_bbox); adapt pss/NanoflannInternals.h to this version"
#endif

namespace pss
{
namespace nanoflann_internals
{

/// The tree's permutation: position i of the tree's leaf order holds point vAcc[i].
template <class Tree>
auto& permutation(Tree& tree)
{
  return tree.vAcc;
}

/// The root node (nullptr for an empty tree).
template <class Tree>
const auto* rootNode(const Tree& tree)
{
  return tree.root_node;
}

/// The root's bounding box: one {low, high} interval per axis.
template <class Tree>
const auto& rootBox(const Tree& tree)
{
  return tree.root_bbox;
}

/// The node type of a tree (what rootNode points to).
template <class Tree>
using Node = std::remove_pointer_t<decltype(std::declval<const Tree&>().root_node)>;

/// Node accessors: a leaf has no children and holds the positions [left, right) of the leaf order.
template <class N>
bool isLeaf(const N& node)
{
  return node.child1 == nullptr && node.child2 == nullptr;
}
template <class N>
std::size_t leafBegin(const N& node)
{
  return static_cast<std::size_t>(node.node_type.lr.left);
}
template <class N>
std::size_t leafEnd(const N& node)
{
  return static_cast<std::size_t>(node.node_type.lr.right);
}
/// An inner node splits on axis(): child1 holds coordinates <= low(), child2 those >= high().
template <class N>
int axis(const N& node)
{
  return static_cast<int>(node.node_type.sub.divfeat);
}
template <class N>
double low(const N& node)
{
  return node.node_type.sub.divlow;
}
template <class N>
double high(const N& node)
{
  return node.node_type.sub.divhigh;
}
template <class N>
const N* lowChild(const N& node)
{
  return node.child1;
}
template <class N>
const N* highChild(const N& node)
{
  return node.child2;
}

} // namespace nanoflann_internals
} // namespace pss

#endif
