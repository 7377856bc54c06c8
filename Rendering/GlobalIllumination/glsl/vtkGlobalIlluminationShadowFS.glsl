//VTK::System::Dec
// LinkGI: one shadow-map layer. The stored depth is linear in world units, so that the
// lighting shader can compare and bias it the same way for every light type: the distance
// to the light (point and spot lights) or along the light's direction (directional lights),
// mapped to [0,1] by giDepthMap = (scale, offset).
in vec3 giWorldPosition;
uniform vec3 giLightPosition;
uniform vec3 giLightDirection;
uniform int giRadial;
uniform vec2 giDepthMap;

void main()
{
  float x = giRadial != 0 ? length(giWorldPosition - giLightPosition)
                          : dot(giWorldPosition, giLightDirection);
  gl_FragDepth = clamp(x * giDepthMap.x + giDepthMap.y, 0.0, 1.0);
}
