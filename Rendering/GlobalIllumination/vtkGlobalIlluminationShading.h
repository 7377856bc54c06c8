/**
 * @class   vtkGlobalIlluminationShading
 * @brief   settings of vtkGlobalIlluminationMapper and vtkGlobalIlluminationCompositeMapper
 *
 * What the global illumination mappers draw and how: the display mode (the paper's
 * Figure 4: direct, indirect, or both), where the per-vertex albedo, indirect irradiance
 * and emission come from, the exposure and tone curve that turn HDR radiance into display
 * values, and the shadow-map settings. One object can be shared by several mappers (e.g.
 * a representation's full-resolution and LOD mappers) so that they always agree.
 *
 * Outgoing radiance per pixel, in linear RGB (the radiometry of vtkGlobalIlluminationFilter):
 * - direct:   L = Le + albedo / pi * E_d + glossy,  E_d from the renderer's lights with shadows;
 * - indirect: L = albedo / pi * E_ind,  E_ind from the IndirectIrradiance point array;
 * - combined: the sum, which is the filter's `Radiance` up to shadow filtering.
 * The albedo is linear: colours that VTK draws (colour maps, solid colours, unsigned char
 * arrays) are display (sRGB) values and are decoded first (vtkGlobalIlluminationColors).
 *
 * Calibration: a surface lit directly and unoccluded, with no indirect light, shows what
 * VTK's own Lambert shading (vtkOpenGLPolyDataMapper, ParaView's Surface) shows under the
 * same lights: its drawn colour times the irradiance, colour x intensity x cos summed over
 * the lights. So with the default HUE_PRESERVING tone mapping the displayed value is
 * KeepHue(Exposure * (C * (E_d + E_ind) + pi * (Le + glossy))), C the drawn (display)
 * colour: global illumination only adds light (bounces, sky, emission) and removes it
 * (shadows), and a colour map's colours stay the data's colours. (VTK multiplies display
 * values by the irradiance; encoding linear light, sRGB(albedo * E), would match it only
 * where E = 1, and would lighten every colour under the light kit's E of about 0.8.)
 * With the photographic curves (LINEAR, EXPONENTIAL, REINHARD) the displayed value is
 * (ToneCurve(Exposure * L))^(1/Gamma): linear light encoded for display (a white surface
 * facing irradiance 1 has L = 1 / pi: Exposure pi shows it white).
 *
 * The look, chosen from the lights (the default AUTOMATIC tone mapping; GetLook() is the
 * rule, the mappers and the ParaView representation all ask it):
 * - Scenes lit on VTK's scale (directional lights, the light kit, headlights, point and
 *   spot lights that do not fall off with distance, VTK's default): HUE_PRESERVING with
 *   Exposure, the calibrated look above.
 * - Scenes with a lamp, a point or spot light that falls off with distance
 *   (vtkGlobalIlluminationLights::Light::FallsOff(), e.g. attenuation (0, 0, 1)): a lamp
 *   near a surface lights it hundreds of times more than the far side of a room, a range
 *   no linear display holds. They are shown as a photograph: EXPONENTIAL with Gamma, and
 *   an automatic exposure that puts the 95th percentile of the luminance of the input's
 *   RadianceArrayName at 85 % of display white (SuggestExposure()), times Exposure.
 *   Without that array the exposure is Exposure alone.
 *
 * Changing the array names, the display mode or the tone curve rebuilds shaders and
 * buffers at the next render; Exposure, Gamma and the shadow filtering are uniforms and
 * cost nothing to change.
 */
#ifndef vtkGlobalIlluminationShading_h
#define vtkGlobalIlluminationShading_h

#include "LinkGIRenderingGlobalIlluminationModule.h" // for export macro
#include "vtkObject.h"

#include <vector> // for std::vector

class vtkDataArray;
class vtkGlobalIlluminationGlobalCasters;

