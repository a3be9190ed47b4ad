// core::LazyWideBVH: every primitive in exactly one leaf slot, boxes that
// hold what is below them, bounded depth, and the same tree whatever the
// thread count and whichever subtrees queries reach first (including from
// several threads at once).
#include "CoreTestUtils.h"

#include <atomic>
#include <thread>

using namespace vtkrt::test;

namespace
{

/// Boxes as primitives; records where each one was placed.
struct BoxPrims
{
  const std::vector<AABB<double>>* Boxes;
  std::vector<std::uint32_t>* SlotId;         ///< id at each slot
  std::vector<std::atomic<int>>* Placed;      ///< times each id was placed
  AABB<double> bounds(std::uint32_t id) const { return (*Boxes)[id]; }
  void placeLeaf(const std::uint32_t* ids, std::uint32_t begin, std::uint32_t end, float lo[3], float hi[3])
  {
    AABB<double> box;
    for (std::uint32_t t = begin; t < end; ++t)
    {
      const std::uint32_t id = ids[t - begin];
      (*SlotId)[t] = id;
      (*Placed)[id]++;
      box.extend((*Boxes)[id]);
    }
    for (int a = 0; a < 3; ++a)
    {
      lo[a] = detail::floorFloat(box.min[a]);
      hi[a] = detail::ceilFloat(box.max[a]);
    }
  }
  void prefetch(std::uint32_t, int) const {}
};

using Tree = LazyWideBVH<BoxPrims>;

bool holds(const float lo[3], const float hi[3], const AABB<double>& b)
{
  for (int a = 0; a < 3; ++a)
  {
    if (!(lo[a] <= b.min[a] && b.max[a] <= hi[a]))
    {
      return false;
    }
  }
  return true;
}

/// Walks the whole tree (building what is missing); checks boxes and
/// depth; returns the slots in leaf order and the tree's shape as text.
struct Walk
{
  Tree& T;
  const std::vector<AABB<double>>& Boxes;
  const std::vector<std::uint32_t>& SlotId;
  std::uint32_t LeafSize;
  std::vector<std::uint32_t> Slots;
  std::string Shape;
  std::uint32_t MaxDepth = 0;

  /// Slot (child, count) with box lo/hi at depth d.
  void visit(const WideNode* nodes, std::uint32_t child, std::uint32_t count, const float lo[3], const float hi[3],
    std::uint32_t d)
  {
    MaxDepth = std::max(MaxDepth, d);
    if (count == kWideSubtree)
    {
      const Tree::Subtree sub = T.subtree(child);
      visit(sub.nodes, sub.child, sub.count, lo, hi, d);
      return;
    }
    if (count > 0)
    {
      VTKRT_CHECK(count <= LeafSize);
      Shape += "L" + std::to_string(count);
      for (std::uint32_t s = child; s < child + count; ++s)
      {
        Slots.push_back(s);
        VTKRT_CHECK(holds(lo, hi, Boxes[SlotId[s]]));
      }
      return;
    }
    const WideNode& n = nodes[child];
    Shape += "(";
    int used = 0;
    for (int i = 0; i < kWideArity; ++i)
    {
      if (!n.slotUsed(i))
      {
        continue;
      }
      ++used;
      float clo[3], chi[3];
      n.slotBox(i, clo, chi);
      // What the walk needs: every primitive below lies in every box on its
      // path (a quantized child box may reach past its parent's grid).
      for (int a = 0; a < 3; ++a)
      {
        VTKRT_CHECK(clo[a] <= chi[a]);
        clo[a] = std::max(clo[a], lo[a]);
        chi[a] = std::min(chi[a], hi[a]);
      }
      visit(nodes, n.child[i], n.count[i], clo, chi, d + 1);
    }
    VTKRT_CHECK(used >= 1);
    Shape += ")";
  }

