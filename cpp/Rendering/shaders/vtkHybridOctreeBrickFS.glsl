//VTK::System::Dec
in vec3 positionMC;
in vec3 normal;
flat in int kind;
flat in vec4 pointFrame;
flat in vec4 pointColor;
flat in float pointWeight;
// The brick's parameters (the vertex shader reads them from the frame's
// brick table, by the brick index of the vertex).
flat in vec3 brickLo;
flat in vec3 inverseStep;
flat in vec3 texels;
flat in vec3 slotOffset; // the brick's slot in its texture page (texels)
flat in float opacityRatio;
flat in vec3 boxLo;
flat in vec3 boxHi;
flat in float sliceSpacing;
flat in int jitter;
flat in float jitterScale; // P / s: the list's largest sample spacing over this brick's
flat in vec3 gradientStep; // stride * spacing (model units)
uniform sampler3D brickTexture;
uniform sampler2D transferTable;
uniform sampler2D opaqueDepth;
uniform vec3 pageTexels; // the page's texels per axis
uniform vec2 tableScaleShift;
uniform float opacityScale; // every opacity's constant factor (1: none)
uniform vec3 eye;
uniform vec3 forward;
uniform int parallel;
uniform vec4 surfaceColor;
uniform mat4 DCMC;
uniform vec2 viewportSize;
uniform vec2 depthScale;
uniform float nearDepth;
#ifdef HO_DEPENDENT2
// Two dependent fields (VTK's IndependentComponentsOff on 2 components):
// the texture holds (colour, opacity); the colour is the table's at channel
// 0, its texture coordinate value * colourScaleShift.x + colourScaleShift.y,
// the opacity the table's at channel 1 through tableScaleShift. The
// gradient (shading, gradient opacity) is channel 0's, as VTK's.
uniform vec2 colourScaleShift;
#endif
#ifdef HO_RGBA
// An RGBA volume (VTK's IndependentComponentsOff on 4 components,
// src/render/rgba.rs): the texture holds the four components (RGBA8 or
// RGBA32F), read as VTK 9.2 reads them (src/transfer/direct_colour.rs):
// the colour channels r, g, b as s = t * rgbScale + rgbBias, clamped to
// [0, 1] after the shading (VTK's computeColor); the opacity the table's
// at channel a's value v' = t * alphaDecode.x + alphaDecode.y; the value
// (scalarAt: the gradient's) is channel r's.
uniform vec3 rgbScale;
uniform vec3 rgbBias;
uniform vec2 alphaDecode;
#endif
#ifdef HO_GRADIENTS
// Gradients (shading, gradient opacity; src/render/shade.rs): the brick
// texture carries one border texel per side; the gradient is the central
// difference one texel away, over gradientStep (stride * spacing, model units).
#endif
#ifdef HO_GRADIENT_OPACITY
// Gradient opacity (src/transfer/gradient_opacity.rs): the function of the
// gradient magnitude tabulated, cell k at magnitude k end / (n - 1); its
// texture coordinate is |g| * scaleShift.x + scaleShift.y.
uniform sampler2D gradientOpacityTable;
uniform vec2 gradientOpacityScaleShift;
#endif
#ifdef HO_SHADE
// Volume shading (VTK 9.2's model, src/transfer/lighting.rs).
uniform vec4 material; // ambient, diffuse, specular, specular power
uniform int twoSided;
uniform int headlight;
uniform int lightCount;
uniform vec3 lightDirection[HO_MAX_LIGHTS];
uniform vec3 lightAmbient[HO_MAX_LIGHTS];
uniform vec3 lightDiffuse[HO_MAX_LIGHTS];
uniform vec3 lightSpecular[HO_MAX_LIGHTS];
#endif
#ifdef HO_CROP
// VTK's cropping (src/plan/crop.rs), model coordinates: the region planes
// (xmin, ymin, zmin), (xmax, ymax, zmax) and the 27 region flags.
uniform vec3 croppingLo;
uniform vec3 croppingHi;
uniform int croppingFlags;
#endif
#ifdef HO_CLIP
// VTK's clipping planes (src/plan/crop.rs), model coordinates.
uniform int clipCount;
uniform vec3 clipOrigin[HO_MAX_CLIP];
uniform vec3 clipNormal[HO_MAX_CLIP];
#endif
#ifdef HO_ISOSURFACE
// The Isosurface blend mode (src/plan/blend.rs): a sample shows the values
// c_k crossed since the sample one step s nearer the eye (v0 < c_k <= v1 or
// v1 <= c_k < v0), each (c(c_k), a(c_k)) uncorrected, nearest v0 first.
uniform int isosurfaceCount;
uniform float isosurfaceValues[HO_MAX_ISOSURFACES];
#endif
#ifdef HO_SLICE
// The Slice blend mode (src/plan/slice.rs): the geometry is the plane's
// polygon in each brick; a fragment is the sample at its position, (a c, a),
// the opacity not corrected (one sample stands for the ray), shaded with HO_SHADE.
#endif
#if defined(HO_GRADIENTS) || defined(HO_ISOSURFACE)
// The brick texture carries one border texel per side.
#define HO_BORDER
#endif
#ifdef HO_REDUCE
// The blend modes besides Composite (src/plan/blend.rs): every sample feeds
// the float target's reduction through the blend equation, resolved through
// the transfer function afterwards (vtkHybridOctreeResolveFS.glsl):
//   maximum, minimum: (v, 1, 0, 0), (-v, 1, 0, 0) under GL_MAX;
//   average, additive: (w a(v) n(v), w, 0, 0) under GL_FUNC_ADD, w = l / d0
//   (opacityRatio), n(v) = (v - lo) / (hi - lo); an average counts v in averageRange.
uniform int reduceMode; // 1 maximum, 2 minimum, 3 average, 4 additive
uniform vec2 scalarRange;
uniform vec2 averageRange;
#endif
//VTK::Output::Dec

