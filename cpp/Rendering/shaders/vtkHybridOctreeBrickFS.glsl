//VTK::System::Dec
in vec3 positionMC;
in vec3 normal;
flat in int kind;
flat in vec4 pointFrame;
flat in vec4 pointColor;
flat in float pointWeight;
uniform sampler3D brickTexture;
uniform sampler2D transferTable;
uniform sampler2D opaqueDepth;
uniform vec3 brickLo;
uniform vec3 inverseStep;
uniform vec3 texels;
uniform vec2 tableScaleShift;
uniform float opacityRatio;
uniform vec3 eye;
uniform vec3 forward;
uniform int parallel;
uniform vec4 surfaceColor;
uniform vec3 boxLo;
uniform vec3 boxHi;
uniform float sliceSpacing;
uniform int jitter;
uniform mat4 DCMC;
uniform vec2 viewportSize;
uniform vec2 depthScale;
uniform float nearDepth;
//VTK::Output::Dec

// The primitive kinds (the vertex attribute kindMC, a whole number).
const int SLICE = 0;
const int SURFACE_TRIANGLE = 1;
const int RAY_MARCHED_BOX = 2;
const int SQUARE_POINT = 3;
const int GAUSSIAN_POINT = 4;

// Opacity a' of the sample at model position p, and its colour. NaN texels
// are no data: the linear filter of a sample touching one is NaN (every
// corner is weighed, 0 * NaN = NaN), and such a sample is transparent black,
// as in the CPU compositor.
vec4 sampleAt(vec3 p)
{
  vec3 u = clamp((p - brickLo) * inverseStep, vec3(0.0), texels - vec3(1.0));
  float value = texture(brickTexture, (u + vec3(0.5)) / texels).r;
  if (isnan(value))
  {
    return vec4(0.0);
  }
  vec4 c = texture(transferTable, vec2(value * tableScaleShift.x + tableScaleShift.y, 0.5));
  float a = clamp(c.a, 0.0, 1.0);
  if (opacityRatio != 1.0 && a > 0.0 && a < 1.0)
  {
    a = 1.0 - exp(opacityRatio * log(1.0 - a));
  }
  return vec4(clamp(c.rgb, 0.0, 1.0), a);
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
    // Samples at z = (k + j) d: j = 0 (the slice lattice), or with jitter a
    // fraction of d fixed per pixel (interleaved gradient noise), the same in
    // every brick, so that a sparse lattice shows noise, not wood grain.
    float j = jitter != 0
      ? fract(52.9829189 * fract(dot(floor(gl_FragCoord.xy), vec2(0.06711056, 0.00583715))))
      : 0.0;
    int k0 = int(ceil(zIn / sliceSpacing - j));
    int k1 = min(int(ceil(zOut / sliceSpacing - j)) - 1, k0 + 4096);
    vec3 C = vec3(0.0);
    float A = 0.0;
    for (int k = k0; k <= k1 && A < 0.999; ++k)
    {
      vec4 s = sampleAt(origin + dir * ((float(k) + j) * sliceSpacing / cosA));
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
  vec4 s = sampleAt(positionMC);
  if (s.a == 0.0)
  {
    discard; // blends to nothing: skip the blend
  }
  gl_FragData[0] = vec4(s.rgb * s.a, s.a);
}
