//VTK::System::Dec
in vec3 vertexMC;
in vec3 normalMC;
in vec2 clipMC;
in float kindMC;
in float alphaMC;
in float brickMC; // the vertex's brick: its index in the list
uniform mat4 MCDC;
// The frame's brick table: seven RGBA texels a brick, from brick brickBase
// (vtkOpenGLHybridOctreeBrickDrawer::SetBricks(), TexelsPerBrick).
uniform samplerBuffer brickTable;
uniform int brickBase;
uniform vec3 eye;
uniform vec3 forward;
uniform vec2 viewportSize;
uniform vec3 pointUp;
uniform float pointSpacing;
out vec3 positionMC;
out vec3 normal;
flat out int kind;
flat out vec4 pointFrame;
flat out vec4 pointColor;
flat out float pointWeight;
flat out vec3 brickLo;
flat out vec3 inverseStep;
flat out vec3 texels;
flat out vec3 slotOffset;
flat out float opacityRatio;
flat out vec3 boxLo;
flat out vec3 boxHi;
flat out float sliceSpacing;
flat out int jitter;
flat out float jitterScale;
flat out vec3 gradientStep;
// The primitive kinds (the vertex attribute kindMC, a whole number).
const int SLICE = 0;
const int SURFACE_TRIANGLE = 1;
const int RAY_MARCHED_BOX = 2;
const int SQUARE_POINT = 3;
const int GAUSSIAN_POINT = 4;

void main()
{
  int b = 7 * (int(brickMC + 0.5) - brickBase);
  vec4 t0 = texelFetch(brickTable, b);
  vec4 t1 = texelFetch(brickTable, b + 1);
  vec4 t2 = texelFetch(brickTable, b + 2);
  vec4 t3 = texelFetch(brickTable, b + 3);
  vec4 t4 = texelFetch(brickTable, b + 4);
  vec4 t5 = texelFetch(brickTable, b + 5);
  vec4 t6 = texelFetch(brickTable, b + 6);
  brickLo = t0.xyz;
  opacityRatio = t0.w;
  inverseStep = t1.xyz;
  sliceSpacing = t1.w;
  texels = t2.xyz;
  jitter = int(t2.w + 0.5);
  slotOffset = t3.xyz;
  jitterScale = t3.w;
  boxLo = t4.xyz;
  boxHi = t5.xyz;
  gradientStep = t6.xyz;
  positionMC = vertexMC;
  normal = normalMC;
  kind = int(kindMC + 0.5);
  pointFrame = vec4(0.0);
  pointColor = vec4(normalMC, alphaMC);
  pointWeight = 0.0;
  if (kind == SQUARE_POINT || kind == GAUSSIAN_POINT)
  {
    // A point: its footprint, s = d0 / pixel pixels across at its depth,
    // as a quad of whole pixels in window coordinates (see the header).
    vec4 c = MCDC * vec4(vertexMC, 1.0);
    vec4 c2 = MCDC * vec4(vertexMC + pointSpacing * pointUp, 1.0);
    vec2 centre = (c.xy / c.w * 0.5 + 0.5) * viewportSize;
    float s = length((c2.xy / c2.w * 0.5 + 0.5) * viewportSize - centre);
    vec2 lo;
    vec2 hi;
    float weight;
    float sigma = 0.0;
    float radius = 0.0;
    if (kind == SQUARE_POINT)
    {
      float side = max(ceil(s), 1.0);
      weight = min(s * s / (side * side), 1.0);
      lo = floor(centre - 0.5 * side + 0.5);
      hi = lo + side;
    }
    else
    {
      sigma = max(0.5 * s, 0.5);
      radius = ceil(3.0 * sigma);
      vec2 f = floor(centre);
      lo = f - radius;
      hi = f + radius + 1.0;
      vec2 sum = vec2(0.0);
      for (float k = -radius; k <= radius; k += 1.0)
      {
        vec2 d = f + k + 0.5 - centre;
        sum += exp(-d * d / (2.0 * sigma * sigma));
      }
      weight = s * s / (sum.x * sum.y);
    }
    vec2 corner = mix(lo, hi, clipMC * 0.5 + 0.5);
    gl_Position = vec4((corner / viewportSize * 2.0 - 1.0) * c.w, c.z, c.w);
    pointFrame = vec4(centre, sigma, radius);
    pointWeight = weight;
    gl_ClipDistance[0] = 1.0;
    gl_ClipDistance[1] = 1.0;
    return;
  }
  float z = dot(vertexMC - eye, forward);
  gl_ClipDistance[0] = z - clipMC.x;
  gl_ClipDistance[1] = clipMC.y - z;
  gl_Position = MCDC * vec4(vertexMC, 1.0);
}
