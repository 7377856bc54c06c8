// The standard test and benchmark scenes, generated in code (nothing is downloaded).
#pragma once

#include "linkgi/Scene.h"

#include <string>
#include <vector>

namespace linkgi
{
struct SceneParams
{
  /// torso only: 0 = rest pose, 1 = bent forward and twisted. Any real value works and the
  /// shape changes continuously with it; positions and normals change, topology never does.
  float deformation = 0.f;
  /// cornell only: false = a point light just below the ceiling opening (the opening is a
  /// plain white patch); true = the opening is an emissive patch and there is no point light.
  bool cornellAreaLight = false;
  /// cornell only: the largest cell edge in metres (0: the published box's 16 mm). A size
  /// above the walls' gives two triangles per wall (the ceiling keeps the cells that frame
  /// the light's opening): the coarse input of refinement.
  float cornellCell = 0.f;
};

/// Names accepted by makeStandardScene:
/// furnace, colorlamp, torso, cornell, tearoom, iphi, conference.
std::vector<std::string> standardSceneNames();

/// Builds a standard scene (Y up, metres). The five scenes of the paper's Table 1 have its
/// vertex counts within a few percent: colorlamp 1.6k, torso 7.1k, tearoom 11.9k, iphi 76.5k,
/// conference 122.8k. cornell is the published Cornell box (8.6k vertices), furnace a
/// closed emitting sphere seen from inside (analytic answer Le / (1 - rho)).
/// Throws linkgi::Error naming the valid names for an unknown name.
Scene makeStandardScene(const std::string& name, const SceneParams& params = {});
}
