/**
 * @class   vtkGlobalIlluminationLights
 * @brief   how LinkGI reads a vtkLight: the one interpretation that the filter (which
 *          bounces the light) and the mapper (which shadows it) share
 *
 * Convert() turns a vtkLight into a Light in world coordinates and linear RGB:
 * - Type: a positional light with a cone angle below 90 degrees is a SPOT light (with the
 *   light's exponent), any other positional light a POINT light (it shines in all
 *   directions, so 90 and 180 are the same); a light that is not positional is
 *   DIRECTIONAL, its parallel rays travelling from its position towards its focal point.
 * - Placement: the transformed position and focal point, so headlights and camera lights
 *   are used where a renderer last placed them.
 * - Intensity = DiffuseColor * Intensity * scale (the filter's or the mapper's
 *   LightIntensityScale): radiant intensity in W/sr for point and spot lights (a surface at
 *   distance r facing the light receives intensity / r^2), irradiance for a directional
 *   light.
 * - Distance falloff, as VTK draws it: a point or spot light's AttenuationValues (c, l, q)
 *   give intensity / (c + l r + q r^2) at distance r. VTK's default (1, 0, 0) does not fall
 *   off, so a point light looks as in VTK's Surface; (0, 0, 1) is a physical lamp's 1/r^2,
 *   which the generated lamp scenes (vtkGlobalIlluminationSceneSource) use and MakeLamp()
 *   sets. A light with a linear or quadratic term is a lamp (FallsOff()), which picks the
 *   mappers' automatic look (vtkGlobalIlluminationShading). Where the lights cannot say
 *   (ParaView's Light Inspector has no attenuation), the user chooses 1/r^2 for all of
 *   them with Convert()'s INVERSE_SQUARE (vtkGlobalIlluminationShading::LightFalloff).
 * - A switched-off light (or nullptr) is skipped silently.
 * - A spot or directional light whose focal point equals its position has no direction:
 *   it is skipped, and the filter and the mapper both warn with Explain()'s sentence
 *   (LightIntensityScale and the rest of the scene still work; an exception would lose the
 *   whole image for one misplaced light). A point light needs no direction.
 * - A light whose colour x intensity x scale is negative or not finite, whose position
 *   or focal point is not finite, or (point and spot) whose attenuation values are negative
 *   or all zero, gives no physical light: skipped with a warning too (the
 *   engine would reject the whole scene; the mapper would draw negative light).
 *
 * Part of LinkGI::FiltersGlobalIllumination, which LinkGI::RenderingGlobalIllumination
 * depends on (the mapper's module sits above the filter's). Not wrapped.
 */
#ifndef vtkGlobalIlluminationLights_h
#define vtkGlobalIlluminationLights_h

#include "LinkGIFiltersGlobalIlluminationModule.h" // for export macro

#include <array>  // for std::array
#include <string> // for std::string

class vtkLight;

class LINKGIFILTERSGLOBALILLUMINATION_EXPORT vtkGlobalIlluminationLights
{
public:
  /// A light as LinkGI sees it: world coordinates, linear RGB.
  struct Light
  {
    /// The values are those of the shaders' GI_LIGHT_TYPES and of linkgi::LightType.
    enum Types
    {
      POINT = 0,
      SPOT = 1,
      DIRECTIONAL = 2
    };
    int Type = POINT;
    std::array<double, 3> Position{ { 0.0, 0.0, 0.0 } };
    /// Unit direction of travel: the spot axis or the directional light's rays. A point
    /// light keeps (0, 0, -1) when its focal point equals its position.
    std::array<double, 3> Direction{ { 0.0, 0.0, -1.0 } };
    std::array<double, 3> Intensity{ { 1.0, 1.0, 1.0 } }; ///< W/sr, or W/m^2 if directional
    double ConeAngle = 180.0; ///< half angle in degrees; a spot's is below 90
    double Exponent = 0.0;    ///< spot falloff cos(angle to axis)^Exponent; 0 = hard cone
    /// Point and spot: constant, linear and quadratic distance attenuation (see above);
    /// a directional light keeps (1, 0, 0).
    std::array<double, 3> Attenuation{ { 1.0, 0.0, 0.0 } };

    /// cos(ConeAngle).
    double CosCone() const;
    /// Whether the light dims with distance: a point or spot light with a linear or
    /// quadratic attenuation term (a lamp).
    bool FallsOff() const;
  };

  /// What Convert() did.
  enum Status
  {
    CONVERTED = 0,
    SWITCHED_OFF = 1, ///< skipped silently
    NO_DIRECTION = 2, ///< a spot or directional light with focal point == position: skipped
    NOT_PHYSICAL = 3  ///< negative or non-finite intensity, non-finite placement: skipped
  };

  /// How point and spot lights fall off with distance.
  enum Falloffs
  {
    AS_LIGHT = 0,      ///< as the light's AttenuationValues say (VTK's rule)
    INVERSE_SQUARE = 1 ///< 1/r^2 for every point and spot light, whatever they say
  };

  /**
   * Converts `light` with its intensity multiplied by `scale`, its distance falloff chosen
   * by `falloff` (Falloffs). Only with CONVERTED is `out` written.
   */
  static Status Convert(vtkLight* light, double scale, Light& out, int falloff = AS_LIGHT);

  /// Makes `light` a physical lamp: positional, attenuation (0, 0, 1), so that a surface at
  /// distance r facing it receives Intensity / r^2.
  static void MakeLamp(vtkLight* light);

  /// The warning for a light that Convert() skipped with `status` (empty for CONVERTED
  /// and SWITCHED_OFF), naming the light. Callers warn whenever it is not empty.
  static std::string Explain(Status status, vtkLight* light);
};

#endif
// VTK-HeaderTest-Exclude: vtkGlobalIlluminationLights.h
