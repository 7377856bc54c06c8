/**
 * @class   vtkGlobalIlluminationMapperCore
 * @brief   the rendering logic shared by vtkGlobalIlluminationMapper and the helper of
 *          vtkGlobalIlluminationCompositeMapper
 *
 * Those two classes derive from different VTK mappers, so they forward the handful of
 * vtkOpenGLPolyDataMapper overrides that matter here to one object of this class: the
 * per-vertex attributes (albedo, indirect irradiance, emission as float arrays), the
 * renderer's lights, the shadow maps, the GLSL replacements of the `//VTK::Light::*` tags
 * and the uniforms.
 *
 * The replacement keeps every VTK shader tag: the lighting code goes before
 * `//VTK::Light::Impl` and writes `fragOutput0`, and `vertexVC` and `normalVCVSOutput` stay
 * as VTK declares them, so render passes that hook in after lighting (vtkSSAOPass) or
 * process the image (vtkToneMappingPass) still compose.
 *
 * Not wrapped, not installed.
 */
#ifndef vtkGlobalIlluminationMapperCore_h
#define vtkGlobalIlluminationMapperCore_h

#include "vtkGlobalIlluminationShading.h"    // for vtkGlobalIlluminationShading::Look
#include "vtkGlobalIlluminationShadowMaps.h" // for vtkGlobalIlluminationShadowMaps
#include "vtkShader.h"                       // for vtkShader::Type
#include "vtkSmartPointer.h"                 // for vtkSmartPointer

#include <array>  // for std::array
#include <map>    // for std::map
#include <string> // for std::string
#include <vector> // for std::vector

class vtkActor;
class vtkFloatArray;
class vtkGlobalIlluminationShading;
class vtkMapper;
class vtkObject;
class vtkOpenGLHelper;
class vtkOpenGLVertexBufferObjectGroup;
class vtkPolyData;
class vtkRenderer;
class vtkShaderProgram;
class vtkWindow;

class vtkGlobalIlluminationMapperCore
{
public:
  /// `owner` receives the warnings.
  explicit vtkGlobalIlluminationMapperCore(vtkObject* owner);
  ~vtkGlobalIlluminationMapperCore();
  vtkGlobalIlluminationMapperCore(const vtkGlobalIlluminationMapperCore&) = delete;
  vtkGlobalIlluminationMapperCore& operator=(const vtkGlobalIlluminationMapperCore&) = delete;

  /// The settings; the owner keeps the reference.
  void SetShading(vtkGlobalIlluminationShading* shading) { this->Shading = shading; }

  /**
   * Whether the global illumination shader draws primitives of this type
   * (vtkOpenGLPolyDataMapper::PrimitiveTypes): triangles and strips of a lit actor
   * (lightComplexity > 0) that is not PBR-shaded. Everything else is drawn by VTK.
   */
  static bool Shades(int primitiveType, int lightComplexity, vtkActor* actor);

  /// Float copies of the shading arrays of one polydata; null where the input has none.
  struct Attributes
  {
    vtkSmartPointer<vtkFloatArray> Albedo;       ///< RGBA: albedo in [0,1], A = 1
    vtkSmartPointer<vtkFloatArray> Indirect;     ///< RGB irradiance
    vtkSmartPointer<vtkFloatArray> IndirectBack; ///< RGB irradiance of back faces
    vtkSmartPointer<vtkFloatArray> Emission;     ///< RGB radiance
  };

  /// Which attributes there are (in a polydata, or in the vertex buffers).
  struct Layout
  {
    bool Albedo = false;
    bool Indirect = false;
    bool IndirectBack = false;
    bool Emission = false;
    bool operator==(const Layout& o) const
    {
      return this->Albedo == o.Albedo && this->Indirect == o.Indirect &&
        this->IndirectBack == o.IndirectBack && this->Emission == o.Emission;
    }
  };

  /// The vertex buffer of one attribute: its name in the shaders, its flag in a Layout and
  /// its array in Attributes.
  struct Buffer
  {
    const char* Name;
    bool Layout::*Present;
    vtkSmartPointer<vtkFloatArray> Attributes::*Array;
  };
  /// The four attributes' buffers.
  static const std::array<Buffer, 4>& Buffers();

  /**
   * The attributes of `poly`. The back faces' indirect irradiance is the array named like
   * the indirect one plus "Back" (vtkGlobalIlluminationFilter's TwoSided output). With
   * `fill`, missing ones become zeros (albedo with A = 0, meaning "use the actor's
   * colour"; the back faces take the front's values), so that blocks of a composite
   * dataset line up.
   */
  Attributes MakeAttributes(vtkPolyData* poly, bool fill) const;

  /// Which of the attributes `poly` has.
  Layout GetLayout(vtkPolyData* poly) const;

  ///@{
  /// Which attributes the shaders read; set when the vertex buffers are built.
  void SetLayout(const Layout& layout) { this->Present = layout; }
  const Layout& GetLayout() const { return this->Present; }
  ///@}

  ///@{
  /// Keeps arrays handed to a VBO group alive until its next build (the group keeps only
  /// raw pointers until it uploads them).
  void Keep(const Attributes& attributes);
  void ClearKept() { this->Kept.clear(); }
  ///@}