class LINKGIRENDERINGGLOBALILLUMINATION_EXPORT vtkGlobalIlluminationShading : public vtkObject
{
public:
  static vtkGlobalIlluminationShading* New();
  vtkTypeMacro(vtkGlobalIlluminationShading, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// Which part of the light is drawn.
  enum DisplayModes
  {
    COMBINED = 0, ///< direct + indirect light (the final image)
    DIRECT = 1,   ///< direct light with shadows, and emission
    INDIRECT = 2  ///< per-vertex indirect light only
  };

  /// How radiance becomes a display value (see the class description).
  enum ToneMappingTypes
  {
    LINEAR = 0,      ///< none: values above 1 clip in an 8-bit framebuffer, stay in a float one
    EXPONENTIAL = 1, ///< 1 - exp(-x) per channel, as vtkToneMappingPass's Exponential
    REINHARD = 2,    ///< x / (1 + x) per channel
    /// Calibrated to VTK's Lambert shading; colours within display range are shown as they
    /// are; a colour beyond it keeps its luminance (up to white) and hue and loses only as
    /// much saturation as it must, so over-exposed areas turn white instead of changing hue.
    HUE_PRESERVING = 3,
    /// HUE_PRESERVING, or EXPONENTIAL with an automatic exposure where a light is a lamp
    /// (see the class description and GetLook()).
    AUTOMATIC = 4
  };

  /// The tone curve (never AUTOMATIC) and exposure a mapper draws with.
  struct Look
  {
    int ToneMapping = AUTOMATIC;
    double Exposure = 1.0;
  };

  /**
   * The look's one rule (see the class description): the curve and exposure for a scene
   * that has a lamp (`lamps`) or not, `radiance` being the linear RGB radiance of what is
   * drawn (the filter's Radiance arrays; empty or null entries are skipped). Curves other
   * than AUTOMATIC are drawn as chosen, with Exposure.
   */
  Look GetLook(bool lamps, const std::vector<vtkDataArray*>& radiance) const;

  ///@{
  /**
   * COMBINED, DIRECT or INDIRECT. The default value is COMBINED.
   */
  vtkSetClampMacro(DisplayMode, int, COMBINED, INDIRECT);
  vtkGetMacro(DisplayMode, int);
  void SetDisplayModeToCombined() { this->SetDisplayMode(COMBINED); }
  void SetDisplayModeToDirect() { this->SetDisplayMode(DIRECT); }
  void SetDisplayModeToIndirect() { this->SetDisplayMode(INDIRECT); }
  const char* GetDisplayModeAsString();
  ///@}

  ///@{
  /**
   * Point array holding the diffuse albedo (linear RGB in [0,1]; 1 or 2 components are
   * grey, unsigned char is a display colour decoded from sRGB, values above 1 are clamped,
   * as in vtkGlobalIlluminationFilter). Where the input has no such array, the actor's diffuse
   * colour (or the mapped scalar colour) times its Diffuse coefficient is the albedo.
   * The default value is "Albedo".
   */
  vtkSetStringMacro(AlbedoArrayName);
  vtkGetStringMacro(AlbedoArrayName);
  ///@}

  ///@{
  /**
   * Point array holding the indirect irradiance E_ind (float RGB), as written by
   * vtkGlobalIlluminationFilter. Without it the indirect light is black. Back faces use the
   * array of the same name plus "Back" where there is one (the filter's TwoSided output,
   * for open surfaces), else the front's values. The default value is
   * "IndirectIrradiance".
   */
  vtkSetStringMacro(IndirectIrradianceArrayName);
  vtkGetStringMacro(IndirectIrradianceArrayName);
  ///@}

  ///@{
  /**
   * Point array holding emitted radiance Le (linear RGB), drawn as part of the direct
   * light. Without it (or with an array of zeros, which is skipped) nothing emits. The
   * default value is "Emission".
   */
  vtkSetStringMacro(EmissionArrayName);
  vtkGetStringMacro(EmissionArrayName);
  ///@}

  ///@{
  /**
   * Factor applied to every light's DiffuseColor * Intensity; use the value given to
   * vtkGlobalIlluminationFilter::SetLightIntensityScale. The default value is 1.
   */
  vtkSetClampMacro(LightIntensityScale, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(LightIntensityScale, double);
  ///@}

  ///@{
  /**
   * How point and spot lights fall off with distance (vtkGlobalIlluminationLights::Falloffs):
   * AS_LIGHT, as each vtkLight's AttenuationValues say (VTK's default does not fall off), or
   * INVERSE_SQUARE, 1/r^2 for all of them (physical lamps, where the lights cannot say it,
   * as in ParaView). Give the filter lights that say the same (the ParaView representation
   * does). The default value is AS_LIGHT.
   */
  vtkSetClampMacro(LightFalloff, int, 0, 1);
  vtkGetMacro(LightFalloff, int);
  ///@}

  ///@{
  /**
   * Multiplies the radiance before the tone curve. The default value is 1.
   */
  vtkSetClampMacro(Exposure, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(Exposure, double);
  ///@}

  /**
   * An Exposure that shows a high percentile of the luminance of `radiance` (the filter's
   * Radiance array, or any linear RGB radiance) at 85 % of display white with the current
   * tone mapping (and Gamma; AUTOMATIC counts as EXPONENTIAL, its lamp curve): the 80th
   * with HUE_PRESERVING, which does not compress highlights, the 95th with the other
   * curves. For scenes whose lights are not on VTK's scale (physical units). Returns 1 for
   * an empty or black array.
   */
  double SuggestExposure(vtkDataArray* radiance) const;
  double SuggestExposure(const std::vector<vtkDataArray*>& radiance, int toneMapping) const;

  ///@{
  /**
   * Point array holding the radiance of what is drawn (float RGB, as written by
   * vtkGlobalIlluminationFilter), read by the automatic exposure of lamp scenes. The
   * default value is "Radiance".
   */
  vtkSetStringMacro(RadianceArrayName);
  vtkGetStringMacro(RadianceArrayName);
  ///@}

  ///@{
  /**
   * AUTOMATIC, HUE_PRESERVING, LINEAR, EXPONENTIAL or REINHARD. To tone map with
   * vtkToneMappingPass instead, choose LINEAR with Gamma 2.2 (the encoding that pass
   * expects). The default value is AUTOMATIC: HUE_PRESERVING unless a light is a lamp.
   */
  vtkSetClampMacro(ToneMapping, int, LINEAR, AUTOMATIC);
  vtkGetMacro(ToneMapping, int);
  void SetToneMappingToLinear() { this->SetToneMapping(LINEAR); }
  void SetToneMappingToExponential() { this->SetToneMapping(EXPONENTIAL); }
  void SetToneMappingToReinhard() { this->SetToneMapping(REINHARD); }
  void SetToneMappingToHuePreserving() { this->SetToneMapping(HUE_PRESERVING); }
  void SetToneMappingToAutomatic() { this->SetToneMapping(AUTOMATIC); }
  ///@}

  ///@{
  /**
   * Display gamma of the photographic curves (LINEAR, EXPONENTIAL, REINHARD): the output is
   * the tone-mapped value to the power 1/Gamma; 1 writes linear values (AUTOMATIC's lamp
   * curve too). HUE_PRESERVING does not use it. The default value is 2.2.
   */
  vtkSetClampMacro(Gamma, double, 0.1, 10.0);
  vtkGetMacro(Gamma, double);
  ///@}

  ///@{
  /**
   * Shadow-map the lights. Off, every light reaches every surface facing it. The default
   * value is on.
   */
  vtkSetMacro(Shadows, vtkTypeBool);
  vtkGetMacro(Shadows, vtkTypeBool);
  vtkBooleanMacro(Shadows, vtkTypeBool);
  ///@}

  ///@{
  /**
   * Width and height in texels of every shadow map layer (a point light uses six, one per
   * cube face; a spot or directional light one). Memory: 4 bytes per texel and layer.
   * The default value is 1024.
   */
  vtkSetClampMacro(ShadowMapResolution, int, 16, 8192);
  vtkGetMacro(ShadowMapResolution, int);
  ///@}

  ///@{
  /**
   * Percentage-closer filtering, in shadow-map texels. Every lookup is a bilinear depth
   * comparison, which blends the 2 x 2 nearest texels. A radius above 0 takes four such
   * lookups at +-radius / 2 texels: a tent over radius + 2 texels, for soft shadow edges.
   * 0 takes a single lookup: a quarter of the texture cost (what a software rasterizer
   * such as Mesa llvmpipe spends most of its time on) for edges that are only
   * anti-aliased. Changing between 0 and above 0 rebuilds the shader. The default value is
   * 1.5.
   */
  vtkSetClampMacro(ShadowFilterRadius, double, 0.0, 16.0);
  vtkGetMacro(ShadowFilterRadius, double);
  ///@}

  ///@{
  /**
   * Shadow bias, in shadow-map texels at the receiver: the shadow lookup moves off the
   * triangle along its normal by ShadowBias * (0.5 + sqrt(2) * (ShadowFilterRadius / 2 + 1)
   * * sin(angle of incidence)) texels, which is what the filter's footprint needs to be
   * free of acne at any angle, without detaching shadows from their casters. Where a
   * triangle turns edge-on to a light (the last ~6 degrees) its shadow fades out, so that
   * coarse curved meshes do not shadow themselves at the terminator. The default value
   * is 1.
   */
  vtkSetClampMacro(ShadowBias, double, 0.0, 64.0);
  vtkGetMacro(ShadowBias, double);
  ///@}

  ///@{
  /**
   * The triangles of the other processes of a parallel run, which the mappers draw into
   * their shadow maps besides their own (see vtkGlobalIlluminationGlobalCasters; its
   * Gather() is the caller's, collectively). The default value is null: a mapper's shadow
   * maps hold its own triangles only.
   */
  virtual void SetGlobalCasters(vtkGlobalIlluminationGlobalCasters* casters);
  vtkGetObjectMacro(GlobalCasters, vtkGlobalIlluminationGlobalCasters);
  ///@}

  /**
   * The most lights a mapper shades; further lights are ignored with a warning.
   */
  static int GetMaximumNumberOfLights() { return 16; }

protected:
  vtkGlobalIlluminationShading();
  ~vtkGlobalIlluminationShading() override;

  int DisplayMode = COMBINED;
  char* AlbedoArrayName = nullptr;
  char* IndirectIrradianceArrayName = nullptr;
  char* EmissionArrayName = nullptr;
  char* RadianceArrayName = nullptr;
  double LightIntensityScale = 1.0;
  int LightFalloff = 0;
  double Exposure = 1.0;
  int ToneMapping = AUTOMATIC;
  double Gamma = 2.2;
  vtkTypeBool Shadows = 1;
  int ShadowMapResolution = 1024;
  double ShadowFilterRadius = 1.5;
  double ShadowBias = 1.0;
  vtkGlobalIlluminationGlobalCasters* GlobalCasters = nullptr;

private:
  vtkGlobalIlluminationShading(const vtkGlobalIlluminationShading&) = delete;
  void operator=(const vtkGlobalIlluminationShading&) = delete;
};

#endif
