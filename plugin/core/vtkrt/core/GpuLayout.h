// The records the GPU tracer reads, as C++ structs: every scene buffer is an
// RGBA32UI texture buffer (16-byte texels; floats stored as their bits,
// integers bit exact), and each struct below is a whole number of texels.
// The C++ writes the fields by name; the shader reads them by the same names:
// glslLayout() generates, from offsetof and sizeof of these structs, a GLSL
// struct of the same name and fields per record and its reader (fetchNode
// ...), so the two cannot drift apart. The C++ twins of the shader's walks
// read the records through readers of the same names (GpuTraversal.h).
#ifndef vtkrt_core_GpuLayout_h
#define vtkrt_core_GpuLayout_h

#include <glm/glm.hpp>

#include <cassert>
#include <cctype>
#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <sstream>
#include <string>
#include <type_traits>
#include <vector>

namespace vtkrt::core::gpu
{

// The shader's vector types: the records' fields and the twins' values.
using vec2 = glm::vec2;
using vec3 = glm::vec3;
using vec4 = glm::vec4;
using uvec2 = glm::uvec2;
using uvec3 = glm::uvec3;
using uvec4 = glm::uvec4;

/// Bytes of one texel of an RGBA32UI texture buffer.
constexpr std::size_t kTexelBytes = 16;

/// One texel, for buffers that hold records of several types.
struct Texel
{
  std::uint32_t v[4];
};

// Each record's fields are listed once, in order, by a macro next to it:
// FIELD(record, member) for what the shader reads, PAD(record, member) for
// padding (no GLSL member). VTKRT_GPU_RECORDS below checks that a list
// covers its struct.

/// Node of a flattened BVH: count == 0 is an interior node whose children
/// are nodes index and index + 1; count > 0 a leaf over primitives
/// [index, index + count). Boxes are float, rounded outward.
struct Node
{
  vec3 lo;
  std::uint32_t index;
  vec3 hi;
  std::uint32_t count;
};
#define VTKRT_GPU_NODE_FIELDS(FIELD, PAD)                                                          \
  FIELD(Node, lo) FIELD(Node, index) FIELD(Node, hi) FIELD(Node, count)

/// A triangle's vertices relative to its geometry's origin, its VTK cell id
/// and which of its edges are edges of that cell (TriangleEdges bits).
struct Triangle
{
  vec3 v0;
  std::uint32_t cellId;
  vec3 v1;
  std::uint32_t cellEdges;
  vec3 v2;
  float unused2;
};
#define VTKRT_GPU_TRIANGLE_FIELDS(FIELD, PAD)                                                      \
  FIELD(Triangle, v0) FIELD(Triangle, cellId) FIELD(Triangle, v1) FIELD(Triangle, cellEdges)       \
    FIELD(Triangle, v2) PAD(Triangle, unused2)

/// Triangle::cellEdges bits, as vtkOpenGLIndexBufferObject numbers a
/// triangle's edges: v0-v1, v1-v2, v2-v0.
enum TriangleEdges : std::uint32_t
{
  kEdge01 = 1u,
  kEdge12 = 2u,
  kEdge20 = 4u,
  kAllEdges = 7u
};

/// The point ids of a triangle's vertices (for normals and point colors).
struct TriangleVertices
{
  uvec3 ids;
  std::uint32_t unused;
};
#define VTKRT_GPU_TRIANGLE_VERTICES_FIELDS(FIELD, PAD)                                             \
  FIELD(TriangleVertices, ids) PAD(TriangleVertices, unused)

/// A sphere relative to its geometry's origin (radius 0: sized per frame).
struct Sphere
{
  vec3 center;
  float radius;
};
#define VTKRT_GPU_SPHERE_FIELDS(FIELD, PAD) FIELD(Sphere, center) FIELD(Sphere, radius)

/// An ellipsoid: the rows of the affine map [A | b] of its geometry's local
/// space onto its unit sphere. It shares the sphere buffer, whose leaf
/// indices count texels: one ellipsoid takes three primitive slots and is
/// read at its first texel.
struct Ellipsoid
{
  vec4 rows[3];
};
#define VTKRT_GPU_ELLIPSOID_FIELDS(FIELD, PAD) FIELD(Ellipsoid, rows)
constexpr std::uint32_t kEllipsoidTexels = 3;

/// One segment of a line drawn as a tube: its end points relative to its
/// geometry's origin and their VTK point ids (point colors). It shares the
/// sphere buffer as ellipsoids do: two primitive slots, read at its first
/// texel. Its radii come with each frame (the instance's screenRadiusPlane).
struct Segment
{
  vec3 a;
  std::uint32_t pointId0;
  vec3 b;
  std::uint32_t pointId1;
};
#define VTKRT_GPU_SEGMENT_FIELDS(FIELD, PAD)                                                       \
  FIELD(Segment, a) FIELD(Segment, pointId0) FIELD(Segment, b) FIELD(Segment, pointId1)
constexpr std::uint32_t kSegmentTexels = 2;

/// A point normal, or a cell normal (indexed by VTK cell id).
struct Normal
{
  vec3 direction;
  float unused;
};
#define VTKRT_GPU_NORMAL_FIELDS(FIELD, PAD) FIELD(Normal, direction) PAD(Normal, unused)

/// Where the walks of the camera rays of one screen tile start
/// (VTKRT_TILE_ENTRIES): node ids (into the nodes' buffer) at words
/// [first, first + count) of the same buffer, four to a texel, count >= 1,
/// each pushed on the walk's stack when the ray meets its box, in order
/// (the nearest last, so that it is walked first).
struct TileList
{
  std::uint32_t first;
  std::uint32_t count;
  std::uint32_t unused[2];
};
#define VTKRT_GPU_TILE_LIST_FIELDS(FIELD, PAD)                                                     \
  FIELD(TileList, first) FIELD(TileList, count) PAD(TileList, unused)

/// The per-instance record, rewritten every frame (its matrix and box are
/// camera-relative). Scalar colors replace the ambient and diffuse colors,
/// weighted by the two intensities (as VTK 9.1 does); screen-sized spheres
/// take the local radius max(0, dot(screenRadiusPlane.xyz, center) + .w)
/// and their BVH boxes grow by sphereGrow local units.
struct InstanceRecord
{
  vec4 cameraToLocal[3];     ///< rows of the camera-to-local affine matrix
  vec3 boxMin;               ///< camera-space box, padded for float rounding
  std::uint32_t root;        ///< the bottom-level BVH's root node
  vec3 boxMax;
  std::uint32_t flags;       ///< InstanceFlags
  vec3 ambient;              ///< colors weighted by their intensities
  float specularPower;
  vec3 diffuse;
  std::uint32_t colorBase;   ///< first packed color (or color texture header)
  vec3 specular;
  std::uint32_t normalBase;  ///< first point (or, with CellNormals, cell) normal
  std::uint32_t firstClipPlane;
  std::uint32_t clipPlaneCount;
  std::uint32_t propIndex;
  std::uint32_t compositeIndex; ///< what hardware selection's composite pass reports
  float ambientIntensity;
  float diffuseIntensity;
  float sphereGrow;
  float opacity;               ///< vtkProperty::Opacity (Translucent instances)
  vec4 screenRadiusPlane;
  vec3 backAmbient;            ///< BackfaceProperty colors, weighted by its intensities
  std::uint32_t textureBase;   ///< Textured: first word of the texture's header
  vec3 backDiffuse;
  std::uint32_t textureCoordinateBase; ///< Textured: first word of the points' (s, t)
  vec3 backSpecular;
  float backSpecularPower;
  vec4 localToCamera[3];       ///< SurfaceEdges / Wireframe: rows of the inverse of cameraToLocal
  vec3 edgeColor;              ///< SurfaceEdges: vtkProperty::EdgeColor
  float lineWidth;             ///< SurfaceEdges / Wireframe: in pixels
  /// SphereCellIds: word sphereCellIdBase + p of uSpheres is the VTK cell
  /// id of the sphere at texel p (the cell ids follow the geometry's records).
  std::uint32_t sphereCellIdBase;
  std::uint32_t unused[3];
};
#define VTKRT_GPU_INSTANCE_FIELDS(FIELD, PAD)                                                      \
  FIELD(InstanceRecord, cameraToLocal) FIELD(InstanceRecord, boxMin) FIELD(InstanceRecord, root)   \
    FIELD(InstanceRecord, boxMax) FIELD(InstanceRecord, flags) FIELD(InstanceRecord, ambient)      \
      FIELD(InstanceRecord, specularPower) FIELD(InstanceRecord, diffuse)                          \
        FIELD(InstanceRecord, colorBase) FIELD(InstanceRecord, specular)                           \
          FIELD(InstanceRecord, normalBase) FIELD(InstanceRecord, firstClipPlane)                  \
            FIELD(InstanceRecord, clipPlaneCount) FIELD(InstanceRecord, propIndex)                 \
              FIELD(InstanceRecord, compositeIndex) FIELD(InstanceRecord, ambientIntensity)          \
                FIELD(InstanceRecord, diffuseIntensity) FIELD(InstanceRecord, sphereGrow)          \
                  FIELD(InstanceRecord, opacity) FIELD(InstanceRecord, screenRadiusPlane)    \
                    FIELD(InstanceRecord, backAmbient) FIELD(InstanceRecord, textureBase)      \
                      FIELD(InstanceRecord, backDiffuse)                                       \
                        FIELD(InstanceRecord, textureCoordinateBase)                           \
                          FIELD(InstanceRecord, backSpecular)                                  \
                            FIELD(InstanceRecord, backSpecularPower)                           \
                              FIELD(InstanceRecord, localToCamera)                             \
                                FIELD(InstanceRecord, edgeColor)                               \
                                  FIELD(InstanceRecord, lineWidth)                               \
                                    FIELD(InstanceRecord, sphereCellIdBase)                      \
                                      PAD(InstanceRecord, unused)

/// The texels of an InstanceRecord that a traced pixel reads in any scene
/// (matrix, box, root, flags, colors, normal base, ids, intensities,
/// opacity): a shader of one instance holds them apart from the rest
/// (uInstance and uInstanceTail), so that they alone can be flat inputs.
constexpr std::size_t kInstanceHeadTexels = 10;
static_assert(offsetof(InstanceRecord, opacity) + sizeof(float) <= kInstanceHeadTexels * kTexelBytes &&
    offsetof(InstanceRecord, screenRadiusPlane) == kInstanceHeadTexels * kTexelBytes,
  "InstanceRecord: the fields every pixel reads fill the head texels, the rest starts after them");

/// How the shader indexes a record's buffer: record i is texels
/// i * texels + k (ByRecord), or starts at texel i (ByTexel: ellipsoids
/// and segments, whose buffer also holds one-texel spheres).
enum class Indexing
{
  ByRecord,
  ByTexel
};

/// Every record: RECORD(type, NAME, indexing, fields), NAME naming the
/// GLSL's VTKRT_<NAME>_TEXELS, fields the record's field list.
#define VTKRT_GPU_RECORDS(RECORD, FIELD, PAD)                                                      \
  RECORD(Node, NODE, ByRecord, VTKRT_GPU_NODE_FIELDS(FIELD, PAD))                                  \
  RECORD(Triangle, TRIANGLE, ByRecord, VTKRT_GPU_TRIANGLE_FIELDS(FIELD, PAD))                      \
  RECORD(TriangleVertices, TRIANGLE_VERTICES, ByRecord,                                            \
    VTKRT_GPU_TRIANGLE_VERTICES_FIELDS(FIELD, PAD))                                                \
  RECORD(Sphere, SPHERE, ByRecord, VTKRT_GPU_SPHERE_FIELDS(FIELD, PAD))                            \
  RECORD(Ellipsoid, ELLIPSOID, ByTexel, VTKRT_GPU_ELLIPSOID_FIELDS(FIELD, PAD))                    \
  RECORD(Segment, SEGMENT, ByTexel, VTKRT_GPU_SEGMENT_FIELDS(FIELD, PAD))                          \
  RECORD(Normal, NORMAL, ByRecord, VTKRT_GPU_NORMAL_FIELDS(FIELD, PAD))                            \
  RECORD(TileList, TILE_LIST, ByRecord, VTKRT_GPU_TILE_LIST_FIELDS(FIELD, PAD))                    \
  RECORD(InstanceRecord, INSTANCE, ByRecord, VTKRT_GPU_INSTANCE_FIELDS(FIELD, PAD))

/// A field list entry that expands to nothing.
#define VTKRT_GPU_NO_FIELD(record, member)

/// Flags of InstanceRecord::flags. X(name, bit) lists them once: the enum
/// and the GLSL constants kInstance<name> come from the same list.
#define VTKRT_GPU_INSTANCE_FLAGS(X)                                                                \
  X(Spheres, 1u)                                                                                   \
  X(Lit, 2u)                                                                                       \
  X(VertexNormals, 4u)                                                                             \
  X(PointColors, 8u)                                                                               \
  X(CellColors, 16u)                                                                               \
  X(Mirrored, 32u)                                                                                 \
  X(Ellipsoids, 64u)                                                                               \
  X(ColorTexture, 128u)                                                                            \
  X(CellNormals, 256u)                                                                             \
  X(Textured, 512u)                                                                                \
  X(TextureOnBackface, 1024u)                                                                      \
  X(BackfaceProperty, 2048u)                                                                       \
  X(CullBackfaces, 4096u)                                                                          \
  X(CullFrontfaces, 8192u)                                                                         \
  X(TextureCutOuts, 16384u)                                                                        \
  X(Translucent, 32768u)                                                                           \
  X(SurfaceEdges, 65536u)                                                                          \
  X(Wireframe, 131072u)                                                                            \
  X(Tubes, 262144u)                                                                                \
  X(SphereCellIds, 524288u)                                                                        \
  X(ScreenSpheres, 1048576u)

enum InstanceFlags : std::uint32_t
{
#define VTKRT_GPU_FLAG_ENUM(name, bit) kInstance##name = bit,
  VTKRT_GPU_INSTANCE_FLAGS(VTKRT_GPU_FLAG_ENUM)
#undef VTKRT_GPU_FLAG_ENUM
};

/// One switched-on light, as vtkOpenGLRenderer hands it to the raster
/// mapper, in the shader's coordinates (uploaded as uniform arrays).
struct Light
{
  float color[3];       ///< diffuse color times intensity
  float direction[3];   ///< unit, away from the light
  float position[3];    ///< relative to the shader's origin
  float attenuation[3];
  float cone[3];        ///< cone angle, exponent, positional (0 or 1)
};

template <class T>
constexpr std::uint32_t texelsOf()
{
  return static_cast<std::uint32_t>(sizeof(T) / kTexelBytes);
}

/// The InstanceRecord's texels after its head (uInstanceTail).
constexpr std::size_t kInstanceTailTexels = texelsOf<InstanceRecord>() - kInstanceHeadTexels;

/// The first texel of record i of a buffer of Records.
template <class Record>
constexpr int firstTexel(Indexing indexing, int i)
{
  return indexing == Indexing::ByRecord ? i * static_cast<int>(texelsOf<Record>()) : i;
}

namespace detail
{
/// A record field's GLSL type: a scalar or vector the size of its C++
/// type (an array field: of its element).
template <class T>
struct GlslType;
template <>
struct GlslType<float>
{
  static constexpr const char* name = "float";
  static constexpr bool isUint = false;
};
template <>
struct GlslType<std::uint32_t>
{
  static constexpr const char* name = "uint";
  static constexpr bool isUint = true;
};
template <>
struct GlslType<vec3>
{
  static constexpr const char* name = "vec3";
  static constexpr bool isUint = false;
};
template <>
struct GlslType<vec4>
{
  static constexpr const char* name = "vec4";
  static constexpr bool isUint = false;
};
template <>
struct GlslType<uvec3>
{
  static constexpr const char* name = "uvec3";
  static constexpr bool isUint = true;
};

/// Whether a field at `offset` keeps each element within one texel (the
/// GLSL reads an element as one swizzle of one texel).
template <class Member>
constexpr bool elementsLieInTexels(std::size_t offset)
{
  using Element = std::remove_all_extents_t<Member>;
  for (std::size_t e = 0; e < sizeof(Member) / sizeof(Element); ++e)
  {
    const std::size_t at = offset + e * sizeof(Element);
    if (at % kTexelBytes + sizeof(Element) > kTexelBytes)
    {
      return false;
    }
  }
  return true;
}

/// One record field as the GLSL reads it.
struct GlslField
{
  const char* name;         ///< the C++ member's name
  const char* type;         ///< GLSL type of the field (of an element, for an array)
  bool isUint;              ///< read as bits, else uintBitsToFloat of them
  std::size_t offset;       ///< bytes from the record's start
  std::size_t elementBytes; ///< bytes of the field (of an element, for an array)
  std::size_t count;        ///< array length; 0: not an array
};

template <class Member>
GlslField glslField(const char* name, std::size_t offset)
{
  using Element = std::remove_extent_t<Member>;
  static_assert(std::rank_v<Member> <= 1, "record fields are scalars, vectors or arrays of them");
  return { name, GlslType<Element>::name, GlslType<Element>::isUint, offset, sizeof(Element),
    std::extent_v<Member> };
}

/// The components of its texel that a field element of `bytes` at `offset` takes.
inline const char* swizzle(std::size_t offset, std::size_t bytes)
{
  static const char* table[4][4] = { { "x", "xy", "xyz", "xyzw" }, { "y", "yz", "yzw", "" },
    { "z", "zw", "", "" }, { "w", "", "", "" } };
  return table[(offset % kTexelBytes) / 4][bytes / 4 - 1];
}

/// The GLSL value of a field element at `offset` of a record whose texel k
/// is the expression texel(k).
template <class TexelExpression>
std::string glslElement(const GlslField& f, std::size_t offset, TexelExpression&& texel)
{
  const std::string bits = texel(offset / kTexelBytes) + "." + swizzle(offset, f.elementBytes);
  return f.isUint ? bits : "uintBitsToFloat(" + bits + ")";
}

/// The GLSL of a record: VTKRT_<NAME>_TEXELS, a struct of the record's name
/// with a member per field, and its reader <Type> fetch<Type>(b, i), which
/// fetches the texels holding those fields once each.
inline void writeGlslRecord(std::ostream& s, const char* type, const char* name, std::uint32_t texels,
  Indexing indexing, std::initializer_list<GlslField> fields)
{
  s << "#define VTKRT_" << name << "_TEXELS " << texels << "\n";
  s << "struct " << type << "\n{\n";
  std::vector<bool> used(texels, false);
  for (const GlslField& f : fields)
  {
    s << "  " << f.type << " " << f.name;
    if (f.count > 0)
    {
      s << "[" << f.count << "]";
    }
    s << ";\n";
    for (std::size_t e = 0; e < (f.count > 0 ? f.count : 1); ++e)
    {
      used[(f.offset + e * f.elementBytes) / kTexelBytes] = true;
    }
  }
  s << "};\n";
  const auto texel = [](std::size_t k) { return "t" + std::to_string(k); };
  const auto writeFields = [&]() {
    s << "  " << type << " r;\n";
    for (const GlslField& f : fields)
    {
      if (f.count == 0)
      {
        s << "  r." << f.name << " = " << glslElement(f, f.offset, texel) << ";\n";
      }
      for (std::size_t e = 0; e < f.count; ++e)
      {
        s << "  r." << f.name << "[" << e << "] = " << glslElement(f, f.offset + e * f.elementBytes, texel)
          << ";\n";
      }
    }
    s << "  return r;\n}\n";
  };
  // The texels the fields use, t<k> = source(k), then the fields from them.
  const auto writeBody = [&](const auto& source) {
    for (std::uint32_t k = 0; k < texels; ++k)
    {
      if (used[k])
      {
        s << "  uvec4 t" << k << " = " << source(k) << ";\n";
      }
    }
    writeFields();
  };
  s << type << " fetch" << type << "(usamplerBuffer b, int i)\n{\n";
  s << "  int first = " << (indexing == Indexing::ByRecord ? "i * VTKRT_" + std::string(name) + "_TEXELS" : "i")
    << ";\n";
  writeBody([](std::uint32_t k) { return "texelFetch(b, first + " + std::to_string(k) + ")"; });
  // The same record from texels held elsewhere (a uniform array).
  s << type << " unpack" << type << "(uvec4 t[VTKRT_" << name << "_TEXELS])\n{\n";
  writeBody([](std::uint32_t k) { return "t[" + std::to_string(k) + "]"; });
}

/// One accessor per field of the records of a uniform buffer, for a shader
/// that reads a record's fields at different places: <prefix><Member>(i)
/// (an array field: <prefix><Member>(i, e), its elements whole texels).
/// Where `single` is #defined, the shader's one record is in uvec4 arrays
/// (declared by the shader: the pass's frame constants) instead, its first
/// `headTexels` texels in `uniformArray`, the rest in `tailArray` (i is then
/// 0): its reads are the same for every pixel, so not fetched per pixel.
inline void writeGlslAccessors(std::ostream& s, const char* prefix, const char* buffer, const char* name,
  const char* single, const char* uniformArray, const char* tailArray, std::size_t headTexels,
  std::initializer_list<GlslField> fields)
{
  for (const GlslField& f : fields)
  {
    const std::string member = std::string(1, static_cast<char>(std::toupper(f.name[0]))) + (f.name + 1);
    const bool array = f.count > 0;
    assert((!array || f.elementBytes == kTexelBytes) && "an accessor's array elements are whole texels");
    assert((!array || f.offset / kTexelBytes >= headTexels || f.offset / kTexelBytes + f.count <= headTexels) &&
      "an accessor's array lies in the head texels or after them");
    s << f.type << " " << prefix << member << (array ? "(int i, int e)" : "(int i)") << "\n{\n";
    const auto texel = [&](std::size_t k) {
      return std::string("texelFetch(") + buffer + ", i * VTKRT_" + name + "_TEXELS + " + std::to_string(k) +
        (array ? " + e)" : ")");
    };
    const auto uniformTexel = [&](std::size_t k) {
      const bool head = k < headTexels;
      return std::string(head ? uniformArray : tailArray) + "[" + std::to_string(head ? k : k - headTexels) +
        (array ? " + e]" : "]");
    };
    s << "#ifdef " << single << "\n  return " << glslElement(f, f.offset, uniformTexel) << ";\n#else\n";
    s << "  return " << glslElement(f, f.offset, texel) << ";\n#endif\n}\n";
  }
}
} // namespace detail

// The checks that the records' GLSL relies on.
static_assert(sizeof(Texel) == kTexelBytes, "Texel: 16 bytes");
#define VTKRT_GPU_FIELD_BYTES(record, member) +sizeof(record::member)
#define VTKRT_GPU_FIELD_IN_TEXELS(record, member)                                                  \
  &&detail::elementsLieInTexels<decltype(record::member)>(offsetof(record, member))
#define VTKRT_GPU_CHECK_RECORD(type, NAME, indexing, fields)                                       \
  static_assert(sizeof(type) % kTexelBytes == 0, #type ": a whole number of texels");              \
  static_assert(std::is_trivially_copyable_v<type> && std::is_standard_layout_v<type>,             \
    #type ": uploaded as bytes");
#define VTKRT_GPU_CHECK_FIELDS(type, NAME, indexing, fields)                                       \
  static_assert(0 fields == sizeof(type), #type ": its field list names every member");
#define VTKRT_GPU_CHECK_TEXELS(type, NAME, indexing, fields)                                       \
  static_assert(true fields, #type ": a field's elements each lie in one texel");
VTKRT_GPU_RECORDS(VTKRT_GPU_CHECK_RECORD, VTKRT_GPU_NO_FIELD, VTKRT_GPU_NO_FIELD)
VTKRT_GPU_RECORDS(VTKRT_GPU_CHECK_FIELDS, VTKRT_GPU_FIELD_BYTES, VTKRT_GPU_FIELD_BYTES)
VTKRT_GPU_RECORDS(VTKRT_GPU_CHECK_TEXELS, VTKRT_GPU_FIELD_IN_TEXELS, VTKRT_GPU_NO_FIELD)
#undef VTKRT_GPU_FIELD_BYTES
#undef VTKRT_GPU_FIELD_IN_TEXELS
#undef VTKRT_GPU_CHECK_RECORD
#undef VTKRT_GPU_CHECK_FIELDS
#undef VTKRT_GPU_CHECK_TEXELS
static_assert(texelsOf<Ellipsoid>() == kEllipsoidTexels, "Ellipsoid: 3 texels");
static_assert(texelsOf<Segment>() == kSegmentTexels, "Segment: 2 texels");

/// A walk's stack entry (the shader's StackEntry) packs the node's index
/// and primitive count into one word, the count in the low kStackCountBits
/// bits: leaves hold at most kMaxPackedStackCount primitives (the pass's
/// triangle leaf sizes are clamped to it, its sphere leaves hold 16) and
/// indices (nodes, triangles, sphere texels) stay at most
/// kMaxPackedStackIndex (VTKRT_PACKED_STACK_ENTRIES); larger buffers get
/// entries of two words.
constexpr std::uint32_t kStackCountBits = 7;
constexpr std::uint32_t kMaxPackedStackCount = (1u << kStackCountBits) - 1;
constexpr std::uint32_t kMaxPackedStackIndex = (1u << (32 - kStackCountBits)) - 1;

/// The GLSL for the layouts: the instance flags kInstance<Name>, the
/// triangle edge bits kEdge01, kEdge12, kEdge20, per record
/// its struct, texel count VTKRT_<NAME>_TEXELS and readers fetch<Type>(b, i)
/// (from a buffer) and unpack<Type>(texels) (from an array the shader
/// holds), and one accessor per instance record field (instanceBoxMin(i),
/// instanceFlags(i) ...) reading the usamplerBuffer uInstances, or, in a
/// shader of one instance (VTKRT_SINGLE_INSTANCE), the arrays uInstance and
/// uInstanceTail (the pass's frame constants).
inline std::string glslLayout()
{
  std::ostringstream s;
  s << "// Generated from vtkrt/core/GpuLayout.h.\n";
#define VTKRT_GPU_FLAG_GLSL(name, bit) s << "const uint kInstance" #name " = " << bit << "u;\n";
  VTKRT_GPU_INSTANCE_FLAGS(VTKRT_GPU_FLAG_GLSL)
#undef VTKRT_GPU_FLAG_GLSL
  s << "const uint kEdge01 = " << kEdge01 << "u;\nconst uint kEdge12 = " << kEdge12
    << "u;\nconst uint kEdge20 = " << kEdge20 << "u;\n";
  s << "const uint kStackCountBits = " << kStackCountBits << "u;\nconst uint kMaxPackedStackCount = "
    << kMaxPackedStackCount << "u;\n";
#define VTKRT_GPU_GLSL_FIELD(record, member)                                                       \
  detail::glslField<decltype(record::member)>(#member, offsetof(record, member)),
#define VTKRT_GPU_GLSL_RECORD(type, NAME, indexing, fields)                                        \
  detail::writeGlslRecord(s, #type, #NAME, texelsOf<type>(), Indexing::indexing, { fields });
  VTKRT_GPU_RECORDS(VTKRT_GPU_GLSL_RECORD, VTKRT_GPU_GLSL_FIELD, VTKRT_GPU_NO_FIELD)
  s << "uniform usamplerBuffer uInstances;\n";
  detail::writeGlslAccessors(s, "instance", "uInstances", "INSTANCE", "VTKRT_SINGLE_INSTANCE", "uInstance",
    "uInstanceTail", kInstanceHeadTexels, { VTKRT_GPU_INSTANCE_FIELDS(VTKRT_GPU_GLSL_FIELD, VTKRT_GPU_NO_FIELD) });
#undef VTKRT_GPU_GLSL_RECORD
#undef VTKRT_GPU_GLSL_FIELD
  return s.str();
}

} // namespace vtkrt::core::gpu

#endif