// The brick texture's decoding: a read t (normalized for R8 and R16 codes)
// is the value bias + scale t (src/plan/texel_format.rs; 1, 0 for R32F).
uniform vec2 texelDecode; // scale, bias

// The page coordinate of the brick's texel coordinates u (texel centres at
// whole numbers): u clamped to [g, n - 1 - g], g = 1/64 of a texel (the
// middle where n < 2 + 2g), so the linear filter never reads a
// neighbouring slot (vtkOpenGLHybridOctreeBrickPages).
vec3 pageCoord(vec3 u)
{
  vec3 g = min(vec3(1.0 / 64.0), 0.5 * (texels - vec3(1.0)));
  return (slotOffset + clamp(u, g, texels - vec3(1.0) - g) + vec3(0.5)) / pageTexels;
}

// The scalar at texel coordinates u.
float scalarAt(vec3 u)
{
  return texture(brickTexture, pageCoord(u)).r * texelDecode.x + texelDecode.y;
}

// The primitive kinds (the vertex attribute kindMC, a whole number).
const int SLICE = 0;
const int SURFACE_TRIANGLE = 1;
const int RAY_MARCHED_BOX = 2;
const int SQUARE_POINT = 3;
const int GAUSSIAN_POINT = 4;

#ifdef HO_GRADIENTS
float texelAt(vec3 u)
{
  return scalarAt(u);
}

// The gradient at texel coordinates u (border included): central differences
// one texel away, g_a = (F(u + e_a) - F(u - e_a)) / (2 h_a).
vec3 gradientAt(vec3 u)
{
  return vec3(texelAt(u + vec3(1.0, 0.0, 0.0)) - texelAt(u - vec3(1.0, 0.0, 0.0)),
           texelAt(u + vec3(0.0, 1.0, 0.0)) - texelAt(u - vec3(0.0, 1.0, 0.0)),
           texelAt(u + vec3(0.0, 0.0, 1.0)) - texelAt(u - vec3(0.0, 0.0, 1.0))) /
    (2.0 * gradientStep);
}
#endif

