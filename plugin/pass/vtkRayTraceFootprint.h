// Private to vtkRayTracePass: the pixels where a camera ray can meet the
// traced instances, so that no ray is cast elsewhere. No GL here.
#ifndef vtkRayTraceFootprint_h
#define vtkRayTraceFootprint_h

#include "vtkRayTraceTypes.h"
#include "vtkrt/core/AABB.h"

#include <array>
#include <vector>

class vtkRenderer;

namespace vtkrt
{
namespace pass
{
struct CameraFrame;
struct FrameRecords;

/// Where an instance's primitives are: the boxes of its BVH's nodes down to
/// Depth (local coordinates, as the nodes hold them; leaves above it stand
/// for themselves), read from Tree when the tiles are made, and the map of
/// local to shader coordinates. No Tree: only the instance's world box
/// bounds it (primitives whose size depends on the view, as screen-sized
/// spheres, tubes and lines are, or an empty tree).
struct InstanceOutline
{
  std::array<double, 16> LocalToShader{}; ///< row-major
  const Geometry* Tree = nullptr;
  int Depth = 0;
};

/// The outline of `inst` whose local to shader map is `localToShader`,
/// with nodes down to `depth`.
InstanceOutline OutlineOf(const Instance& inst, const double localToShader[16], int depth);

/// The depth of the outlines of a frame of `instances` instances: about
/// 4096 boxes in all, at most 8 levels (256 boxes) per instance.
int OutlineDepth(std::size_t instances);

/// The pixels where a primary ray can meet the frame's instances: the
/// window rectangle (x, y, width, height) around the projections of their
/// world boxes' parts in front of the near plane (where camera rays start),
/// a pixel wider on each side. False when it is the whole viewport anyway,
/// or when a box lies across the eye plane of a projection with no near
/// plane of one depth (its projection is unbounded).
bool TracedFootprint(const CameraFrame& camera, const FrameRecords& frame, vtkRenderer* ren,
  int rect[4]);

/// The same pixels, finer: window rectangles (x, y, width, height), none
/// overlapping, covering the square tiles (a sixteenth of the viewport's
/// smaller side, from 8 to tileSize pixels) that the projections of the
/// instances' outline boxes, a pixel wider, touch. For camera-relative
/// coordinates, whose float rays stray far less than that pixel. Empty when
/// the tiles are no fewer pixels than `footprint` (TracedFootprint's
/// rectangle, or null for the whole viewport), when TracedFootprint has no
/// bound, or when they take more than maxRects rectangles.
std::vector<std::array<int, 4>> TracedTiles(const CameraFrame& camera, const FrameRecords& frame,
  vtkRenderer* ren, const int* footprint, int tileSize, std::size_t maxRects);
/// Where the walks of camera rays start, per screen tile (the shader's
/// VTKRT_TILE_ENTRIES), for a frame of one triangle instance: Words is the
/// uTileEntries buffer (core::gpu::TileList headers: list 0 the root alone,
/// then one a tile, row by row; then their node ids), Grid the uTileGrid
/// uniform (tiles per unit of viewport coordinates in x and y, tiles in x
/// and y).
struct TileEntryLists
{
  std::vector<std::uint32_t> Words;
  float Grid[4] = { 1.0f, 1.0f, 1.0f, 1.0f };
  std::size_t Entries = 0; ///< node ids over all tiles
};

/// The lists: for each tile (as TracedTiles makes them, of at most
/// tileSize pixels), nodes of the instance's tree that hold every primitive
/// whose box's projection, a pixel wider, touches the tile: starting from
/// the root, the node with the tallest subtree is replaced by its children
/// that touch the tile, while the list keeps at most maxEntries nodes and
/// fits the shader's stack of stackSize entries
/// (core::gpu::entriesFitStack); the nearest last. A tile no box touches,
/// and every tile of a frame with no tree, gets the root's list.
TileEntryLists MakeTileEntryLists(const CameraFrame& camera, const FrameRecords& frame, vtkRenderer* ren,
  int tileSize, std::uint32_t maxEntries, std::uint32_t stackSize);
} // namespace pass
} // namespace vtkrt

#endif
