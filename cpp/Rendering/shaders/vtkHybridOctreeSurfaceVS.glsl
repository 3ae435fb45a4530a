//VTK::System::Dec
in vec3 vertexMC;
in vec3 normalMC;
uniform mat4 MCDC;
out vec3 positionMC;
out vec3 normal;
void main()
{
  positionMC = vertexMC;
  normal = normalMC;
  gl_Position = MCDC * vec4(vertexMC, 1.0);
}