#ifdef HO_GRADIENT_OPACITY
// a_grad(|g|), piecewise linear, held past its ends; a magnitude that is not
// a number (a difference touching no data) counts as 0.
float gradientOpacity(vec3 g)
{
  float m = length(g);
  m = isnan(m) ? 0.0 : m;
  float t = clamp(m * gradientOpacityScaleShift.x + gradientOpacityScaleShift.y, 0.0, 1.0);
  return clamp(texture(gradientOpacityTable, vec2(t, 0.5)).r, 0.0, 1.0);
}
#endif

#ifdef HO_TRANSFER_2D
// The 2D transfer function (src/transfer/transfer2d.rs; always with
// HO_GRADIENTS): colour and opacity T(v, |g|) read at x = (v - lo) / (hi - lo),
// y = min(|g| / g_max, 1) from an RGBA table with linear filtering and
// clamp-to-edge, as VTK 9.2's ray caster reads its TransferFunction2D; a
// magnitude that is not a number counts as 0. transfer2DAxes = (lo,
// 1 / (hi - lo), 1 / g_max).
uniform sampler2D transfer2DTable;
uniform vec3 transfer2DAxes;
vec4 transfer2DAt(float v, vec3 g)
{
  float m = length(g);
  m = isnan(m) ? 0.0 : m;
  vec2 t = vec2((v - transfer2DAxes.x) * transfer2DAxes.y, min(m * transfer2DAxes.z, 1.0));
  return texture(transfer2DTable, t);
}
#endif

#ifdef HO_SHADE
// The shaded colour of c with gradient g, seen along the unit ray direction
// v: N the normalised gradient (0 where it is 0 or touches no data), then
// headlight: ka c + [d > 0] (kd d Ld c + ks max(R.V, 0)^p Ls), R = 2 (N.L) N - L, L = V;
// lights:    ka sum La + kd sum [d > 0] d Ld c + ks sum [d > 0][R.V > 0] (R.V)^p Ls,
//            R = normalize(2 d N - L); d = N.L, |N.L| when two-sided; clamped to [0, 1].
vec3 shade(vec3 g, vec3 c, vec3 v)
{
  float len = length(g);
  vec3 n = (len > 0.0 && !isnan(len) && !isinf(len)) ? g / len : vec3(0.0);
  vec3 outColor;
  if (headlight != 0)
  {
    float d = dot(n, v);
    vec3 r = 2.0 * d * n - v;
    float rv = max(dot(r, v), 0.0);
    if (d < 0.0 && twoSided != 0)
    {
      d = -d;
    }
    outColor = material.x * c;
    if (d > 0.0)
    {
      outColor += material.y * d * lightDiffuse[0] * c + material.z * pow(rv, material.w) * lightSpecular[0];
    }
  }
  else
  {
    vec3 amb = vec3(0.0);
    vec3 dif = vec3(0.0);
    vec3 spe = vec3(0.0);
    for (int i = 0; i < lightCount; ++i)
    {
      vec3 l = lightDirection[i];
      float d = dot(n, l);
      if (d < 0.0 && twoSided != 0)
      {
        d = -d;
      }
      if (d > 0.0)
      {
        vec3 r = normalize(2.0 * d * n - l);
        float rv = dot(r, v);
        dif += d * lightDiffuse[i];
        if (rv > 0.0)
        {
          spe += pow(rv, material.w) * lightSpecular[i];
        }
      }
      amb += lightAmbient[i];
    }
    outColor = material.x * amb + material.y * dif * c + material.z * spe;
  }
#ifdef HO_SCATTERING
  return outColor; // clamped after the scattering's blend, as VTK's
#else
  return clamp(outColor, 0.0, 1.0);
#endif
}
#endif

