/**
 * @class   vtkGlobalIlluminationRepresentation
 * @brief   ParaView's "Global Illumination" surface representation
 *
 * A surface representation that lights its data with vtkGlobalIlluminationFilter, using
 * the view's own lights, and draws it with vtkGlobalIlluminationCompositeMapper: direct
 * light with shadow maps plus the per-vertex indirect light.
 *
 * The filter runs where the data is rendered, just before each render (the view's render
 * request), on the delivered composite dataset, whose blocks it solves as one scene so
 * that light bounces between them. Its lights are the
 * view's lights in world coordinates, gathered at that moment:
 * - every light of the Light Inspector (vtkPVLight), scene or camera relative;
 * - the light kit's key light (UseKeyLight), a directional light that follows the camera.
 *   The kit's fill, back and head lights are not bounced: they stand in for the indirect
 *   light that the filter computes. (The mapper draws the direct light of all lights.)
 * When a light moves or changes, or the camera moves a camera light, the next render
 * recomputes only the direct light and the bounces; the links are rebuilt only when the
 * data or the ray settings change. Progress is reported through this representation,
 * which ParaView's progress bar shows.
 *
 * The albedo is the colour the surface is drawn with: an `Albedo` point array if the data
 * has one, else the colours mapped from the coloring array, else the solid colour, times
 * the Diffuse coefficient. Points and lines are drawn unlit by the filter's light.
 * Level-of-detail rendering is off for this representation (its decimated geometry would
 * need its own links).
 */
#ifndef vtkGlobalIlluminationRepresentation_h
#define vtkGlobalIlluminationRepresentation_h

#include "LinkGIParaViewGlobalIlluminationModule.h" // for export macro
#include "vtkGeometryRepresentationWithFaces.h"

#include <memory> // for std::unique_ptr

class vtkGlobalIlluminationFilter;
class vtkGlobalIlluminationShading;
class vtkRenderer;

class LINKGIPARAVIEWGLOBALILLUMINATION_EXPORT vtkGlobalIlluminationRepresentation
  : public vtkGeometryRepresentationWithFaces
{
public:
  static vtkGlobalIlluminationRepresentation* New();
  vtkTypeMacro(vtkGlobalIlluminationRepresentation, vtkGeometryRepresentationWithFaces);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  int ProcessViewRequest(vtkInformationRequestKey* request_type, vtkInformation* inInfo,
    vtkInformation* outInfo) override;

  /// Always suppressed: see the class description.
  void SetSuppressLOD(bool) override;

  ///@{
  /**
   * Forwarded to the filter: rays per vertex, bounces, smoothing, sky colour and the
   * factor on every light's intensity (also given to the mapper).
   */
  void SetRaysPerVertex(int rays);
  void SetNumberOfBounces(int bounces);
  /// vtkGlobalIlluminationFilter::SetMethod (LINKS, INSTANT_RADIOSITY).
  void SetMethod(int method);
  void SetSmoothing(int smoothing);
  void SetEnvironmentColor(double r, double g, double b);
  void SetLightIntensityScale(double scale);
  ///@}

  ///@{
  /**
   * Forwarded to the mapper's vtkGlobalIlluminationShading: display mode (0 combined,
   * 1 direct, 2 indirect), exposure, tone mapping (vtkGlobalIlluminationShading's
   * ToneMappingTypes) and shadows.
   */
  void SetDisplayMode(int mode);
  void SetExposure(double exposure);
  void SetToneMapping(int toneMapping);
  void SetShadows(int shadows);
  ///@}

  ///@{
  /**
   * Bounce the light kit's key light too. The default value is on.
   */
  void SetUseKeyLight(bool use);
  bool GetUseKeyLight() { return this->UseKeyLight; }
  ///@}

  ///@{
  /**
   * What the last update did, for tests and the curious: the filter's counters (its
   * lifetime numbers of link builds, light-link builds and bounce runs), the number of
   * times the filter ran, the lights it used, and the mean of the indirect irradiance
   * over the points and channels.
   */
  int GetLinkBuilds();
  int GetLightLinkBuilds();
  int GetBounceRuns();
  int GetNumberOfUpdates() { return this->NumberOfUpdates; }
  int GetNumberOfLights();
  double GetMeanIndirectIrradiance();
  ///@}

  /// The internal filter, for C++ callers.
  vtkGlobalIlluminationFilter* GetFilter();

protected:
  vtkGlobalIlluminationRepresentation();
  ~vtkGlobalIlluminationRepresentation() override;

  /**
   * Runs the filter on the delivered data with the renderer's lights if anything changed;
   * returns what the mapper draws (the filter's output, or the delivered data when there is
   * nothing to solve).
   */
  vtkDataObject* UpdateGlobalIllumination(vtkDataObject* delivered, vtkRenderer* renderer);

  /// Copies the renderer's lights that are bounced into the filter's own world-space lights.
  void GatherLights(vtkRenderer* renderer);

  /// The filter's progress, end and warning events.
  void OnFilterEvent(vtkObject* caller, unsigned long event, void* data);

  bool UseKeyLight = true;
  int NumberOfUpdates = 0;

private:
  vtkGlobalIlluminationRepresentation(const vtkGlobalIlluminationRepresentation&) = delete;
  void operator=(const vtkGlobalIlluminationRepresentation&) = delete;

  struct vtkInternals;
  std::unique_ptr<vtkInternals> Internals;
};

#endif
