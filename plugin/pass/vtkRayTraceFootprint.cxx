#include "vtkRayTraceFootprint.h"

#include "vtkRayTraceRecords.h"

#include "vtkrt/core/GpuTraversal.h"

#include "vtkMatrix4x4.h"
#include "vtkRenderer.h"

#include <algorithm>
#include <cmath>
#include <unordered_map>

namespace vtkrt
{
namespace pass
{
namespace
{
/// Pixel rectangles [x0, x1) x [y0, y1) of a viewport, from the normalized
/// device coordinates' extent [lo, hi], a pixel wider on each side.
struct PixelRange
{
  int First[2];
  int Last[2];
};

PixelRange pixelRange(const double lo[2], const double hi[2], const int size[2])
{
  PixelRange r;
  for (int k = 0; k < 2; ++k)
  {
    const double a = std::min(1.0, std::max(-1.0, lo[k])), b = std::min(1.0, std::max(-1.0, hi[k]));
    r.First[k] = std::max(0, static_cast<int>(std::floor((a * 0.5 + 0.5) * size[k])) - 1);
    r.Last[k] = std::min(size[k], static_cast<int>(std::ceil((b * 0.5 + 0.5) * size[k])) + 1);
  }
  return r;
}

/// Square tiles of side Tile over a viewport of Size pixels, Count of them
/// in each direction.
struct TileLayout
{
  int Size[2];
  int Tile;
  int Count[2];

  TileLayout(const int size[2], int tile)
    : Size{ size[0], size[1] }
    , Tile(tile)
    , Count{ (size[0] + tile - 1) / tile, (size[1] + tile - 1) / tile }
  {
  }

  /// The tiles (inclusive ranges First..Last) that the pixel range r
  /// touches; none when r is empty.
  bool Span(const PixelRange& r, int first[2], int last[2]) const
  {
    for (int k = 0; k < 2; ++k)
    {
      first[k] = r.First[k] / this->Tile;
      last[k] = (r.Last[k] - 1) / this->Tile;
    }
    return r.Last[0] > r.First[0] && r.Last[1] > r.First[1];
  }
};

/// The side of the square tiles of a viewport: about a sixteenth of its
/// smaller side (a power of two), 8 pixels or more, at most maxTile unless
/// that is under 8.
int tileSizeFor(int width, int height, int maxTile)
{
  int tile = 8;
  while (2 * tile <= maxTile && 2 * tile * 16 <= std::min(width, height))
  {
    tile *= 2;
  }
  return tile;
}

/// Where a box lies against the near plane: wholly in front (its
/// projection is bounded), wholly behind it (no camera ray, which starts on
/// the near plane, reaches it) or across the eye plane with no near plane
/// known (no bound).
enum class Side
{
  Front,
  Behind,
  Across
};

/// Extends [lo, hi] by the projection of the clip-space point p (p[3] > 0).
void extendProjection(const double p[4], double lo[2], double hi[2])
{
  for (int k = 0; k < 2; ++k)
  {
    lo[k] = std::min(lo[k], p[k] / p[3]);
    hi[k] = std::max(hi[k], p[k] / p[3]);
  }
}

/// The normalized device extent [lo, hi] of the part in front of the near
/// plane of the box whose corner c is corner(c) in shader coordinates: its
/// corners there and, for a box across it, where its edges cross it (the
/// clipped box's vertices). nearW: the clip w of the near plane (0 when
/// the projection has none: then a box across the eye plane has no bound).
template <class Corner>
Side projectBox(vtkMatrix4x4* cameraToClip, double nearW, Corner&& corner, double lo[2], double hi[2],
  double* nearest = nullptr)
{
  lo[0] = lo[1] = VTK_DOUBLE_MAX;
  hi[0] = hi[1] = -VTK_DOUBLE_MAX;
  double nearestDepth = VTK_DOUBLE_MAX;
  double clip[8][4];
  bool front[8];
  int behind = 0;
  for (int c = 0; c < 8; ++c)
  {
    double* p = clip[c];
    p[0] = p[1] = p[2] = 0.0;
    p[3] = 1.0;
    corner(c, p);
    cameraToClip->MultiplyPoint(p, p);
    // A hair in front of the near plane counts as on it, so rounding keeps
    // what the rays can reach.
    front[c] = nearW > 0.0 ? p[3] >= nearW * (1.0 - 1e-6)
                           : p[3] > 1e-12 * (std::abs(p[0]) + std::abs(p[1]) + std::abs(p[2]));
    behind += front[c] ? 0 : 1;
    if (front[c])
    {
      extendProjection(p, lo, hi);
      nearestDepth = std::min(nearestDepth, p[2] / p[3]);
    }
  }
  if (nearest)
  {
    // A box across the near plane starts there.
    *nearest = behind == 0 ? nearestDepth : -1.0;
  }
  if (behind == 0 || behind == 8)
  {
    return behind == 0 ? Side::Front : Side::Behind;
  }
  if (!(nearW > 0.0))
  {
    return Side::Across;
  }
  const double w = nearW * (1.0 - 1e-6);
  for (int c = 0; c < 8; ++c)
  {
    for (int bit = 1; bit < 8; bit <<= 1)
    {
      const int d = c | bit;
      if (d == c || front[c] == front[d])
      {
        continue;
      }
      const double s = (w - clip[c][3]) / (clip[d][3] - clip[c][3]);
      double p[4];
      for (int k = 0; k < 4; ++k)
      {
        p[k] = clip[c][k] + s * (clip[d][k] - clip[c][k]);
      }
      p[3] = w;
      extendProjection(p, lo, hi);
    }
  }
  return Side::Front;
}

/// A world box's corner c in shader coordinates.
void worldCorner(const CameraFrame& camera, const core::AABB<double>& box, int c, double shader[3])
{
  const double world[3] = { (c & 1) ? box.max.x : box.min.x, (c & 2) ? box.max.y : box.min.y,
    (c & 4) ? box.max.z : box.min.z };
  camera.ToShader(world, shader);
}

/// A grid of tiles over the viewport, marked where a box's pixels are.
struct TileGrid : TileLayout
{
  std::vector<char> Covered;

