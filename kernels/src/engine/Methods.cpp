// The method registry: linkgi::Method to its MethodSpec, over the generated table.
#include "engine/Methods.h"

#include "linkgi/Error.h"

#include <algorithm>

namespace linkgi
{
namespace engine
{
const MethodSpec& methodSpec(Method method)
{
  for (const MethodEntry& entry : methodTable())
  {
    if (entry.method == method)
    {
      return entry.spec();
    }
  }
  throw Error("Unknown solution method " + std::to_string(int(method)) + ".");
}
}

std::vector<Method> methods()
{
  std::vector<Method> all;
  for (const engine::MethodEntry& entry : engine::methodTable())
  {
    all.push_back(entry.method);
  }
  std::sort(all.begin(), all.end());
  return all;
}

const char* methodName(Method method)
{
  return engine::methodSpec(method).name();
}

std::string methodNames(const std::string& separator)
{
  std::string names;
  for (Method m : methods())
  {
    names += (names.empty() ? "" : separator) + methodName(m);
  }
  return names;
}

Method methodByName(const std::string& name)
{
  for (Method m : methods())
  {
    if (name == methodName(m))
    {
      return m;
    }
  }
  throw Error("Unknown method '" + name + "'; use " + methodNames() + ".");
}
}
