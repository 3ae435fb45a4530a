//VTK::System::Dec
// The reduction of the blend modes besides Composite (see the brick shader's
// HO_REDUCE) resolved into a premultiplied colour, as src/render/intensity.rs
// resolves it, then blended over the window:
//   maximum, minimum: m the extreme value, (a(m) c(m), a(m));
//   average:          g = sum / weight, (g, g, g, 1);
//   additive:         g = sum where the pixel's ray crosses the volume's box
//                     in front of opaque geometry, (g, g, g, 1);
// g clamped to [0, 1]; transparent without a sample. Each target texel is
// resolved before the bilinear filter of a coarser image sample distance
// (a filtered maximum is no maximum).
in vec2 texCoord;
uniform sampler2D composited;
uniform sampler2D transferTable;
uniform sampler2D opaqueDepth;
uniform vec2 tableScaleShift;
uniform int reduceMode; // 1 maximum, 2 minimum, 3 average, 4 additive
uniform vec2 targetSize;
uniform vec2 depthScale;
uniform vec2 depthSize;
uniform mat4 DCMC;
uniform vec3 volumeLo;
uniform vec3 volumeHi;
//VTK::Output::Dec

// Whether the ray of target texel t crosses the volume's box before the
// opaque depth there (and between the near and far planes).
bool crossed(ivec2 t)
{
  vec2 ndc = (vec2(t) + vec2(0.5)) / targetSize * 2.0 - 1.0;
  ivec2 d = clamp(ivec2((vec2(t) + vec2(0.5)) * depthScale), ivec2(0), ivec2(depthSize) - ivec2(1));
  float opaque = texelFetch(opaqueDepth, d, 0).r;
  vec4 n = DCMC * vec4(ndc, -1.0, 1.0);
  vec4 f = DCMC * vec4(ndc, opaque * 2.0 - 1.0, 1.0);
  vec3 a = n.xyz / n.w;
  vec3 b = f.xyz / f.w;
  vec3 inv = 1.0 / (b - a);
  vec3 t1 = (volumeLo - a) * inv;
  vec3 t2 = (volumeHi - a) * inv;
  float tIn = max(max(max(min(t1.x, t2.x), min(t1.y, t2.y)), min(t1.z, t2.z)), 0.0);
  float tOut = min(min(min(max(t1.x, t2.x), max(t1.y, t2.y)), max(t1.z, t2.z)), 1.0);
  return tIn <= tOut && tIn < 1.0;
}

vec4 resolved(ivec2 t)
{
  vec4 r = texelFetch(composited, t, 0);
  if (reduceMode <= 2)
  {
    if (r.g <= 0.0)
    {
      return vec4(0.0);
    }
    float m = reduceMode == 1 ? r.r : -r.r;
    vec4 c = texture(transferTable, vec2(m * tableScaleShift.x + tableScaleShift.y, 0.5));
    float a = clamp(c.a, 0.0, 1.0);
    return vec4(clamp(c.rgb, 0.0, 1.0) * a, a);
  }
  if (reduceMode == 3)
  {
    return r.g > 0.0 ? vec4(vec3(clamp(r.r / r.g, 0.0, 1.0)), 1.0) : vec4(0.0);
  }
  return crossed(t) ? vec4(vec3(clamp(r.r, 0.0, 1.0)), 1.0) : vec4(0.0);
}

void main()
{
  vec2 p = texCoord * targetSize - vec2(0.5);
  ivec2 i = ivec2(floor(p));
  vec2 f = p - vec2(i);
  ivec2 top = ivec2(targetSize) - ivec2(1);
  vec4 c00 = resolved(clamp(i, ivec2(0), top));
  vec4 c10 = resolved(clamp(i + ivec2(1, 0), ivec2(0), top));
  vec4 c01 = resolved(clamp(i + ivec2(0, 1), ivec2(0), top));
  vec4 c11 = resolved(clamp(i + ivec2(1, 1), ivec2(0), top));
  gl_FragData[0] = mix(mix(c00, c10, f.x), mix(c01, c11, f.x), f.y);
}
