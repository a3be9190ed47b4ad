// The records the GPU tracer reads, as C++ structs: every scene buffer is an
// RGBA32UI texture buffer (16-byte texels; floats stored as their bits,
// integers bit exact), and each struct below is a whole number of texels.
// The C++ writes the fields by name; the GLSL's texel offsets, swizzles and
// flag values are generated from these structs (glslLayout()), so the two
// cannot drift apart.
#ifndef vtkrt_core_GpuLayout_h
#define vtkrt_core_GpuLayout_h

#include <cassert>
#include <cstddef>
#include <cstdint>
#include <sstream>
#include <string>
#include <type_traits>

namespace vtkrt::core::gpu
{

/// Bytes of one texel of an RGBA32UI texture buffer.
constexpr std::size_t kTexelBytes = 16;

/// One texel, for buffers that hold records of several types.
struct Texel
{
  std::uint32_t v[4];
};

/// Node of a flattened BVH: count == 0 is an interior node whose children
/// are nodes index and index + 1; count > 0 a leaf over primitives
/// [index, index + count). Boxes are float, rounded outward.
struct Node
{
  float lo[3];
  std::uint32_t index;
  float hi[3];
  std::uint32_t count;
};

/// A triangle's vertices relative to its geometry's origin, and its VTK cell id.
struct Triangle
{
  float v0[3];
  std::uint32_t cellId;
  float v1[3];
  float unused1;
  float v2[3];
  float unused2;
};

/// The point ids of a triangle's vertices (for normals and point colors).
struct TriangleVertices
{
  std::uint32_t ids[3];
  std::uint32_t unused;
};

/// A sphere relative to its geometry's origin (radius 0: sized per frame).
struct Sphere
{
  float center[3];
  float radius;
};

/// An ellipsoid: the rows of the affine map [A | b] of its geometry's local
/// space onto its unit sphere. Its leaf indices count texels, so one
/// ellipsoid takes three primitive slots.
struct Ellipsoid
{
  float rows[3][4];
};
constexpr std::uint32_t kEllipsoidTexels = 3;

/// A vertex normal.
struct Normal
{
  float xyz[3];
  float unused;
};

/// The per-instance record, rewritten every frame (its matrix and box are
/// camera-relative). Scalar colors replace the ambient and diffuse colors,
/// weighted by the two intensities (as VTK 9.1 does); screen-sized spheres
/// take the local radius max(0, dot(screenRadiusPlane.xyz, center) + .w)
/// and their BVH boxes grow by sphereGrow local units.
struct InstanceRecord
{
  float cameraToLocal[3][4]; ///< rows of the camera-to-local affine matrix
  float boxMin[3];           ///< camera-space box, padded for float rounding
  std::uint32_t root;        ///< the bottom-level BVH's root node
  float boxMax[3];
  std::uint32_t flags;       ///< InstanceFlags
  float ambient[3];          ///< colors weighted by their intensities
  float specularPower;
  float diffuse[3];
  std::uint32_t colorBase;   ///< first packed color (or color texture header)
  float specular[3];
  std::uint32_t normalBase;  ///< first vertex normal
  std::uint32_t firstClipPlane;
  std::uint32_t clipPlaneCount;
  std::uint32_t propIndex;
  std::uint32_t compositeIndex; ///< what hardware selection's composite pass reports
  float ambientIntensity;
  float diffuseIntensity;
  float sphereGrow;
  float unused9;
  float screenRadiusPlane[4];
};

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
  X(ColorTexture, 128u)

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

static_assert(sizeof(Texel) == kTexelBytes, "Texel: 16 bytes");
static_assert(sizeof(Node) == 2 * kTexelBytes && offsetof(Node, hi) == kTexelBytes, "Node: 2 texels");
static_assert(sizeof(Triangle) == 3 * kTexelBytes && offsetof(Triangle, v1) == kTexelBytes &&
    offsetof(Triangle, v2) == 2 * kTexelBytes, "Triangle: 3 texels, a vertex each");
static_assert(sizeof(TriangleVertices) == kTexelBytes, "TriangleVertices: 1 texel");
static_assert(sizeof(Sphere) == kTexelBytes, "Sphere: 1 texel");
static_assert(sizeof(Ellipsoid) == kEllipsoidTexels * kTexelBytes, "Ellipsoid: 3 texels");
static_assert(sizeof(Normal) == kTexelBytes, "Normal: 1 texel");
static_assert(sizeof(InstanceRecord) == 11 * kTexelBytes, "InstanceRecord: 11 texels");
static_assert(offsetof(InstanceRecord, boxMin) == 3 * kTexelBytes &&
    offsetof(InstanceRecord, root) == 3 * kTexelBytes + 12 &&
    offsetof(InstanceRecord, firstClipPlane) == 8 * kTexelBytes &&
    offsetof(InstanceRecord, screenRadiusPlane) == 10 * kTexelBytes,
  "InstanceRecord fields keep their texels (a field must not straddle two)");
static_assert(std::is_trivially_copyable_v<InstanceRecord> && std::is_standard_layout_v<InstanceRecord>,
  "records are uploaded as bytes");

namespace detail
{
/// One record field as the GLSL reads it: which texel, which components.
struct GlslField
{
  const char* name; ///< the GLSL accessor is instance<Name>(i)
  const char* type; ///< GLSL type
  std::size_t offset;
  std::size_t bytes;
  bool isUint;
};

inline const char* swizzle(std::size_t offset, std::size_t bytes)
{
  static const char* table[4][4] = { { "x", "xy", "xyz", "xyzw" }, { "y", "yz", "yzw", "" },
    { "z", "zw", "", "" }, { "w", "", "", "" } };
  return table[(offset % kTexelBytes) / 4][bytes / 4 - 1];
}
} // namespace detail

#define VTKRT_GPU_FIELD(name, member, type, isUint)                                                \
  detail::GlslField                                                                                \
  {                                                                                                \
    name, type, offsetof(InstanceRecord, member), sizeof(InstanceRecord::member), isUint           \
  }

/// The GLSL for the layouts: texel counts, the instance flags, and one
/// accessor per instance record field (instanceBoxMin(i), instanceFlags(i)
/// ...) reading the field's texel of the usamplerBuffer uInstances.
inline std::string glslLayout()
{
  const detail::GlslField fields[] = {
    VTKRT_GPU_FIELD("CameraToLocalRow0", cameraToLocal[0], "vec4", false),
    VTKRT_GPU_FIELD("CameraToLocalRow1", cameraToLocal[1], "vec4", false),
    VTKRT_GPU_FIELD("CameraToLocalRow2", cameraToLocal[2], "vec4", false),
    VTKRT_GPU_FIELD("BoxMin", boxMin, "vec3", false),
    VTKRT_GPU_FIELD("Root", root, "uint", true),
    VTKRT_GPU_FIELD("BoxMax", boxMax, "vec3", false),
    VTKRT_GPU_FIELD("Flags", flags, "uint", true),
    VTKRT_GPU_FIELD("Ambient", ambient, "vec3", false),
    VTKRT_GPU_FIELD("SpecularPower", specularPower, "float", false),
    VTKRT_GPU_FIELD("Diffuse", diffuse, "vec3", false),
    VTKRT_GPU_FIELD("ColorBase", colorBase, "uint", true),
    VTKRT_GPU_FIELD("Specular", specular, "vec3", false),
    VTKRT_GPU_FIELD("NormalBase", normalBase, "uint", true),
    VTKRT_GPU_FIELD("FirstClipPlane", firstClipPlane, "uint", true),
    VTKRT_GPU_FIELD("ClipPlaneCount", clipPlaneCount, "uint", true),
    VTKRT_GPU_FIELD("PropIndex", propIndex, "uint", true),
    VTKRT_GPU_FIELD("CompositeIndex", compositeIndex, "uint", true),
    VTKRT_GPU_FIELD("AmbientIntensity", ambientIntensity, "float", false),
    VTKRT_GPU_FIELD("DiffuseIntensity", diffuseIntensity, "float", false),
    VTKRT_GPU_FIELD("SphereGrow", sphereGrow, "float", false),
    VTKRT_GPU_FIELD("ScreenRadiusPlane", screenRadiusPlane, "vec4", false),
  };
  std::ostringstream s;
  s << "// Generated from vtkrt/core/GpuLayout.h.\n";
  s << "#define VTKRT_NODE_TEXELS " << texelsOf<Node>() << "\n";
  s << "#define VTKRT_TRIANGLE_TEXELS " << texelsOf<Triangle>() << "\n";
  s << "#define VTKRT_ELLIPSOID_TEXELS " << texelsOf<Ellipsoid>() << "\n";
  s << "#define VTKRT_INSTANCE_TEXELS " << texelsOf<InstanceRecord>() << "\n";
#define VTKRT_GPU_FLAG_GLSL(name, bit) s << "const uint kInstance" #name " = " << bit << "u;\n";
  VTKRT_GPU_INSTANCE_FLAGS(VTKRT_GPU_FLAG_GLSL)
#undef VTKRT_GPU_FLAG_GLSL
  s << "uniform usamplerBuffer uInstances;\n";
  for (const detail::GlslField& f : fields)
  {
    const std::size_t texel = f.offset / kTexelBytes;
    assert(f.offset % kTexelBytes + f.bytes <= kTexelBytes && "a field must lie in one texel");
    s << f.type << " instance" << f.name << "(int i)\n{\n  return ";
    const char* sw = detail::swizzle(f.offset, f.bytes);
    if (f.isUint)
    {
      s << "texelFetch(uInstances, i * VTKRT_INSTANCE_TEXELS + " << texel << ")." << sw;
    }
    else
    {
      s << "uintBitsToFloat(texelFetch(uInstances, i * VTKRT_INSTANCE_TEXELS + " << texel << ")." << sw
        << ")";
    }
    s << ";\n}\n";
  }
  return s.str();
}

#undef VTKRT_GPU_FIELD

} // namespace vtkrt::core::gpu

#endif