#ifdef HO_SCATTERING
// Volumetric scattering (VTK 9.2's model; src/transfer/scattering.rs,
// src/render/scattering.rs; always with HO_SHADE and HO_GRADIENTS). The
// shadow rays read the shadow volume, the whole volume at up to 64 points
// per axis (one 3D texture, linear filter), through the transfer table.
// VTK's texture space: t = (p - scatterCorner) / scatterSize.
uniform sampler3D shadowVolume;
uniform vec3 scatterCorner;
uniform vec3 scatterSize;
uniform vec3 shadowScale; // shadow texture coordinate t * shadowScale + shadowShift
uniform vec3 shadowShift;
uniform float scatterBlending;   // B in [0, 2]
uniform float scatterAnisotropy; // g in [-1, 1]
uniform vec3 headlightAmbient;
uniform float gradientScale;  // VTK's shading-gradient length per world gradient, 2 / (hi - lo)
uniform float scatterExtent;  // R, texture units
uniform float sampleDistance; // VTK's d, model units
uniform float toVtk;          // d / d0
uniform int maxShadowSteps;

// 1 - (1 - a)^ratio.
float correctedOpacity(float a, float ratio)
{
  return (a <= 0.0 || a >= 1.0 || ratio == 1.0) ? a : 1.0 - exp(ratio * log(1.0 - a));
}

// Henyey-Greenstein normalised to 4 pi; 1 when |g| < 0.01.
float phaseFunction(float cosAngle)
{
  float g = scatterAnisotropy;
  if (abs(g) < 0.01)
  {
    return 1.0;
  }
  float d = 1.0 + g * g - 2.0 * g * cosAngle;
  return (1.0 - g * g) / (d * sqrt(d));
}

// The transfer table's opacity (per d0) of the shadow volume at texture point t.
float shadowOpacity(vec3 t)
{
  float v = texture(shadowVolume, t * shadowScale + shadowShift).r;
  if (isnan(v))
  {
    return 0.0;
  }
  return clamp(texture(transferTable, vec2(v * tableScaleShift.x + tableScaleShift.y, 0.5)).a, 0.0, 1.0);
}

// VTK's volumeShadow from texture point q towards `light` (a point when
// positional, else a direction), view step s0: from q + s0 n in steps of s0
// (at most maxShadowSteps equal steps, each opacity corrected for its length)
// up to min(cube exit, scatterExtent), T = prod (1 - a).
float transmittance(vec3 q, vec3 light, bool positional, float s0)
{
  vec3 n = normalize(positional ? light - q : light);
  vec3 start = q + s0 * n;
  // VTK's BBoxIntersect with the unit cube (components below 0.001 taken as +-0.001).
  vec3 d = mix(n, sign(n) * 0.001, lessThan(abs(n), vec3(0.001)));
  vec3 inv = 1.0 / d;
  vec3 ta = (vec3(0.0) - start) * inv;
  vec3 tb = (vec3(1.0) - start) * inv;
  vec3 tn = min(ta, tb);
  vec3 tf = max(ta, tb);
  float t0 = max(max(tn.x, tn.y), tn.z);
  float t1 = min(min(tf.x, tf.y), tf.z);
  if (!(t1 > max(t0, 0.0)) || t1 < s0)
  {
    return 1.0;
  }
  float reach = min(min(t1, positional ? length(light - start) : t1), scatterExtent);
  if (!(reach >= 0.001))
  {
    return 1.0;
  }
  float steps = float(maxShadowSteps);
  float s = ceil(reach / s0) > steps ? reach / steps : s0;
  float ratio = s / s0 * toVtk;
  float shadow = 1.0;
  for (int k = 0; k < maxShadowSteps && float(k) * s < reach; ++k)
  {
    shadow *= 1.0 - correctedOpacity(shadowOpacity(start + float(k) * s * n), ratio);
    if (shadow <= 0.0)
    {
      return 0.0;
    }
  }
  return shadow;
}

