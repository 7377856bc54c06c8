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
namespace ir
{
const engine::MethodSpec& instantRadiosityMethod();
}
namespace iv
{
const engine::MethodSpec& implicitVisibilityMethod();
}
namespace pm
{
const engine::MethodSpec& photonMappingMethod();
}

namespace engine
{
const MethodSpec& methodSpec(Method method)
{
  switch (method)
  {
    case Method::Links:
      return links::linksMethod();
    case Method::InstantRadiosity:
      return ir::instantRadiosityMethod();
    case Method::ImplicitVisibility:
      return iv::implicitVisibilityMethod();
    case Method::PhotonMapping:
      return pm::photonMappingMethod();
  }
  throw Error("Unknown solution method " + std::to_string(int(method)) + ".");
}
}

Method methodByName(const std::string& name)
{
  std::string names;
  for (int m = 0;; ++m)
  {
    const engine::MethodSpec* spec = nullptr;
    try
    {
      spec = &engine::methodSpec(Method(m));
    }
    catch (const Error&)
    {
      break; // past the last method
    }
    if (name == spec->name())
    {
      return Method(m);
    }
    names += std::string(names.empty() ? "" : ", ") + spec->name();
  }
  throw Error("Unknown method '" + name + "'; use " + names + ".");
}
}