  TileGrid(const int size[2], int tile)
    : TileLayout(size, tile)
    , Covered(static_cast<std::size_t>(Count[0]) * Count[1], 0)
  {
  }

  void mark(const double lo[2], const double hi[2])
  {
    int first[2], last[2];
    if (!this->Span(pixelRange(lo, hi, this->Size), first, last))
    {
      return;
    }
    for (int ty = first[1]; ty <= last[1]; ++ty)
    {
      std::fill_n(this->Covered.begin() + ty * this->Count[0] + first[0], last[0] - first[0] + 1, 1);
    }
  }

  /// The covered tiles as rectangles (viewport pixels): runs of a row,
  /// joined with the same runs of the rows above.
  std::vector<std::array<int, 4>> rectangles() const
  {
    std::vector<std::array<int, 4>> rects;
    std::vector<std::array<int, 4>> open; // the previous row's runs, growing upward
    for (int ty = 0; ty < this->Count[1]; ++ty)
    {
      std::vector<std::array<int, 4>> row;
      const int y0 = ty * this->Tile, y1 = std::min(this->Size[1], y0 + this->Tile);
      for (int tx = 0; tx < this->Count[0];)
      {
        if (!this->Covered[ty * this->Count[0] + tx])
        {
          ++tx;
          continue;
        }
        const int start = tx;
        while (tx < this->Count[0] && this->Covered[ty * this->Count[0] + tx])
        {
          ++tx;
        }
        const int x0 = start * this->Tile, x1 = std::min(this->Size[0], tx * this->Tile);
        row.push_back({ x0, y0, x1 - x0, y1 - y0 });
      }
      const bool same = row.size() == open.size() &&
        std::equal(row.begin(), row.end(), open.begin(),
          [](const std::array<int, 4>& a, const std::array<int, 4>& b) { return a[0] == b[0] && a[2] == b[2]; });
      if (same)
      {
        for (std::size_t k = 0; k < open.size(); ++k)
        {
          open[k][3] += row[k][3];
        }
        continue;
      }
      rects.insert(rects.end(), open.begin(), open.end());
      open = std::move(row);
    }
    rects.insert(rects.end(), open.begin(), open.end());
    return rects;
  }
};
} // namespace

int OutlineDepth(std::size_t instances)
{
  int depth = 0;
  while (depth < 8 && (instances << (depth + 1)) <= 4096)
  {
    ++depth;
  }
  return depth;
}

InstanceOutline OutlineOf(const Instance& inst, const double localToShader[16], int depth)
{
  InstanceOutline outline;
  std::copy(localToShader, localToShader + 16, outline.LocalToShader.begin());
  const Geometry& g = *inst.Geom;
  // What the view sizes (screen-sized spheres, tubes, wires some pixels
  // wide) reaches past the nodes' boxes; surface edges only color hits.
  if (!(g.ScreenSized || g.Tubes || inst.Wireframe || g.Nodes.size() == 0))
  {
    outline.Tree = &g;
    outline.Depth = depth;
  }
  return outline;
}

bool TracedFootprint(const CameraFrame& camera, const FrameRecords& frame, vtkRenderer* ren,
  int rect[4])
{
  const int width = camera.ViewportSize[0], height = camera.ViewportSize[1];
  const int x0 = camera.ViewportOrigin[0], y0 = camera.ViewportOrigin[1];
  if (width <= 0 || height <= 0 || frame.WorldBoxes.empty())
  {
    return false;
  }
  double lo[2] = { VTK_DOUBLE_MAX, VTK_DOUBLE_MAX };
  double hi[2] = { -VTK_DOUBLE_MAX, -VTK_DOUBLE_MAX };
  for (const core::AABB<double>& box : frame.WorldBoxes)
  {
    double boxLo[2], boxHi[2];
    const Side side = projectBox(camera.CameraToClip.Get(), camera.NearPlaneW(),
      [&](int c, double shader[3]) { worldCorner(camera, box, c, shader); }, boxLo, boxHi);
    if (side == Side::Across)
    {
      return false;
    }
    for (int k = 0; k < 2; ++k)
    {
      lo[k] = std::min(lo[k], boxLo[k]);
      hi[k] = std::max(hi[k], boxHi[k]);
    }
  }
  const int size[2] = { width, height };
  const PixelRange r = pixelRange(lo, hi, size);
  if (r.First[0] == 0 && r.First[1] == 0 && r.Last[0] == width && r.Last[1] == height)
  {
    return false;
  }
  rect[0] = x0 + r.First[0];
  rect[1] = y0 + r.First[1];
  rect[2] = std::max(0, r.Last[0] - r.First[0]);
  rect[3] = std::max(0, r.Last[1] - r.First[1]);
  return true;
}

namespace
{
/// The projection of a tree node's box (projectBox), through the local
/// to shader rows m.
Side projectNode(vtkMatrix4x4* cameraToClip, double nearW, const double* m, const core::gpu::Node& node,
  double lo[2], double hi[2], double* nearest = nullptr)
{
  return projectBox(cameraToClip, nearW,
    [&](int c, double shader[3]) {
      const double p[3] = { (c & 1) ? node.hi.x : node.lo.x, (c & 2) ? node.hi.y : node.lo.y,
        (c & 4) ? node.hi.z : node.lo.z };
      for (int r = 0; r < 3; ++r)
      {
        shader[r] = m[4 * r] * p[0] + m[4 * r + 1] * p[1] + m[4 * r + 2] * p[2] + m[4 * r + 3];
      }
    },
    lo, hi, nearest);
}

/// Marks the tiles of instance i's outline boxes, its tree's nodes down to
/// the outline's depth (or of its world box when it has no tree); false
/// when a box has no bounded projection (Side::Across).
bool markInstance(const CameraFrame& camera, const FrameRecords& frame, std::size_t i, TileGrid& grid)
{
  const InstanceOutline& outline = frame.Outlines[i];
  vtkMatrix4x4* cameraToClip = camera.CameraToClip.Get();
  const double nearW = camera.NearPlaneW();
  double lo[2], hi[2];
  if (!outline.Tree)
  {
    const core::AABB<double>& box = frame.WorldBoxes[i];
    const Side side = projectBox(
      cameraToClip, nearW, [&](int c, double shader[3]) { worldCorner(camera, box, c, shader); }, lo, hi);
    if (side == Side::Front)
    {
      grid.mark(lo, hi);
    }
    return side != Side::Across;
  }
  const double* m = outline.LocalToShader.data();
  struct Entry
  {
    std::uint32_t Node;
    int Depth;
  };
  std::vector<Entry> stack{ { 0u, 0 } };
  while (!stack.empty())
  {
    const Entry e = stack.back();
    stack.pop_back();
    const core::gpu::Node& node = outline.Tree->Nodes[e.Node];
    if (node.count == 0 && e.Depth < outline.Depth)
    {
      stack.push_back({ node.index, e.Depth + 1 });
      stack.push_back({ node.index + 1, e.Depth + 1 });
      continue;
    }
    const Side side = projectNode(cameraToClip, nearW, m, node, lo, hi);
    if (side == Side::Across)
    {
      return false;
    }
    if (side == Side::Front)
    {
      grid.mark(lo, hi);
    }
  }
  return true;
}
} // namespace

std::vector<std::array<int, 4>> TracedTiles(const CameraFrame& camera, const FrameRecords& frame,
  vtkRenderer* ren, const int* footprint, int tileSize, std::size_t maxRects)
{
  const int width = camera.ViewportSize[0], height = camera.ViewportSize[1];
  const int x0 = camera.ViewportOrigin[0], y0 = camera.ViewportOrigin[1];
  const int size[2] = { width, height };
  if (width <= 0 || height <= 0 || frame.Outlines.size() != frame.WorldBoxes.size())
  {
    return {};
  }
  TileGrid grid(size, tileSizeFor(width, height, tileSize));
  for (std::size_t i = 0; i < frame.Outlines.size(); ++i)
  {
    if (!markInstance(camera, frame, i, grid))
    {
      return {};
    }
  }
  std::vector<std::array<int, 4>> rects = grid.rectangles();
  std::size_t tiledPixels = 0;
  for (const auto& r : rects)
  {
    tiledPixels += static_cast<std::size_t>(r[2]) * r[3];
  }
  const std::size_t footprintPixels = footprint ? static_cast<std::size_t>(footprint[2]) * footprint[3]
                                                : static_cast<std::size_t>(width) * height;
  if (rects.size() > maxRects || tiledPixels >= footprintPixels)
  {
    return {};
  }
  for (auto& r : rects)
  {
    r[0] += x0;
    r[1] += y0;
  }
  return rects;
}

namespace
{
/// A node of a tile list: the tiles (inclusive ranges) its box reaches, its
/// nearest normalized device depth, and at most how many levels lie below it.
struct CutNode
{
  std::uint32_t Node;
  std::uint32_t Height; ///< a leaf: 0
  int First[2];
  int Last[2];
  double Nearest;
  bool Reaches; ///< false: behind the near plane, or no pixel of the viewport
};

/// The tile lists' builder: each tile's list starts as the root and
/// splits its shallowest node into the children that reach the tile while
/// the list stays within maxEntries and the stack; the nodes' projections
/// are made once a frame.
class TileCuts
{
public:
  TileCuts(const CameraFrame& camera, const InstanceOutline& outline, const int size[2], int tile)
    : CameraToClip(camera.CameraToClip.Get())
    , NearW(camera.NearPlaneW())
    , Outline(outline)
    , Tiles(size, tile)
  {
  }

