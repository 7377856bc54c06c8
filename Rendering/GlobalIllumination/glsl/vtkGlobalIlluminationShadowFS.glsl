//VTK::System::Dec
// LinkGI: one shadow-map layer. The stored depth is linear in world units, so that the
// lighting shader can compare and bias it the same way for every light type: the distance
// to the light (point and spot lights) or along the light's direction (directional lights),
// mapped to [0,1] by giDepthMap = (scale, offset). A directional light's orthographic
// projection already makes that depth (its near and far planes enclose the casters): its
// program (giRadial undefined) writes none, so the rasterizer tests depth before shading.
//VTK::ShadowDepth::Dec
#ifdef giRadial
in vec3 giWorldPosition;
uniform vec3 giLightPosition;
uniform vec2 giDepthMap;
#endif

void main()
{
#ifdef giRadial
  gl_FragDepth = clamp(length(giWorldPosition - giLightPosition) * giDepthMap.x + giDepthMap.y, 0.0, 1.0);
#endif
}
