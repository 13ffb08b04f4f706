// The patch's properties on random and adversarial meshes: a deterministic sweep shared by the
// default test (10^4 patches) and the long one (10^6, ctest label "long").
#pragma once

#include <cstdint>
#include <string>

namespace gf::sim::testing {

/// What a sweep computed and what broke.
struct PropertySweep {
  long patches = 0;         ///< computePatch calls
  long valid = 0;           ///< of them, patches with valid == true
  long sgos = 0;            ///< SGOs and filled inner points checked
  long meshes = 0;          ///< meshes generated
  long failures = 0;        ///< broken properties (each patch counts once)
  long warm_walks = 0;      ///< warm against cold: walks carried from the primed cache
  long slack_walks = 0;     ///< of them, carried within their slack (crossings unchecked)
  double warm_error = 0.0;  ///< and the largest distance of a carried point from its cold one (m)
  std::string first_failure;  ///< what broke first, with the mesh kind, seed and inputs
};

/// Computes `patches` patches on meshes drawn from `seed` (soups, jittered and inside-out
/// spheres, mixed winding, unwelded duplicates, zero-area and sliver triangles, non-manifold fans,
/// height fields, primitives from 1 mm to 10 m) with contacts at random points, exact vertices
/// and edge midpoints, and settings anywhere in their legal ranges. Checks that every accepted
/// patch has a finite radius within r_max, at most n_sgo SGOs, every SGO and inner point finite
/// and on the surface (within 1e-9 of the mesh's diagonal), every walk no longer than its d_i and
/// within its crossing budget, and load shares summing to 1. With `warm_vs_cold`, each patch is
/// also computed with warm-started walks carried from the same contact moved twice by 1e-6 of
/// the mesh's diagonal (and its normal turned 1e-6 rad each time), and every point and path
/// point must lie within 1e-9 m of the cold patch's.
PropertySweep sweepPatchProperties(std::uint32_t seed, long patches, bool warm_vs_cold = false);

/// Runs the sweep as a gtest check: all `patches` computed, none broken, and most of them carrying
/// points (at least 10 per patch on average); prints what it checked.
/// With `warm_vs_cold`, also walks carried (3 per patch on average; only face hits carry) and
/// more than one per patch within its slack.
void expectSweepHolds(std::uint32_t seed, long patches, bool warm_vs_cold = false);

}  // namespace gf::sim::testing
