  // LinkGI: outgoing radiance L = Le + albedo / pi * E + glossy (linear light), and its
  // display (vtkGlobalIlluminationShading: calibrated to VTK's Lambert shading by default).
  vec3 giPosition = (giViewToWorld * vec4(vertexVC.xyz, 1.0)).xyz;
  // The front of a triangle is the side its normals point to, as for the filter. VTK turns
  // the normal on back faces (by winding); where a triangle's normals point against its
  // winding, that leaves the normal facing away from the eye (giTriangleNormalVC, from the
  // position derivatives, always faces it): turned back, the side the normals point to is
  // lit, and its indirect light is the front's.
  bool giAgrees = dot(giTriangleNormalVC, normalVCVSOutput) >= 0.0;
  bool giFront = giAgrees == gl_FrontFacing;
  vec3 giNormal = normalize(mat3(giViewToWorld) * (giAgrees ? normalVCVSOutput : -normalVCVSOutput));
  // The triangle's own normal, on the same side as the shading normal.
  vec3 giTriangle = mat3(giViewToWorld) * giTriangleNormalVC;
  giTriangle = dot(giTriangle, giTriangle) > 0.0 ? normalize(giTriangle) : giNormal;
  giTriangle = dot(giTriangle, giNormal) < 0.0 ? -giTriangle : giTriangle;
  // The colour VTK draws (diffuseColor) is a display value; the albedo array is linear.
#if GI_HAS_ALBEDO
  vec3 giAlbedo = mix(giToLinear(diffuseColor), giAlbedoVSOutput.rgb, giAlbedoVSOutput.a);
  vec3 giDrawn = mix(diffuseColor, giToDisplay(giAlbedoVSOutput.rgb), giAlbedoVSOutput.a);
#else
  vec3 giAlbedo = giToLinear(diffuseColor);
  vec3 giDrawn = diffuseColor;
#endif
  vec3 giIrradiance = vec3(0.0);
  vec3 giEmitted = vec3(0.0); // Le + glossy
#if GI_MODE != 2
  vec3 giEye = giCamera.w > 0.5 ? giCamera.xyz : normalize(giCamera.xyz - giPosition);
  vec3 giGlossy;
  giIrradiance +=
    giDirectIrradiance(giPosition, giNormal, giTriangle, giEye, specularPower, giGlossy);
  giEmitted += specularColor * giGlossy;
#if GI_HAS_EMISSION
  giEmitted += giEmissionVSOutput;
#endif
#endif
#if GI_MODE != 1 && GI_HAS_INDIRECT
#if GI_HAS_INDIRECT_BACK
  giIrradiance += giFront ? giIndirectVSOutput : giIndirectBackVSOutput;
#else
  giIrradiance += giIndirectVSOutput;
#endif
#endif
#if GI_TONE_MAPPING == 3
  vec3 giDisplay = giKeepHue(giExposure * (giDrawn * giIrradiance + GI_PI * giEmitted));
#else
  vec3 giDisplay = giToneMap(giAlbedo * (1.0 / GI_PI) * giIrradiance + giEmitted);
#endif
  fragOutput0 = vec4(giDisplay, opacity);