// The colour of the sample at model position p: straight colour c, its
// shaded colour (not clamped), opacity a (the table's, per d0, before
// gradient opacity), gradient g, unit ray direction v:
//   clamp((1 - k) shaded + k sum_i [T_i P(cos_i) kd Ld_i c + ka La_i], 0, 1),
//   k = B exp(-B |g|' a_d) (B < 1), (2 - B) exp(-B |g|' a_d) + B - 1 (B >= 1).
vec3 scatter(vec3 p, vec3 g, vec3 c, vec3 shaded, float a, vec3 v)
{
  float gl = length(g);
  float gv = (isnan(gl) || isinf(gl)) ? 0.0 : gl * gradientScale;
  float e = exp(-scatterBlending * gv * correctedOpacity(a, toVtk));
  float k = scatterBlending < 1.0 ? scatterBlending * e : (2.0 - scatterBlending) * e + scatterBlending - 1.0;
  vec3 q = (p - scatterCorner) / scatterSize;
  float s0 = length(v / scatterSize) * sampleDistance;
  vec3 secondary = vec3(0.0);
  if (headlight != 0)
  {
    float t = transmittance(q, (eye - scatterCorner) / scatterSize, true, s0);
    secondary = t * phaseFunction(-1.0) * c * material.y * lightDiffuse[0] + material.x * headlightAmbient;
  }
  else
  {
    vec3 toEye = normalize((eye - p) / scatterSize);
    for (int i = 0; i < lightCount; ++i)
    {
      vec3 towards = -lightDirection[i] / scatterSize;
      float t = transmittance(q, towards, false, s0);
      secondary += t * phaseFunction(-dot(normalize(towards), toEye)) * c * material.y * lightDiffuse[i] +
        material.x * lightAmbient[i];
    }
  }
  return clamp((1.0 - k) * shaded + k * secondary, 0.0, 1.0);
}
#endif

// The pixel's noise n(x, y) in [0, 1) (src/plan/jitter.rs): the lowbias32
// hash of x xor hash(y), (x, y) whole pixels from the top left, 24 bits
// (exact in a float, the CPU compositor's bits).
uint lowbias32(uint v)
{
  v ^= v >> 16u;
  v *= 0x7feb352du;
  v ^= v >> 15u;
  v *= 0x846ca68bu;
  v ^= v >> 16u;
  return v;
}

float pixelNoise()
{
  uint x = uint(gl_FragCoord.x);
  uint y = uint(int(viewportSize.y) - 1 - int(gl_FragCoord.y));
  return float(lowbias32(x ^ lowbias32(y)) >> 8u) / 16777216.0;
}

// Whether the sample at model position p is removed (src/plan/crop.rs):
// cropping keeps region (i, j, k) when bit i + 3 j + 9 k of the flags is
// set, a coordinate being 0 below the min plane, 1 from min to max (both
// included), 2 above the max plane; a clipping plane keeps n . (p - o) >= 0.
// Never without HO_CROP and HO_CLIP. A removed sample is no sample in every
// blend mode: not blended, not reduced, no isosurface.
bool removed(vec3 p)
{
#ifdef HO_CROP
  ivec3 r = ivec3(greaterThanEqual(p, croppingLo)) + ivec3(greaterThan(p, croppingHi));
  if (((croppingFlags >> (r.x + 3 * r.y + 9 * r.z)) & 1) == 0)
  {
    return true;
  }
#endif
#ifdef HO_CLIP
  for (int i = 0; i < clipCount; ++i)
  {
    if (dot(clipNormal[i], p - clipOrigin[i]) < 0.0)
    {
      return true;
    }
  }
#endif
  return false;
}

#ifdef HO_REDUCE
// The reduction's share of the value v (not NaN) of a sample standing for w
// reference spacings.
vec4 reductionOf(float v, float w)
{
  if (reduceMode == 1)
  {
    return vec4(v, 1.0, 0.0, 0.0);
  }
  if (reduceMode == 2)
  {
    return vec4(-v, 1.0, 0.0, 0.0);
  }
  if (reduceMode == 3 && (v < averageRange.x || v > averageRange.y))
  {
    return vec4(0.0);
  }
  float a = clamp(texture(transferTable, vec2(v * tableScaleShift.x + tableScaleShift.y, 0.5)).a, 0.0, 1.0);
  float n = scalarRange.y > scalarRange.x ? (v - scalarRange.x) / (scalarRange.y - scalarRange.x) : 0.0;
  return vec4(w * a * n, w, 0.0, 0.0);
}

