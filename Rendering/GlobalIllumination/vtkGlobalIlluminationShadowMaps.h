/**
 * @class   vtkGlobalIlluminationShadowMaps
 * @brief   shadow maps of the global illumination mappers: cube maps for point lights,
 *          2D maps for spot and directional lights, all layers of one depth texture array
 *
 * Owned by one mapper (or composite helper), which hands it the renderer's lights and a
 * callback that draws its triangles. Update() re-renders the maps only when a shadowed
 * light's placement, the caster positions, their placement or the resolution changed:
 * colour and intensity changes, new point data (a new indirect irradiance), camera moves and
 * ordinary frames reuse them. A light at the eye (a headlight) gets no map: every surface
 * point the camera sees is also seen by that light, so its shadows are never visible.
 *
 * Every layer stores linear depth: the distance to the light (point and spot lights) or
 * along the light's direction (directional lights), scaled to [0,1]. A point light takes
 * six layers in the face order +X -X +Y -Y +Z -Z; spot lights with cone angles above 60
 * degrees are shadowed like point lights (a single perspective map would waste its texels
 * at the rim). The layout of the uniforms matches glsl/vtkGlobalIlluminationLightDec.glsl.
 *
 * Not wrapped, not installed.
 */
#ifndef vtkGlobalIlluminationShadowMaps_h
#define vtkGlobalIlluminationShadowMaps_h

#include "vtkGlobalIlluminationLights.h" // for vtkGlobalIlluminationLights::Light
#include "vtkNew.h"                      // for vtkNew
#include "vtkOpenGLBufferObject.h"        // for vtkNew<vtkOpenGLBufferObject>
#include "vtkType.h" // for vtkMTimeType

#include <array>      // for std::array
#include <functional> // for std::function
#include <string>     // for std::string
#include <vector>     // for std::vector

class vtkOpenGLRenderWindow;
class vtkOpenGLVertexArrayObject;
class vtkRenderer;
class vtkShaderProgram;
class vtkTextureObject;
class vtkWindow;

class vtkGlobalIlluminationShadowMaps
{
public:
  /// A light as the shaders see it: world coordinates, linear RGB. The mappers convert
  /// the renderer's lights with vtkGlobalIlluminationLights::Convert, as the filter does.
  using Light = vtkGlobalIlluminationLights::Light;

  /// What casts shadows.
  struct Casters
  {
    /// Binds the caster positions to the program's `vertexMC` in the bound VAO and draws
    /// triangles.
    std::function<void(vtkShaderProgram*, vtkOpenGLVertexArrayObject*)> Draw;
    std::array<double, 16> ModelToWorld{}; ///< row-major, from the positions as drawn
    std::array<double, 6> WorldBounds{};
    /// Changes whenever the caster positions or triangles change (a hash, not a time);
    /// nothing else (new point colours or irradiance must not re-render the maps).
    vtkMTimeType Version = 0;
    /// Triangles of other processes (vtkGlobalIlluminationGlobalCasters) drawn besides
    /// Draw's: 9 floats (three corners) each, null or empty for none. WorldBounds covers
    /// them too.
    const std::vector<float>* Remote = nullptr;
    std::array<double, 16> RemoteToWorld{}; ///< row-major, from the remote positions
    /// Changes whenever the remote positions do.
    vtkMTimeType RemoteVersion = 0;
  };

  vtkGlobalIlluminationShadowMaps();
  ~vtkGlobalIlluminationShadowMaps();
  vtkGlobalIlluminationShadowMaps(const vtkGlobalIlluminationShadowMaps&) = delete;
  vtkGlobalIlluminationShadowMaps& operator=(const vtkGlobalIlluminationShadowMaps&) = delete;

  /**
   * Makes the maps match `lights` (shadowed if `shadows`) and `casters`, re-rendering them
   * only if something they depend on changed. Lights whose `atEye` entry is true (headlights)
   * get no map, and their placement is not part of what the maps depend on. Returns true if
   * it rendered.
   */
  bool Update(vtkOpenGLRenderWindow* window, const std::vector<Light>& lights,
    const std::vector<bool>& atEye, bool shadows, const Casters& casters, int resolution);

  ///@{
  /// Binds the depth texture array to a free texture unit for the lighting shader;
  /// false (and nothing bound) before the first Update.
  bool Activate();
  void Deactivate();
  ///@}

  /**
   * Sets the giShadow* uniforms of the `lightCount` lights of the last Update (their kinds
   * are compiled into the shader, see GetKinds), the filter radius and the bias (in
   * texels) and the texture unit. Call after Activate().
   */
  void SetUniforms(vtkShaderProgram* program, int lightCount, double filterRadius, double bias);

  /// The map kind of each of the first `lightCount` lights (0: none, 1: cube,
  /// 2: perspective, 3: orthographic), comma separated, for the shader source.
  std::string GetKinds(int lightCount) const;

  /// How many times the maps were rendered (tests check that frames reuse them).
  int GetRenderCount() const { return this->RenderCount; }

  void ReleaseGraphicsResources(vtkWindow* window);

  /// Per light: how its layers were rendered.
  struct Map
  {
    int Kind = 0; ///< 0 none, 1 cube, 2 perspective (spot), 3 orthographic (directional)
    int Layer = 0;
    std::array<double, 16> WorldToClip{};           ///< row-major; kinds 2 and 3
    std::array<double, 2> DepthMap{ { 1.0, 0.0 } }; ///< stored depth = x * [0] + [1]
    std::array<double, 2> Texel{ { 0.0, 0.0 } };    ///< texel size = [0] * distance + [1]
  };

private:
  std::vector<Map> Plan(const std::vector<Light>& lights, const std::vector<bool>& atEye,
    const double bounds[6], int resolution, int& layers) const;
  void Allocate(vtkOpenGLRenderWindow* window, int layers, int resolution);
  void Render(
    vtkOpenGLRenderWindow* window, const std::vector<Light>& lights, const Casters& casters);

  std::vector<Map> Maps;
  std::vector<double> Signature;
  vtkNew<vtkTextureObject> Texture; // wraps the GL texture array for texture unit management
  vtkNew<vtkOpenGLBufferObject> RemoteBuffer; // the remote casters' corners
  vtkMTimeType RemoteUploaded = 0;             // their version in RemoteBuffer
  int RemoteVertices = 0;
  vtkOpenGLRenderWindow* Context = nullptr;
  unsigned int TextureHandle = 0;
  unsigned int Framebuffer = 0;
  int Layers = 0;
  int Resolution = 0;
  int RenderCount = 0;
};

#endif
// VTK-HeaderTest-Exclude: vtkGlobalIlluminationShadowMaps.h
