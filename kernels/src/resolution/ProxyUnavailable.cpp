// Builds without OpenMesh: no decimation, and a message that says what is missing.
#include "linkgi/Resolution.h"
#include "resolution/Decimate.h"

#include "linkgi/Error.h"

namespace linkgi
{
bool proxyAvailable()
{
  return false;
}

ProxyMesh decimate(const Scene&, std::size_t, float, const ProgressCallback&)
{
  throw Error("Proxies need OpenMesh, and this build has none (install libopenmesh-dev, or "
              "OpenMesh 9, and configure again); use 0 proxy vertices.");
}
}