// Two reductions combined as the blend equation combines them.
vec4 combined(vec4 a, vec4 b)
{
  return reduceMode <= 2 ? max(a, b) : a + b;
}

// The texel value at model position p (the unshaded lattice).
float valueAt(vec3 p)
{
  vec3 u = clamp((p - brickLo) * inverseStep, vec3(0.0), texels - vec3(1.0));
  return scalarAt(u);
}
#endif

#ifdef HO_ISOSURFACE
// Straight colour and opacity at isovalue c.
vec4 isosurfaceColor(float c)
{
  vec4 t = texture(transferTable, vec2(c * tableScaleShift.x + tableScaleShift.y, 0.5));
  return vec4(clamp(t.rgb, 0.0, 1.0), clamp(t.a, 0.0, 1.0));
}

// The isovalues crossed going from v0 to v1 composited front to back into
// one premultiplied (C, A): C = sum (1 - A_k) a_k c_k, A = sum (1 - A_k) a_k.
vec4 crossings(float v0, float v1)
{
  vec4 acc = vec4(0.0);
  for (int i = 0; i < isosurfaceCount; ++i)
  {
    // Rising: ascending values; falling: descending.
    int k = v0 < v1 ? i : isosurfaceCount - 1 - i;
    float c = isosurfaceValues[k];
    if ((v0 < v1 && v0 < c && c <= v1) || (v1 < v0 && v1 <= c && c < v0))
    {
      vec4 s = isosurfaceColor(c);
      acc += (1.0 - acc.a) * vec4(s.rgb * s.a, s.a);
    }
  }
  return acc;
}
#endif

