  // LinkGI: outgoing radiance L = Le + albedo / pi (E_d + E_ind) + glossy, tone mapped.
  vec3 giPosition = (giViewToWorld * vec4(vertexVC.xyz, 1.0)).xyz;
  vec3 giNormal = normalize(mat3(giViewToWorld) * normalVCVSOutput);
  // The triangle's own normal (from the position derivatives taken in uniform control
  // flow), on the same side as the shading normal.
  vec3 giTriangle = mat3(giViewToWorld) * giTriangleNormalVC;
  giTriangle = dot(giTriangle, giTriangle) > 0.0 ? normalize(giTriangle) : giNormal;
  giTriangle = dot(giTriangle, giNormal) < 0.0 ? -giTriangle : giTriangle;
#if GI_HAS_ALBEDO
  vec3 giAlbedo = mix(diffuseColor, giAlbedoVSOutput.rgb, giAlbedoVSOutput.a);
#else
  vec3 giAlbedo = diffuseColor;
#endif
  vec3 giRadiance = vec3(0.0);
#if GI_MODE != 2
  vec3 giEye = giCamera.w > 0.5 ? giCamera.xyz : normalize(giCamera.xyz - giPosition);
  vec3 giGlossy;
  vec3 giDirect =
    giDirectIrradiance(giPosition, giNormal, giTriangle, giEye, specularPower, giGlossy);
  giRadiance += giAlbedo * (1.0 / GI_PI) * giDirect + specularColor * giGlossy;
#if GI_HAS_EMISSION
  giRadiance += giEmissionVSOutput;
#endif
#endif
#if GI_MODE != 1 && GI_HAS_INDIRECT
#if GI_HAS_INDIRECT_BACK
  vec3 giIndirect = gl_FrontFacing ? giIndirectVSOutput : giIndirectBackVSOutput;
#else
  vec3 giIndirect = giIndirectVSOutput;
#endif
  giRadiance += giAlbedo * (1.0 / GI_PI) * giIndirect;
#endif
  fragOutput0 = vec4(giToneMap(giRadiance), opacity);
