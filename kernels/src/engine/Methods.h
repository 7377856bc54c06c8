// The method registry's table: generated at configure time from the linkgi_method() calls of
// src/methods/*/Method.cmake (kernels/CMakeLists.txt), so a method registers itself from its
// own folder. The engine reads it through methodSpec(); users through linkgi::methods().
#pragma once

#include "engine/Pipeline.h"

#include <vector>

namespace linkgi::engine
{
struct MethodEntry
{
  Method method;
  const MethodSpec& (*spec)();
};

/// Every method this build has, in the order of the Method.cmake files (generated
/// MethodTable.cpp).
const std::vector<MethodEntry>& methodTable();
}