// Opacity a' of the sample at model position p (the 2D transfer function's
// with HO_TRANSFER_2D, times opacityScale, times
// the gradient opacity with HO_GRADIENT_OPACITY, then corrected for the
// slice spacing), and its colour (shaded along the ray direction v with
// HO_SHADE). NaN texels
// are no data: the linear filter of a sample touching one is NaN (every
// corner is weighed, 0 * NaN = NaN), and such a sample is transparent black,
// as in the CPU compositor. A sample cropping or a clipping plane removes
// is transparent black (slices and ray-marched bricks both sample here).
vec4 sampleAt(vec3 p, vec3 v)
{
#if defined(HO_CROP) || defined(HO_CLIP)
  if (removed(p))
  {
    return vec4(0.0);
  }
#endif
#ifdef HO_BORDER
  vec3 u = clamp((p - brickLo) * inverseStep + vec3(1.0), vec3(1.0), texels - vec3(2.0));
#else
  vec3 u = clamp((p - brickLo) * inverseStep, vec3(0.0), texels - vec3(1.0));
#endif
  float value = scalarAt(u);
  if (isnan(value))
  {
    return vec4(0.0);
  }
#ifdef HO_ISOSURFACE
  // The sample one step nearer the eye: p - v s / (v . forward), in the border when it leaves the brick.
  vec3 b = clamp((p - v * (sliceSpacing / dot(v, forward)) - brickLo) * inverseStep + vec3(1.0),
    vec3(0.0), texels - vec3(1.0));
  vec4 crossed = crossings(scalarAt(b), value);
  if (crossed.a <= 0.0)
  {
    return vec4(0.0);
  }
  // One sample standing for them all: straight colour C / A, opacity A.
  vec4 c = vec4(crossed.rgb / crossed.a, crossed.a);
#elif defined(HO_TRANSFER_2D)
  // The gradient first: the table reads its magnitude (one gradient, shared with the shading).
  vec3 g = gradientAt(u);
  vec4 c = transfer2DAt(value, g);
#elif defined(HO_DEPENDENT2)
  float opacityValue = texture(brickTexture, pageCoord(u)).g;
  if (isnan(opacityValue))
  {
    return vec4(0.0);
  }
  vec4 c = vec4(texture(transferTable, vec2(value * colourScaleShift.x + colourScaleShift.y, 0.5)).rgb,
    texture(transferTable, vec2(opacityValue * tableScaleShift.x + tableScaleShift.y, 0.5)).a);
#elif defined(HO_RGBA)
  vec4 q = texture(brickTexture, pageCoord(u));
  vec3 s = q.rgb * rgbScale + rgbBias;
  float opacityValue = q.a * alphaDecode.x + alphaDecode.y;
  if (any(isnan(s)) || isnan(opacityValue))
  {
    return vec4(0.0);
  }
  vec4 c = vec4(s, texture(transferTable, vec2(opacityValue * tableScaleShift.x + tableScaleShift.y, 0.5)).a);
#else
  vec4 c = texture(transferTable, vec2(value * tableScaleShift.x + tableScaleShift.y, 0.5));
#endif
  float a = clamp(c.a, 0.0, 1.0) * opacityScale;
#ifdef HO_SCATTERING
  float tableOpacity = clamp(c.a, 0.0, 1.0); // VTK blends with it, before the gradient opacity
#endif
#if defined(HO_GRADIENTS) && !defined(HO_TRANSFER_2D)
  vec3 g = a > 0.0 ? gradientAt(u) : vec3(0.0);
#endif
#ifdef HO_GRADIENT_OPACITY
  a *= gradientOpacity(g);
#endif
#if !defined(HO_ISOSURFACE) && !defined(HO_SLICE)
  if (opacityRatio != 1.0 && a > 0.0 && a < 1.0)
  {
    a = 1.0 - exp(opacityRatio * log(1.0 - a));
  }
#endif
#ifdef HO_RGBA
  vec3 rgb = c.rgb; // clamped after the shading
#else
  vec3 rgb = clamp(c.rgb, 0.0, 1.0);
#endif
#ifdef HO_SHADE
  if (a > 0.0)
  {
#ifdef HO_SCATTERING
    rgb = scatter(p, g, rgb, shade(g, rgb, v), tableOpacity, v);
#else
    rgb = shade(g, rgb, v);
#endif
  }
#endif
#ifdef HO_RGBA
  rgb = clamp(rgb, 0.0, 1.0);
#endif
  return vec4(rgb, a);
}

// The view depth (x - eye) . forward of the point at this pixel and depth-buffer value d.
float viewDepth(float d)
{
  vec4 q = DCMC * vec4(gl_FragCoord.xy / viewportSize * 2.0 - 1.0, d * 2.0 - 1.0, 1.0);
  return dot(q.xyz / q.w - eye, forward);
}

