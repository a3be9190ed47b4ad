// vtkrt: draws one traced prop's pixels for a vtkHardwareSelector pass. The
// pass traced, per pixel, the hit prop (index + 1, 0: none), the VTK id's
// low 24 and high bits and the composite index into a float buffer (exact
// for integers below 2^24); this copies the chosen value out in the
// selector's 24-bit color encoding (low byte in red, as
// vtkHardwareSelector::Convert) with the traced depth, so the props the
// selector draws with raster composite with it by depth.

in vec2 texCoord;
layout(location = 0) out vec4 fragOutput0;

uniform sampler2D uSelectIds;
uniform sampler2D uSelectDepth;
uniform float uProp;    // traced prop index + 1 whose pixels this draws
uniform int uComponent; // 0: uPropColor; 1: id low 24 bits; 2: id high bits; 3: composite index
uniform vec3 uPropColor;

vec3 encode24(float value)
{
  uint v = uint(value);
  return vec3(float(v & 255u), float((v >> 8u) & 255u), float((v >> 16u) & 255u)) / 255.0;
}

void main()
{
  ivec2 texel = ivec2(texCoord * vec2(textureSize(uSelectIds, 0)));
  vec4 ids = texelFetch(uSelectIds, texel, 0);
  if (ids.r != uProp)
  {
    discard;
  }
  vec3 color = uPropColor;
  if (uComponent == 1)
  {
    color = encode24(ids.g);
  }
  else if (uComponent == 2)
  {
    color = encode24(ids.b);
  }
  else if (uComponent == 3)
  {
    color = encode24(ids.a);
  }
  fragOutput0 = vec4(color, 1.0);
  gl_FragDepth = texelFetch(uSelectDepth, texel, 0).r;
}
