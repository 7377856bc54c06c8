// The method registry: the one place that maps linkgi::Method to its MethodSpec. A new method
// adds its enum value (SolverTypes.h) and one case here.
#include "engine/Pipeline.h"

#include "linkgi/Error.h"

namespace linkgi
{
namespace links
{
const engine::MethodSpec& linksMethod();
}

namespace engine
{
const MethodSpec& methodSpec(Method method)
{
  switch (method)
  {
    case Method::Links:
      return links::linksMethod();
  }
  throw Error("Unknown solution method " + std::to_string(int(method)) + ".");
}
}
}