  /// The lists: headers, then each tile's node ids (global: root + local),
  /// the nearest last.
  TileEntryLists Lists(std::uint32_t root, std::uint32_t maxEntries, std::uint32_t stackSize)
  {
    const int* count = this->Tiles.Count;
    const std::size_t tiles = static_cast<std::size_t>(count[0]) * count[1];
    TileEntryLists out;
    const std::size_t headerWords = 4 * (tiles + 1);
    out.Words.assign(headerWords, 0u);
    out.Words.push_back(root);
    out.Words[0] = static_cast<std::uint32_t>(headerWords);
    out.Words[1] = 1u;
    std::vector<const CutNode*> list;
    for (int ty = 0; ty < count[1]; ++ty)
    {
      for (int tx = 0; tx < count[0]; ++tx)
      {
        this->ListOf(tx, ty, maxEntries, stackSize, list);
        std::uint32_t* header = out.Words.data() + 4 * (1 + static_cast<std::size_t>(ty) * count[0] + tx);
        header[0] = list.empty() ? out.Words[0] : static_cast<std::uint32_t>(out.Words.size());
        header[1] = list.empty() ? 1u : static_cast<std::uint32_t>(list.size());
        std::sort(list.begin(), list.end(), [](const CutNode* a, const CutNode* b) { return a->Nearest > b->Nearest; });
        for (const CutNode* c : list)
        {
          out.Words.push_back(root + c->Node);
        }
        out.Entries += list.size();
      }
    }
    out.Words.resize((out.Words.size() + 3) / 4 * 4, 0u);
    for (int k = 0; k < 2; ++k)
    {
      out.Grid[k] = static_cast<float>(this->Tiles.Size[k]) / static_cast<float>(this->Tiles.Tile);
      out.Grid[2 + k] = static_cast<float>(count[k]);
    }
    return out;
  }

private:
  vtkMatrix4x4* CameraToClip;
  double NearW;
  const InstanceOutline& Outline;
  TileLayout Tiles;
  std::unordered_map<std::uint32_t, CutNode> Reached; ///< the projections made
  std::vector<const CutNode*> Next;                   ///< ListOf's list after a split

