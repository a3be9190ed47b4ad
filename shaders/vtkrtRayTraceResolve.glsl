// vtkrt: copies the pass's accumulation buffer out to the renderer's
// framebuffer. The buffer holds, per pixel, the sum of the hit samples'
// colors (RGB) and their count (A) over all accumulated samples; dividing by
// the number of samples gives the color premultiplied by the pixel's
// coverage, blended over VTK's own background (ONE, ONE_MINUS_SRC_ALPHA), so
// silhouettes blend with any background. The depth is the accumulation's
// depth: the nearest hit of the first accumulated frame's samples.

in vec2 texCoord;
layout(location = 0) out vec4 fragOutput0;

uniform sampler2D uAccumulation;
uniform sampler2D uAccumulationDepth;
uniform float uInverseSamples; // 1 / samples accumulated per pixel

void main()
{
  vec4 sum = texture(uAccumulation, texCoord);
  if (sum.a <= 0.0)
  {
    discard;
  }
  fragOutput0 = vec4(sum.rgb * uInverseSamples, min(1.0, sum.a * uInverseSamples));
  gl_FragDepth = texture(uAccumulationDepth, texCoord).r;
}
