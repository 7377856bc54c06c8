# Photon mapping with clustered final gather and caustics (Wang, Wang, Zhou & Guo 2009).
linkgi_method(ENUM PhotonMapping VALUE 3 LABEL "Photon Mapping"
  DESCRIPTION "photons from the lights, a final gather at one sample vertex per cluster of vertices, interpolated to the others (a light move keeps the clusters; mirrors, glass and caustics)."
  SPEC pm::photonMappingMethod
  SOURCES PhotonMapping.cpp PmCpu.cpp PmMethod.cpp PointTree.cpp SurfacePieces.cpp
  CUDA_SOURCES cuda/PmCuda.cpp cuda/PmKernels.cu)