  /// Node `node` (local), `height` levels at most below it, projected.
  const CutNode& Reach(std::uint32_t node, std::uint32_t height)
  {
    auto found = this->Reached.find(node);
    if (found != this->Reached.end())
    {
      return found->second;
    }
    CutNode& out = this->Reached[node];
    const core::gpu::Node& n = this->Outline.Tree->Nodes[node];
    out.Node = node;
    out.Height = n.count > 0 ? 0u : std::max(height, 1u);
    double lo[2], hi[2];
    const Side side =
      projectNode(this->CameraToClip, this->NearW, this->Outline.LocalToShader.data(), n, lo, hi, &out.Nearest);
    const int* size = this->Tiles.Size;
    const PixelRange r =
      side == Side::Across ? PixelRange{ { 0, 0 }, { size[0], size[1] } } : pixelRange(lo, hi, size);
    out.Reaches = this->Tiles.Span(r, out.First, out.Last) && side != Side::Behind;
    return out;
  }

  static bool Touches(const CutNode& c, int tx, int ty)
  {
    return c.Reaches && tx >= c.First[0] && tx <= c.Last[0] && ty >= c.First[1] && ty <= c.Last[1];
  }

  /// Tile (tx, ty)'s list, in no order; empty when no box reaches it.
  void ListOf(int tx, int ty, std::uint32_t maxEntries, std::uint32_t stackSize, std::vector<const CutNode*>& list)
  {
    list.clear();
    const CutNode& root = this->Reach(0u, this->Outline.Tree->MaxDepth);
    if (Touches(root, tx, ty))
    {
      list.push_back(&root);
    }
    std::vector<const CutNode*>& next = this->Next;
    for (;;)
    {
      // The shallowest interior node (the tallest subtree) splits next.
      const auto split = std::max_element(
        list.begin(), list.end(), [](const CutNode* a, const CutNode* b) { return a->Height < b->Height; });
      if (split == list.end() || (*split)->Height == 0)
      {
        return;
      }
      const std::uint32_t height = (*split)->Height;
      const core::gpu::Node& n = this->Outline.Tree->Nodes[(*split)->Node];
      next.assign(list.begin(), split);
      next.insert(next.end(), split + 1, list.end());
      std::uint32_t tallest = 0;
      for (std::uint32_t child : { n.index, n.index + 1 })
      {
        const CutNode& c = this->Reach(child, height - 1);
        if (Touches(c, tx, ty))
        {
          next.push_back(&c);
        }
      }
      for (const CutNode* c : next)
      {
        tallest = std::max(tallest, c->Height);
      }
      if (next.size() > maxEntries ||
        !core::gpu::entriesFitStack(static_cast<std::uint32_t>(next.size()), tallest, stackSize))
      {
        return;
      }
      list.swap(next);
    }
  }
};

/// The root's list for every ray: one tile over the viewport.
TileEntryLists RootLists(std::uint32_t root)
{
  TileEntryLists out;
  out.Words = { 8u, 1u, 0u, 0u, 8u, 1u, 0u, 0u, root, 0u, 0u, 0u };
  return out;
}
} // namespace

TileEntryLists MakeTileEntryLists(const CameraFrame& camera, const FrameRecords& frame, vtkRenderer* ren,
  int tileSize, std::uint32_t maxEntries, std::uint32_t stackSize)
{
  if (frame.Records.empty())
  {
    return RootLists(0u);
  }
  const std::uint32_t root = frame.Records[0].root;
  if (frame.Records.size() != 1 || frame.Outlines.size() != 1)
  {
    return RootLists(root);
  }
  const InstanceOutline& outline = frame.Outlines[0];
  const int width = camera.ViewportSize[0], height = camera.ViewportSize[1];
  if (!outline.Tree || outline.Tree->Nodes.size() == 0 || width <= 0 || height <= 0)
  {
    return RootLists(root);
  }
  const int size[2] = { width, height };
  TileCuts cuts(camera, outline, size, tileSizeFor(width, height, tileSize));
  return cuts.Lists(root, maxEntries, stackSize);
}

} // namespace pass
} // namespace vtkrt