  void run()
  {
    const auto& top = T.nodes();
    if (top.empty())
    {
      return;
    }
    const float inf = std::numeric_limits<float>::infinity();
    const float lo[3] = { -inf, -inf, -inf }, hi[3] = { inf, inf, inf };
    visit(top.data(), 0, 0, lo, hi, 0);
  }
};

struct Built
{
  std::vector<std::uint32_t> slotId;
  std::vector<std::uint32_t> slots;
  std::string shape;
  std::uint32_t depth = 0;
  bool placedOnce = true;
};

/// order: 0 buildAll serially, 1 buildAll with a two-thread parallelFor,
/// 2 subtrees from a walk, 3 subtrees from four threads at once.
Built build(const std::vector<AABB<double>>& boxes, const AABB<double>& bounds, std::uint32_t leafSize, int order)
{
  Built out;
  out.slotId.assign(boxes.size(), 0xffffffffu);
  std::vector<std::atomic<int>> placed(boxes.size());
  BuildOptions options;
  options.maxLeafSize = leafSize;
  options.numThreads = 1; // order 0: serial (no parallelFor, one thread)
  if (order == 1)
  {
    options.parallelFor = [](std::size_t n, const std::function<void(std::size_t, std::size_t)>& body) {
      std::thread other([&]() { body(n / 2, n); });
      body(0, n / 2);
      other.join();
    };
  }
  Tree tree(BoxPrims{ &boxes, &out.slotId, &placed }, options);
  tree.build(boxes.size(), bounds);
  if (order == 0 || order == 1)
  {
    tree.buildAll();
    VTKRT_CHECK(tree.complete());
  }
  if (order == 3)
  {
    std::vector<std::thread> threads;
    for (int k = 0; k < 4; ++k)
    {
      threads.emplace_back([&tree, k]() {
        for (std::size_t b = 0; b < tree.bucketCount(); ++b)
        {
          tree.subtree(static_cast<std::uint32_t>((b * 7 + k * 13) % tree.bucketCount()));
        }
      });
    }
    for (auto& t : threads)
    {
      t.join();
    }
  }
  Walk w{ tree, boxes, out.slotId, leafSize, {}, {}, 0 };
  w.run();
  VTKRT_CHECK(tree.complete());
  out.slots = w.Slots;
  out.shape = w.Shape;
  out.depth = w.MaxDepth;
  for (auto& p : placed)
  {
    out.placedOnce = out.placedOnce && p.load() == 1;
  }
  return out;
}

void check(const char* name, const std::vector<AABB<double>>& boxes, const AABB<double>& bounds, std::uint32_t leafSize)
{
  std::printf("%s: %zu primitives, leaf size %u\n", name, boxes.size(), leafSize);
  Built ref = build(boxes, bounds, leafSize, 0);
  VTKRT_CHECK(ref.placedOnce);
  VTKRT_CHECK(ref.slots.size() == boxes.size());
  for (std::size_t i = 0; i < ref.slots.size(); ++i)
  {
    VTKRT_CHECK(ref.slots[i] == i); // leaves cover the slots in order
  }
  VTKRT_CHECK(ref.depth <= kMaxStackSize);
  for (int order = 1; order <= 3; ++order)
  {
    const Built b = build(boxes, bounds, leafSize, order);
    VTKRT_CHECK_MSG(b.placedOnce, "order %d", order);
    VTKRT_CHECK_MSG(b.slotId == ref.slotId && b.shape == ref.shape, "order %d gives another tree", order);
  }
}

std::vector<AABB<double>> triangleBoxes(const MeshData& m)
{
  std::vector<AABB<double>> boxes;
  for (std::size_t t = 0; t < m.triangleCount(); ++t)
  {
    AABB<double> b;
    for (int k = 0; k < 3; ++k)
    {
      b.extend(m.vertices[m.indices[3 * t + k]]);
    }
    boxes.push_back(b);
  }
  return boxes;
}

AABB<double> boundsOf(const std::vector<AABB<double>>& boxes)
{
  AABB<double> b;
  for (const auto& x : boxes)
  {
    b.extend(x);
  }
  return b;
}

} // namespace

int main()
{
  Rng rng(17);
  check("empty", {}, AABB<double>(), 8);
  const std::vector<AABB<double>> one{ AABB<double>(Vec3<double>(1.0), Vec3<double>(2.0)) };
  check("one", one, boundsOf(one), 8);

  // A closed surface, big enough for several bucket levels.
  const auto sphere = triangleBoxes(makeIcosphere(6)); // 81920 triangles
  check("icosphere", sphere, boundsOf(sphere), 8);
  check("icosphere, leaf 1", sphere, boundsOf(sphere), 1);

  // A soup with an outlier far away, duplicates and a crowd in one spot:
  // equal codes, empty buckets, one bucket holding nearly everything.
  MeshData soup = makeTriangleSoup(rng, 20000, 1.0);
  std::vector<AABB<double>> boxes = triangleBoxes(soup);
  for (int i = 0; i < 3000; ++i)
  {
    boxes.push_back(boxes[i % 7]); // duplicates
  }
  for (int i = 0; i < 3000; ++i)
  {
    const Vec3<double> p(0.5 + 1e-12 * i, 0.5, 0.5);
    boxes.push_back(AABB<double>(p, p)); // a crowd of points
  }
  boxes.push_back(AABB<double>(Vec3<double>(1e6), Vec3<double>(1e6 + 1.0))); // the outlier
  check("soup with outlier", boxes, boundsOf(boxes), 8);

  // Bounds that miss some centroids: they clamp to the border buckets.
  AABB<double> tight = boundsOf(sphere);
  tight.max = tight.center();
  check("icosphere, bounds too small", sphere, tight, 4);
  return testResult("TestCoreWideBVH");
}
