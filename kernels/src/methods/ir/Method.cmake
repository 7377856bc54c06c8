# Instant radiosity (Marques & Santos 2010): virtual point lights, nothing precomputed.
linkgi_method(ENUM InstantRadiosity VALUE 1 LABEL "Instant Radiosity"
  DESCRIPTION "light paths leave virtual point lights on the surfaces, gathered at every vertex (nothing precomputed: a deformation costs what a light move costs)."
  SPEC ir::instantRadiosityMethod
  SOURCES IrCpu.cpp IrHost.cpp IrMethod.cpp
  CUDA_SOURCES cuda/IrCuda.cpp cuda/IrKernels.cu)
