/**
 * @class   vtkGlobalIlluminationSceneSource
 * @brief   LinkGI's standard scenes (Cornell box, furnace, tearoom, ...) as vtkPolyData.
 *
 * Produces one of the engine's generated test and benchmark scenes as triangles with point
 * arrays `Normals` (the point normals), `Albedo` and `Emission` (float RGB), and for scenes
 * with mirrors or glass (`caustics`, `cornell-glass`) the cell arrays `Material` and
 * `IndexOfRefraction` (MaterialArrayName, IndexOfRefractionArrayName), ready for
 * vtkGlobalIlluminationFilter (set its AlbedoArrayName to "Albedo" and EmissionArrayName to
 * "Emission"). CreateLights() returns the scene's lights as vtkLight objects, so the same
 * lights can be handed to the filter and to a renderer.
 *
 * The scenes are sized after Table 1 of Schmitz, Tavenrath & Kobbelt 2008: see
 * GetSceneNames(). `torso` deforms with Deformation.
 */
#ifndef vtkGlobalIlluminationSceneSource_h
#define vtkGlobalIlluminationSceneSource_h

#include "LinkGIFiltersGlobalIlluminationModule.h" // For export macro
#include "vtkPolyDataAlgorithm.h"

class vtkLightCollection;
class vtkStringArray;
namespace linkgi
{
struct Scene;
}

class LINKGIFILTERSGLOBALILLUMINATION_EXPORT vtkGlobalIlluminationSceneSource
  : public vtkPolyDataAlgorithm
{
public:
  static vtkGlobalIlluminationSceneSource* New();
  vtkTypeMacro(vtkGlobalIlluminationSceneSource, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * Name of the scene to generate, one of GetSceneNames(). The default value is "cornell".
   */
  vtkSetStringMacro(SceneName);
  vtkGetStringMacro(SceneName);
  ///@}

  ///@{
  /**
   * Deformation of the `torso` scene: 0 is the rest pose, 1 fully bent and twisted; other
   * scenes ignore it. The default value is 0.
   */
  vtkSetMacro(Deformation, double);
  vtkGetMacro(Deformation, double);
  ///@}

  /**
   * The names SetSceneName accepts. The caller owns the returned array.
   */
  static vtkStringArray* GetSceneNames();

  /**
   * Appends the current scene's lights to `lights` as new vtkLight objects (positional
   * lights for point and spot lights, scene lights for directional ones), with colour and
   * intensity such that colour * intensity is the scene's RGB intensity.
   */
  void CreateLights(vtkLightCollection* lights);

protected:
  vtkGlobalIlluminationSceneSource();
  ~vtkGlobalIlluminationSceneSource() override;

  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  bool MakeScene(linkgi::Scene& scene);

  char* SceneName = nullptr;
  double Deformation = 0.0;

private:
  vtkGlobalIlluminationSceneSource(const vtkGlobalIlluminationSceneSource&) = delete;
  void operator=(const vtkGlobalIlluminationSceneSource&) = delete;
};

#endif
