# Photon mapping with clustered final gather and caustics (Wang, Wang, Zhou & Guo 2009).
linkgi_method(ENUM PhotonMapping SPEC pm::photonMappingMethod
  SOURCES PhotonMapping.cpp PmCpu.cpp PmMethod.cpp PointTree.cpp
  CUDA_SOURCES cuda/PmCuda.cpp cuda/PmKernels.cu)
