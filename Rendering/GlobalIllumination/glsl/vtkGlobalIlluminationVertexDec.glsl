// LinkGI (vtkGlobalIlluminationMapper): per-vertex shading attributes, declarations.
// GI_HAS_ALBEDO, GI_HAS_INDIRECT, GI_HAS_INDIRECT_BACK and GI_HAS_EMISSION are #defined
// before this text.
#if GI_HAS_ALBEDO
in vec4 giAlbedoMC; // rgb = albedo, a = 1 where the albedo array gives it
out vec4 giAlbedoVSOutput;
#endif
#if GI_HAS_INDIRECT
in vec3 giIndirectMC; // indirect irradiance E_ind
out vec3 giIndirectVSOutput;
#endif
#if GI_HAS_INDIRECT_BACK
in vec3 giIndirectBackMC; // indirect irradiance of the back side (two-sided solutions)
out vec3 giIndirectBackVSOutput;
#endif
#if GI_HAS_EMISSION
in vec3 giEmissionMC; // emitted radiance Le
out vec3 giEmissionVSOutput;
#endif
