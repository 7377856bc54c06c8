# Implicit-visibility hierarchical links (Dong, Kautz, Theobalt & Seidel 2007).
linkgi_method(ENUM ImplicitVisibility SPEC iv::implicitVisibilityMethod
  SOURCES ClusterTree.cpp ImplicitLinks.cpp IvCpu.cpp IvMethod.cpp PushToLeaves.cpp
  CUDA_SOURCES cuda/IvCuda.cpp cuda/IvKernels.cu)
