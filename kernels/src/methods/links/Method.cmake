# The link structure (Schmitz, Tavenrath & Kobbelt 2008): links traced once, bounces gathered
# through them on every light change.
linkgi_method(ENUM Links VALUE 0 LABEL "Links"
  DESCRIPTION "rays between vertices, traced once, bounced over (a light move costs milliseconds, a deformation relinks)."
  SPEC links::linksMethod
  SOURCES Links.cpp LinksCpu.cpp LinksMethod.cpp
  CUDA_SOURCES cuda/CudaBounces.cpp cuda/CudaEngine.cpp cuda/CudaLinks.cpp cuda/LinkKernels.cu
    cuda/LinksCuda.cpp)
