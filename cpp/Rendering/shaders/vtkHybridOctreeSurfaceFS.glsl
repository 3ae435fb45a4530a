//VTK::System::Dec
in vec3 positionMC;
in vec3 normal;
uniform vec3 eye;
uniform vec3 forward;
uniform int parallel;
uniform vec4 surfaceColor;
uniform int testOpaqueDepth;
uniform sampler2D opaqueDepth;
uniform vec2 depthScale;
//VTK::Output::Dec
void main()
{
  if (testOpaqueDepth != 0 &&
    gl_FragCoord.z > texelFetch(opaqueDepth, ivec2(gl_FragCoord.xy * depthScale), 0).r)
  {
    discard; // behind opaque geometry (drawn into the float target, without a depth buffer)
  }
  vec3 d = parallel != 0 ? forward : normalize(positionMC - eye);
  float len = length(normal);
  float lambert = len > 0.0 ? abs(dot(normal, d)) / len : 1.0;
  vec3 rgb = clamp(surfaceColor.rgb, 0.0, 1.0) * lambert;
  gl_FragData[0] = vec4(rgb * surfaceColor.a, surfaceColor.a);
}
