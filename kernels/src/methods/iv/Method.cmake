# Implicit-visibility hierarchical links (Dong, Kautz, Theobalt & Seidel 2007).
linkgi_method(ENUM ImplicitVisibility VALUE 2 LABEL "Implicit Visibility"
  DESCRIPTION "links between clusters of vertices, the shortest per direction bin, so visibility is implied and the bounced light needs no rays (one-sided surfaces)."
  SPEC iv::implicitVisibilityMethod
  SOURCES ClusterTree.cpp ImplicitLinks.cpp IvCpu.cpp IvMethod.cpp PushToLeaves.cpp
  CUDA_SOURCES cuda/IvCuda.cpp cuda/IvKernels.cu)
