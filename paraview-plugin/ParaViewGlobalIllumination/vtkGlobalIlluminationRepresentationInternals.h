// The representation's private state and the helpers its two source files share
// (vtkGlobalIlluminationRepresentation.cxx: the pipeline, lights, waiting and polling;
// vtkGlobalIlluminationRepresentationProperties.cxx: the properties it forwards to the filter
// and the mapper, and the counters it reports).
#ifndef vtkGlobalIlluminationRepresentationInternals_h
#define vtkGlobalIlluminationRepresentationInternals_h

#include "vtkGlobalIlluminationRepresentation.h"

#include "vtkAbstractArray.h"
#include "vtkDataObject.h"
#include "vtkFieldData.h"
#include "vtkGlobalIlluminationAsyncWatcher.h"
#include "vtkGlobalIlluminationCompositeMapper.h"
#include "vtkGlobalIlluminationDrawnAlbedo.h"
#include "vtkGlobalIlluminationFilter.h"
#include "vtkGlobalIlluminationGlobalCasters.h"
#include "vtkGlobalIlluminationShading.h"
#include "vtkLight.h"
#include "vtkNew.h"
#include "vtkPolyData.h"
#include "vtkSMProxy.h"
#include "vtkSmartPointer.h"
#include "vtkVariant.h"
#include "vtkWeakPointer.h"

#include <set>
#include <string>
#include <vector>

struct vtkGlobalIlluminationRepresentation::vtkInternals
{
  vtkNew<vtkGlobalIlluminationFilter> Filter;
  std::vector<vtkSmartPointer<vtkLight>> Lights; // world-space copies of the view's lights
  std::set<std::string> Warnings;                // each shown once

  vtkNew<vtkGlobalIlluminationDrawnAlbedo> DrawnAlbedo; // the albedo is what is drawn

  // In a parallel run, the other processes' triangles for the shadow maps.
  vtkNew<vtkGlobalIlluminationGlobalCasters> GlobalCasters;
  vtkNew<vtkPolyData> EmptyPartition; // the filter's input where nothing was delivered

  // What the mapper drew last (its block attributes are per block object).
  vtkDataObject* Drawn = nullptr;
  vtkMTimeType DrawnTime = 0;

  int ShownRequest = 0; // the worker's request whose solution is drawn
  int ShownStage = 0;   // ... and which of its progressive stages
  vtkMTimeType SolvedTime = 0; // the drawn solution's, where the filter is synchronous

  // Where renders do not wait, on the process with the view's interactor (the GUI's
  // client): polls the representation proxy, this object or its copy on the server.
  vtkNew<vtkGlobalIlluminationAsyncWatcher> Watcher;
  vtkWeakPointer<vtkSMProxy> Proxy;
  bool ToldServers = false;
};


namespace vtkGlobalIlluminationRepresentationHelpers
{
/// The shading state of the representation's mapper.
inline vtkGlobalIlluminationShading* Shading(vtkMapper* mapper)
{
  return static_cast<vtkGlobalIlluminationCompositeMapper*>(mapper)->GetShading();
}

/// The first value of the field array `name` of `data` (the filter's counters), 0 where
/// there is none.
inline double Field(vtkDataObject* data, const char* name)
{
  vtkAbstractArray* array = data ? data->GetFieldData()->GetAbstractArray(name) : nullptr;
  return array && array->GetNumberOfTuples() > 0 ? array->GetVariantValue(0).ToDouble() : 0.0;
}

inline int FieldInt(vtkDataObject* data, const char* name)
{
  return static_cast<int>(Field(data, name));
}
}

#endif
// VTK-HeaderTest-Exclude: vtkGlobalIlluminationRepresentationInternals.h
