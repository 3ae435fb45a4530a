//VTK::System::Dec
in vec2 texCoord;
uniform sampler2D composited;
//VTK::Output::Dec
void main()
{
  gl_FragData[0] = texture(composited, texCoord);
}