  /// A key of the names of the shading arrays: a change rebuilds the vertex buffers.
  std::string BufferKey() const;

  ///@{
  /**
   * Keeping the buffers when only the light changed. A new result of the filter changes
   * only its arrays, but a vtkOpenGLPolyDataMapper rebuilds every buffer for any change of
   * its input (and, with new positions, the shadow maps are rendered again).
   * GeometryKey is what the superclass builds its buffers of from `polys`, drawn by
   * `mapper` with `actor`: the mapper's and the actor's property's and texture's times, and
   * per polydata its points, cells and point and cell arrays (objects and times), less the
   * arrays only the shading attributes read (the filter's results, see
   * vtkGlobalIlluminationFilter::IsResultArray, and the indirect irradiance arrays) unless
   * `mapper` colours by one. When it equals the last build's, UploadShading (the
   * attributes of `polys`, appended in this order, into the existing buffers of the
   * layout) brings the buffers up to date; ShadingKey (the arrays MakeAttributes reads)
   * says whether even that is needed.
   */
  std::string GeometryKey(
    vtkMapper* mapper, vtkActor* actor, const std::vector<vtkPolyData*>& polys) const;
  std::string ShadingKey(const std::vector<vtkPolyData*>& polys) const;
  void UploadShading(
    vtkOpenGLVertexBufferObjectGroup* vbos, const std::vector<vtkPolyData*>& polys, bool fill) const;
  ///@}

  /// The shadow casters drawn from a mapper's buffers (its triangles and strips), which
  /// hold `drawn` in order. Their version follows the blocks' points and cells only, so
  /// new point data alone (a new indirect irradiance) never re-renders the shadow maps.
  static vtkGlobalIlluminationShadowMaps::Casters MakeCasters(
    vtkOpenGLVertexBufferObjectGroup* vbos, vtkOpenGLHelper* primitives, vtkActor* actor,
    const std::vector<vtkPolyData*>& drawn);

  /// Takes the renderer's lights and brings the shadow maps up to date, with the other
  /// processes' triangles of the shading's GlobalCasters if it has any, and the look
  /// (vtkGlobalIlluminationShading::GetLook) of the lights and the `drawn` polydata's
  /// radiance. Call before drawing.
  void Prepare(vtkRenderer* renderer, vtkActor* actor,
    const vtkGlobalIlluminationShadowMaps::Casters& casters,
    const std::vector<vtkPolyData*>& drawn);

  /// The tone curve and exposure of the last Prepare().
  const vtkGlobalIlluminationShading::Look& GetLook() const { return this->CurrentLook; }

  /// A key of everything the shader source depends on: a change rebuilds the shaders.
  std::string ShaderKey(vtkActor* actor) const;

  /// Replaces the `//VTK::Light::*` tags of the vertex and fragment shaders.
  void ReplaceShaderLight(std::map<vtkShader::Type, vtkShader*> shaders, vtkActor* actor) const;

  /// Sets the uniforms (lights, shadow maps, camera, exposure) of a bound program.
  void SetShaderParameters(vtkShaderProgram* program, vtkRenderer* renderer);

  /// Releases the texture unit taken by SetShaderParameters. Call after drawing.
  void FinishDraw();

  int GetShadowMapRenderCount() const { return this->ShadowMaps.GetRenderCount(); }
  void ReleaseGraphicsResources(vtkWindow* window);

private:
  /// `own` plus the shading's GlobalCasters (drawn with the actor's matrix), if any.
  vtkGlobalIlluminationShadowMaps::Casters AddGlobalCasters(
    const vtkGlobalIlluminationShadowMaps::Casters& own, vtkActor* actor) const;

  /// The name of the back faces' indirect irradiance array.
  std::string BackName() const;

  /// CurrentLook from the lights and the drawn polydata's radiance, when either changed.
  void UpdateLook(const std::vector<vtkPolyData*>& drawn);

  /// The lights' types, comma separated, for the shader source.
  std::string LightTypes() const;
  int LightCount() const { return static_cast<int>(this->Lights.size()); }

  vtkObject* Owner;
  vtkGlobalIlluminationShading* Shading = nullptr;
  /// The shaders' and shadow maps' frame is the world moved by -Origin (the centre of the
  /// casters' bounds, in double precision): single-precision positions then resolve data
  /// at UTM coordinates as finely as data at the origin. Lights and casters are in it.
  std::array<double, 3> Origin{};
  std::vector<vtkGlobalIlluminationShadowMaps::Light> Lights;
  std::vector<vtkSmartPointer<vtkFloatArray>> Kept;
  vtkGlobalIlluminationShadowMaps ShadowMaps;
  Layout Present;
  bool TextureActive = false;
  int IgnoredLightsWarned = 0;
  std::vector<std::string> SkippedLightsWarned; // lights without a direction, last warned
  vtkGlobalIlluminationShading::Look CurrentLook;
  std::string LookKey; // what CurrentLook was computed from
};

#endif
// VTK-HeaderTest-Exclude: vtkGlobalIlluminationMapperCore.h
