// Private to Scenes.cpp and ScenesRooms.cpp: furniture helpers and the larger scenes.
#pragma once

#include "scene/MeshBuilder.h"

#include <array>

namespace linkgi
{
namespace scenes
{
/// Number of cells of at most `cellSize` along `length` (at least one).
int cells(float length, float cellSize);
/// Parallelogram with cells of at most `cellSize`; faces cross(edgeU, edgeV).
Index addRect(MeshBuilder& b, const Vec3f& origin, const Vec3f& edgeU, const Vec3f& edgeV,
  float cellSize, const Vec3f& albedo, const Vec3f& emission = {});
/// Inward box with its own colour per face; walls in the order x = min, x = max, z = min,
/// z = max.
void addRoom(MeshBuilder& b, const Vec3f& min, const Vec3f& max, float cellSize,
  const Vec3f& floor, const Vec3f& ceiling, const std::array<Vec3f, 4>& walls);
/// Closed box of `size` centred at `center`, optionally turned by `yaw` about `pivot`.
Index addBoxAt(MeshBuilder& b, const Vec3f& center, const Vec3f& size, float cellSize,
  const Vec3f& albedo, float yaw = 0.f, const Vec3f& pivot = {});
/// Table standing on `floorCenter`: size = (width, height, depth), top 4 cm thick, round legs.
void addTable(MeshBuilder& b, const Vec3f& floorCenter, const Vec3f& size, float cellSize,
  const Vec3f& top, const Vec3f& legs, int legSegments);
/// Four-legged chair on `floorCenter`, facing +z turned by `yaw`.
void addChair(MeshBuilder& b, const Vec3f& floorCenter, float yaw, float cellSize,
  const Vec3f& seat, const Vec3f& frame);
/// Lamp shade (frustum open at both ends, radius r0 at the bottom, r1 at the top) with two
/// walls, the outer facing out and the inner facing the bulb, and rims that close the gap.
void addShade(MeshBuilder& b, const Vec3f& bottom, float height, float r0, float r1,
  int segments, const Vec3f& albedo);
Light pointLight(const Vec3f& position, const Vec3f& intensity);
}

Scene makeTearoom();
Scene makeIphi();
Scene makeConference();
}
