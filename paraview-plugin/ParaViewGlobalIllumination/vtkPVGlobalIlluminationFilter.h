/**
 * @class   vtkPVGlobalIlluminationFilter
 * @brief   vtkGlobalIlluminationFilter with its lights as plain properties, for ParaView
 *
 * ParaView proxies set numbers and strings, and vtkLight objects are not proxies of the
 * filter, so this subclass owns one vtkLight (the "property light") built from plain
 * properties: type (point, spot, directional), position, focal point, colour, intensity
 * and cone angle. Further lights can be added as objects with AddAdditionalLight, which
 * the proxy uses for ParaView light proxies (`CreateLight()` in Python).
 *
 * It also takes array selections in ParaView's five-element form (index, port,
 * connection, association, name). Nothing else changes: the algorithm is the
 * superclass's.
 */
#ifndef vtkPVGlobalIlluminationFilter_h
#define vtkPVGlobalIlluminationFilter_h

#include "LinkGIParaViewGlobalIlluminationModule.h" // for export macro
#include "vtkGlobalIlluminationFilter.h"
#include "vtkNew.h" // for vtkNew

class vtkLight;

class LINKGIPARAVIEWGLOBALILLUMINATION_EXPORT vtkPVGlobalIlluminationFilter
  : public vtkGlobalIlluminationFilter
{
public:
  static vtkPVGlobalIlluminationFilter* New();
  vtkTypeMacro(vtkPVGlobalIlluminationFilter, vtkGlobalIlluminationFilter);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// Kinds of the property light.
  enum LightTypes
  {
    POINT_LIGHT = 0,       ///< positional, radiates in all directions
    SPOT_LIGHT = 1,        ///< positional, within LightConeAngle of the focal point
    DIRECTIONAL_LIGHT = 2  ///< parallel rays from LightPosition towards LightFocalPoint
  };

  ///@{
  /**
   * Whether the property light shines. The default value is on.
   */
  void SetLightSwitch(vtkTypeBool on);
  vtkTypeBool GetLightSwitch();
  ///@}

  ///@{
  /**
   * POINT_LIGHT, SPOT_LIGHT or DIRECTIONAL_LIGHT. The default value is DIRECTIONAL_LIGHT,
   * whose result does not depend on the scale of the data.
   */
  void SetLightType(int type);
  vtkGetMacro(LightType, int);
  ///@}

  ///@{
  /**
   * Position of a point or spot light; for a directional light, the light shines from
   * here towards the focal point. In world coordinates. The default value is (0, 1, 0).
   */
  void SetLightPosition(double x, double y, double z);
  void GetLightPosition(double position[3]);
  ///@}

  ///@{
  /**
   * Where a spot or directional light points. The default value is (0, 0, 0).
   */
  void SetLightFocalPoint(double x, double y, double z);
  void GetLightFocalPoint(double focalPoint[3]);
  ///@}

  ///@{
  /**
   * Colour of the light (linear RGB), multiplied by LightIntensity. The default value is
   * (1, 1, 1).
   */
  void SetLightColor(double r, double g, double b);
  void GetLightColor(double color[3]);
  ///@}

  ///@{
  /**
   * Intensity: radiant intensity in W/sr for point and spot lights (a surface at distance
   * r facing the light receives intensity / r^2), irradiance for a directional light.
   * The default value is 1.
   */
  void SetLightIntensity(double intensity);
  double GetLightIntensity();
  ///@}

  ///@{
  /**
   * Half-angle of a spot light's cone in degrees, in (0, 89]. Point and directional
   * lights ignore it. The default value is 30.
   */
  void SetLightConeAngle(double angle);
  vtkGetMacro(LightConeAngle, double);
  ///@}

  /**
   * The vtkLight built from the properties above.
   */
  vtkLight* GetPropertyLight();

  ///@{
  /**
   * Lights given as objects (ParaView light proxies), used in addition to the property
   * light. RemoveAllAdditionalLights keeps the property light.
   */
  void AddAdditionalLight(vtkLight* light);
  void RemoveAllAdditionalLights();
  ///@}

  ///@{
  /**
   * Array selections in ParaView's form: `index`, `port` and `connection` are ignored,
   * `association` is vtkDataObject::FIELD_ASSOCIATION_POINTS or _CELLS, and an empty
   * name or "None" selects no array (the constant Albedo, no emission).
   */
  void SetAlbedoArray(int index, int port, int connection, int association, const char* name);
  void SetEmissionArray(int index, int port, int connection, int association, const char* name);
  /// Materials and indices of refraction (the filter reads the cell array of that name, or
  /// else the point array; the association is not needed).
  void SetMaterialArray(int index, int port, int connection, int association, const char* name);
  void SetIndexOfRefractionArray(int index, int port, int connection, int association, const char* name);
  ///@}

protected:
  vtkPVGlobalIlluminationFilter();
  ~vtkPVGlobalIlluminationFilter() override;

  /// Makes the property light positional or not, and sets its cone, from LightType.
  void ApplyLightType();

  vtkNew<vtkLight> PropertyLight;
  int LightType = DIRECTIONAL_LIGHT;
  double LightConeAngle = 30.0;

private:
  vtkPVGlobalIlluminationFilter(const vtkPVGlobalIlluminationFilter&) = delete;
  void operator=(const vtkPVGlobalIlluminationFilter&) = delete;
};

#endif