void main()
{
  float opaque = texelFetch(opaqueDepth, ivec2(gl_FragCoord.xy * depthScale), 0).r;
  if (kind == RAY_MARCHED_BOX)
  {
    // A ray-marched brick: this fragment is on the exit face of its box; the
    // samples are the slice lattice z = k d between entry and exit (the same
    // samples as the slices), front to back, up to opaque geometry.
    vec3 dir = parallel != 0 ? forward : normalize(positionMC - eye);
    vec3 origin = parallel != 0 ? positionMC - forward * dot(positionMC - eye, forward) : eye;
    vec3 inv = 1.0 / dir;
    vec3 t1 = (boxLo - origin) * inv;
    vec3 t2 = (boxHi - origin) * inv;
    vec3 tn = min(t1, t2);
    vec3 tf = max(t1, t2);
    float tIn = max(max(tn.x, tn.y), tn.z);
    float tOut = min(min(tf.x, tf.y), tf.z);
    if (dot(positionMC - origin, dir) < 0.5 * (tIn + tOut))
    {
      discard; // the entry face
    }
    float cosA = dot(dir, forward);
    float zIn = max(tIn * cosA, nearDepth);
    float zOut = min(tOut * cosA, opaque < 1.0 ? viewDepth(opaque) : 1.0e30);
    // Samples at z = (k + j) d: j = 0 (the slice lattice), or jittered
    // j = frac(n P / d), n the pixel's noise: the depth offset n P is the
    // same in every brick, so every brick's lattice is one of the finest
    // brick's and a sparse lattice shows noise, not wood grain.
    float j = jitter != 0 ? fract(pixelNoise() * jitterScale) : 0.0;
    int k0 = int(ceil(zIn / sliceSpacing - j));
    int k1 = min(int(ceil(zOut / sliceSpacing - j)) - 1, k0 + 4096);
#ifdef HO_REDUCE
    // Every sample, no early termination; NaN (no data) or removed is no sample.
    vec4 R = reduceMode <= 2 ? vec4(-3.0e38, 0.0, 0.0, 0.0) : vec4(0.0);
    bool sampled = false;
    for (int k = k0; k <= k1; ++k)
    {
      vec3 p = origin + dir * ((float(k) + j) * sliceSpacing / cosA);
      float v = valueAt(p);
      if (!isnan(v) && !removed(p))
      {
        R = combined(R, reductionOf(v, opacityRatio));
        sampled = true;
      }
    }
    if (!sampled)
    {
      discard;
    }
    gl_FragData[0] = R;
    return;
#endif
    vec3 C = vec3(0.0);
    float A = 0.0;
    for (int k = k0; k <= k1 && A < 0.999; ++k)
    {
      vec4 s = sampleAt(origin + dir * ((float(k) + j) * sliceSpacing / cosA), dir);
      C += (1.0 - A) * s.a * s.rgb;
      A += (1.0 - A) * s.a;
    }
    if (A == 0.0)
    {
      discard;
    }
    gl_FragData[0] = vec4(C, A);
    return;
  }
  // Behind opaque geometry already drawn.
  if (gl_FragCoord.z > opaque)
  {
    discard;
  }
#ifdef HO_REDUCE
  // A reduced ray has no order: only the volume's samples feed it.
  if (kind != SLICE)
  {
    discard;
  }
  float v = valueAt(positionMC);
  if (isnan(v) || removed(positionMC))
  {
    discard;
  }
  gl_FragData[0] = reductionOf(v, opacityRatio);
  return;
#endif
  if (kind == SQUARE_POINT || kind == GAUSSIAN_POINT)
  {
    // A point (paper 3 section 4): its colour and opacity a_p (see the
    // header) times the footprint's coverage.
    float w = pointWeight;
    if (kind == GAUSSIAN_POINT)
    {
      vec2 f = floor(pointFrame.xy);
      if (any(greaterThan(abs(floor(gl_FragCoord.xy) - f), vec2(pointFrame.w))))
      {
        discard;
      }
      vec2 d = gl_FragCoord.xy - pointFrame.xy;
      w = min(exp(-dot(d, d) / (2.0 * pointFrame.z * pointFrame.z)) * w, 1.0);
    }
    float a = pointColor.a * w;
    if (a <= 0.0)
    {
      discard;
    }
    gl_FragData[0] = vec4(pointColor.rgb * a, a);
    return;
  }
  if (kind == SURFACE_TRIANGLE)
  {
    vec3 d = parallel != 0 ? forward : normalize(positionMC - eye);
    float len = length(normal);
    float lambert = len > 0.0 ? abs(dot(normal, d)) / len : 1.0;
    vec3 rgb = clamp(surfaceColor.rgb, 0.0, 1.0) * lambert;
    gl_FragData[0] = vec4(rgb * surfaceColor.a, surfaceColor.a);
    return;
  }
  vec4 s = sampleAt(positionMC, parallel != 0 ? forward : normalize(positionMC - eye));
  if (s.a == 0.0)
  {
    discard; // blends to nothing: skip the blend
  }
  gl_FragData[0] = vec4(s.rgb * s.a, s.a);
}
