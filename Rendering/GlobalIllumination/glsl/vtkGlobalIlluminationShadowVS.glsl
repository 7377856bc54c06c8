//VTK::System::Dec
// LinkGI: one shadow-map layer. Positions of the caster geometry, as the mapper's VBO holds
// them, to world coordinates and to the layer's clip space.
in vec4 vertexMC;
uniform mat4 giModelToWorld;
uniform mat4 giWorldToClip;
out vec3 giWorldPosition;

void main()
{
  vec4 world = giModelToWorld * vertexMC;
  giWorldPosition = world.xyz / world.w;
  gl_Position = giWorldToClip * vec4(giWorldPosition, 1.0);
}
