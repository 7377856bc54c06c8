# Instant radiosity (Marques & Santos 2010): virtual point lights, nothing precomputed.
linkgi_method(ENUM InstantRadiosity SPEC ir::instantRadiosityMethod
  SOURCES IrCpu.cpp IrHost.cpp IrMethod.cpp
  CUDA_SOURCES cuda/IrCuda.cpp cuda/IrKernels.cu)
