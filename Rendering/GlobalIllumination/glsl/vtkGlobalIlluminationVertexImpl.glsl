  // LinkGI: pass the per-vertex shading attributes on, interpolated.
#if GI_HAS_ALBEDO
  giAlbedoVSOutput = giAlbedoMC;
#endif
#if GI_HAS_INDIRECT
  giIndirectVSOutput = giIndirectMC;
#endif
#if GI_HAS_INDIRECT_BACK
  giIndirectBackVSOutput = giIndirectBackMC;
#endif
#if GI_HAS_EMISSION
  giEmissionVSOutput = giEmissionMC;
#endif
