// The three larger standard scenes: TEAROOM, IPHI and CONFERENCE (see Scenes.h).
#include "scene/ScenesCommon.h"

#include <cmath>

namespace linkgi
{
using namespace scenes;

namespace
{
const Vec3f kUp(0.f, 1.f, 0.f);

/// Teapot: squashed body with a flat foot, spout, handle, lid seam and knob; `at` is the
/// centre of its foot.
void addTeapot(MeshBuilder& b, const Vec3f& at, const Vec3f& albedo, int segments)
{
  std::vector<std::pair<float, float>> body = { { 0.f, 0.f }, { 0.035f, 0.f } };
  for (int k = 0; k <= 16; ++k)
  {
    const float theta = kPi * (-60.f + 150.f * float(k) / 16.f) / 180.f;
    body.emplace_back(0.1f * std::cos(theta), 0.08f + 0.08f * std::sin(theta));
  }
  body.back().first = 0.f;
  b.addRevolution(at, kUp, body, segments, albedo);
  const Vec3f spoutBase = at + Vec3f(0.08f, 0.05f, 0.f), spoutTip = at + Vec3f(0.19f, 0.15f, 0.f);
  b.addCone(spoutBase, spoutTip, 0.025f, 0.012f, segments / 2, 6, false, albedo);
  b.addDisk(spoutTip, normalize(spoutTip - spoutBase), 0.012f, segments / 2, 1, albedo);
  b.addTorus(at + Vec3f(-0.1f, 0.085f, 0.f), Vec3f(0.f, 0.f, 1.f), 0.05f, 0.012f, segments / 2,
    8, albedo);
  b.addTorus(at + Vec3f(0.f, 0.142f, 0.f), kUp, 0.06f, 0.006f, segments, 4, albedo);
  b.addSphere(at + Vec3f(0.f, 0.172f, 0.f), 0.016f, 6, 12, albedo);
}

/// Cup on a saucer; one closed surface of revolution from the outer foot over the rim down to
/// the inside bottom, so its inside faces the cavity.
void addCup(MeshBuilder& b, const Vec3f& at, const Vec3f& albedo, int segments)
{
  b.addCone(at, at + Vec3f(0.f, 0.012f, 0.f), 0.05f, 0.075f, segments, 1, false, albedo);
  b.addDisk(at + Vec3f(0.f, 0.012f, 0.f), kUp, 0.075f, segments, 2, albedo);
  const Vec3f foot = at + Vec3f(0.f, 0.012f, 0.f);
  b.addRevolution(foot, kUp,
    { { 0.f, 0.f }, { 0.02f, 0.f }, { 0.028f, 0.002f }, { 0.032f, 0.01f }, { 0.036f, 0.035f },
      { 0.04f, 0.06f }, { 0.042f, 0.07f }, { 0.04f, 0.074f }, { 0.037f, 0.07f },
      { 0.035f, 0.058f }, { 0.031f, 0.034f }, { 0.026f, 0.014f }, { 0.016f, 0.009f },
      { 0.f, 0.008f } },
    segments, albedo);
  b.addTorus(foot + Vec3f(0.045f, 0.04f, 0.f), Vec3f(0.f, 0.f, 1.f), 0.018f, 0.005f, 12, 6,
    albedo);
}
}

/// A 4 x 3 x 4 m tea room: round table with teapot and cups, chairs, sideboard, rug, a
/// pendant lamp over the table and a floor lamp in a corner.
Scene makeTearoom()
{
  MeshBuilder b;
  const Vec3f cream(0.78f, 0.72f, 0.6f), sage(0.45f, 0.55f, 0.4f), wood(0.45f, 0.3f, 0.18f);
  const Vec3f china(0.85f, 0.85f, 0.82f), cloth(0.6f, 0.15f, 0.12f), dark(0.25f);
  addRoom(b, Vec3f(-2.f, 0.f, -2.f), Vec3f(2.f, 3.f, 2.f), 0.19f, wood, Vec3f(0.8f),
    { sage, cream, cream, cream });
  // Rug: a single sheet just above the floor; its underside faces the floor and is never seen.
  addRect(b, Vec3f(-1.2f, 0.005f, -0.9f), Vec3f(0.f, 0.f, 1.8f), Vec3f(2.4f, 0.f, 0.f), 0.15f,
    cloth);

  // Round pedestal table.
  b.addCylinder(Vec3f(0.f, 0.72f, 0.f), Vec3f(0.f, 0.76f, 0.f), 0.6f, 64, 1, true, wood);
  b.addCylinder(Vec3f(0.f, 0.06f, 0.f), Vec3f(0.f, 0.72f, 0.f), 0.05f, 16, 6, false, wood);
  b.addCone(Vec3f(0.f), Vec3f(0.f, 0.06f, 0.f), 0.3f, 0.05f, 32, 3, false, wood);
  addTeapot(b, Vec3f(0.f, 0.76f, 0.f), china, 32);
  for (int k = 0; k < 4; ++k)
  {
    const float a = kPi * (0.25f + 0.5f * float(k));
    addCup(b, Vec3f(0.4f * std::sin(a), 0.76f, 0.4f * std::cos(a)), china, 20);
    // Chairs face the table's centre.
    addChair(b, Vec3f(0.9f * std::sin(a), 0.f, 0.9f * std::cos(a)), a + kPi, 0.1f, wood, dark);
  }
  // Sideboard with a vase, against the +z wall.
  addBoxAt(b, Vec3f(0.f, 0.45f, 1.78f), Vec3f(1.6f, 0.9f, 0.4f), 0.1f, wood);
  b.addRevolution(Vec3f(0.5f, 0.9f, 1.78f), kUp,
    { { 0.f, 0.f }, { 0.05f, 0.f }, { 0.08f, 0.08f }, { 0.07f, 0.18f }, { 0.04f, 0.25f },
      { 0.045f, 0.3f }, { 0.f, 0.3f } },
    24, Vec3f(0.2f, 0.35f, 0.6f));

  // Pendant lamp over the table and a floor lamp in the (+x, -z) corner.
  b.addCylinder(Vec3f(0.f, 2.35f, 0.f), Vec3f(0.f, 3.f, 0.f), 0.006f, 6, 2, false, dark);
  addShade(b, Vec3f(0.f, 2.05f, 0.f), 0.3f, 0.25f, 0.08f, 32, Vec3f(0.85f, 0.7f, 0.35f));
  const Vec3f corner(1.6f, 0.f, -1.6f);
  b.addCylinder(corner, corner + Vec3f(0.f, 0.03f, 0.f), 0.15f, 24, 1, true, dark);
  b.addCylinder(corner + Vec3f(0.f, 0.03f, 0.f), corner + Vec3f(0.f, 1.45f, 0.f), 0.015f, 8, 8,
    false, dark);
  addShade(b, corner + Vec3f(0.f, 1.4f, 0.f), 0.3f, 0.22f, 0.14f, 28, Vec3f(0.8f, 0.75f, 0.6f));

  Scene scene = b.take();
  scene.lights.push_back(pointLight(Vec3f(0.f, 2.2f, 0.f), Vec3f(6.f, 5.5f, 4.8f)));
  scene.lights.push_back(pointLight(corner + Vec3f(0.f, 1.55f, 0.f), Vec3f(3.f, 2.7f, 2.2f)));
  return scene;
}

/// IPHI-like proton injector in a 22 x 6 x 10 m hall: source on a high-voltage platform,
/// low-energy line with solenoids, a four-section RFQ with couplers, a line of quadrupoles and
/// toroidal cavities with bellows, and a shielded beam dump, all on supports; concrete
/// shielding and racks along the walls; four ceiling lights.
Scene makeIphi()
{
  MeshBuilder b;
  const Vec3f concrete(0.55f, 0.55f, 0.52f), wallPaint(0.7f, 0.7f, 0.65f);
  const Vec3f steel(0.6f, 0.6f, 0.62f), copper(0.72f, 0.45f, 0.3f), blue(0.2f, 0.3f, 0.6f);
  const Vec3f red(0.65f, 0.15f, 0.1f), yellow(0.8f, 0.65f, 0.1f), dark(0.2f);
  addRoom(b, Vec3f(-11.f, 0.f, -5.f), Vec3f(11.f, 6.f, 5.f), 0.18f, concrete, Vec3f(0.6f),
    { wallPaint, wallPaint, wallPaint, wallPaint });

  const float Y = 1.3f; // beam height
  const int seg = 50;
  const auto onAxis = [&](float x) { return Vec3f(x, Y, 0.f); };
  const auto tube = [&](float x0, float x1, float r, int segments, bool caps, const Vec3f& c)
  {
    const int stacks = std::max(1, int(std::ceil((x1 - x0) / 0.15f)));
    b.addCylinder(onAxis(x0), onAxis(x1), r, segments, stacks, caps, c);
  };
  const auto cavity = [&](float x, float major, float minor, const Vec3f& c)
  { b.addTorus(onAxis(x), Vec3f(1.f, 0.f, 0.f), major, minor, seg, 24, c); };
  const auto stand = [&](float x, float topY, float width)
  {
    addBoxAt(b, Vec3f(x, topY * 0.5f, 0.f), Vec3f(0.2f, topY, 0.2f), 0.1f, yellow);
    addBoxAt(b, Vec3f(x, 0.02f, 0.f), Vec3f(0.5f, 0.04f, width), 0.1f, dark);
  };

  // Source on its high-voltage platform, inside a cage of posts.
  addBoxAt(b, Vec3f(-8.75f, 0.45f, 0.f), Vec3f(2.5f, 0.9f, 2.f), 0.15f, blue);
  tube(-9.5f, -8.f, 0.4f, seg, true, steel);
  for (int k = 0; k < 4; ++k)
  {
    const Vec3f post(-9.9f + 2.3f * float(k & 1), 0.9f, (k & 2) ? 0.9f : -0.9f);
    b.addCylinder(post, post + Vec3f(0.f, 1.4f, 0.f), 0.03f, 12, 6, true, yellow);
  }
  // Low-energy line: solenoids on a thin tube.
  tube(-8.f, -5.6f, 0.06f, 24, false, steel);
  for (float x : { -7.4f, -6.5f })
  {
    tube(x - 0.18f, x + 0.18f, 0.25f, seg, true, red);
    stand(x, Y - 0.25f, 0.6f);
  }
  // RFQ: four sections with flanges, RF couplers on top and a vacuum port below.
  for (int s = 0; s < 4; ++s)
  {
    const float x0 = -5.6f + 1.45f * float(s), x1 = x0 + 1.45f;
    tube(x0 + 0.05f, x1 - 0.05f, 0.35f, seg, false, copper);
    tube(x0, x0 + 0.05f, 0.45f, seg, true, steel);
    tube(x1 - 0.05f, x1, 0.45f, seg, true, steel);
    const Vec3f c = onAxis(0.5f * (x0 + x1));
    b.addCylinder(c + Vec3f(0.f, 0.33f, 0.f), c + Vec3f(0.f, 0.9f, 0.f), 0.08f, 24, 6, true, steel);
    b.addTorus(c + Vec3f(0.f, 0.7f, 0.f), kUp, 0.1f, 0.03f, 24, 12, steel);
    b.addCylinder(c + Vec3f(0.f, 0.f, 0.33f), c + Vec3f(0.f, 0.f, 0.7f), 0.1f, 24, 4, true, steel);
    stand(x0 + 0.4f, Y - 0.35f, 0.9f);
    stand(x1 - 0.4f, Y - 0.35f, 0.9f);
  }
  // Medium-energy line: quadrupoles, toroidal cavities and bellows on a thin tube.
  tube(0.2f, 7.6f, 0.05f, 24, false, steel);
  for (int k = 0; k < 6; ++k)
  {
    const float x = 0.7f + 1.2f * float(k);
    addBoxAt(b, onAxis(x), Vec3f(0.3f, 0.45f, 0.45f), 0.05f, (k % 2) ? blue : red);
    cavity(x + 0.55f, 0.28f, 0.13f, copper);
    tube(x + 0.45f, x + 0.65f, 0.2f, seg, true, copper);
    for (int bellow = 0; bellow < 3; ++bellow)
    {
      b.addTorus(onAxis(x + 0.25f + 0.04f * float(bellow)), Vec3f(1.f, 0.f, 0.f), 0.065f, 0.015f,
        24, 8, steel);
    }
    stand(x, Y - 0.225f, 0.6f);
  }
  // Beam dump: a cone into a shielded cylinder in a concrete block.
  b.addCone(onAxis(7.6f), onAxis(8.3f), 0.05f, 0.35f, seg, 6, false, steel);
  tube(8.3f, 9.3f, 0.35f, seg, false, steel);
  addBoxAt(b, Vec3f(9.9f, 1.1f, 0.f), Vec3f(1.2f, 2.2f, 2.f), 0.15f, concrete);
  stand(8.8f, Y - 0.35f, 0.9f);

  // Shielding blocks along the back wall, racks along the front wall, a cable tray.
  for (int k = 0; k < 10; ++k)
  {
    addBoxAt(b, Vec3f(-9.f + 2.f * float(k), 0.8f, -4.3f), Vec3f(1.8f, 1.6f, 0.9f), 0.2f,
      concrete);
    addBoxAt(b, Vec3f(-9.f + 2.f * float(k), 1.f, 4.5f), Vec3f(0.6f, 2.f, 0.8f), 0.2f,
      (k % 3) ? dark : Vec3f(0.5f));
  }
  addBoxAt(b, Vec3f(0.f, 3.2f, -4.6f), Vec3f(20.f, 0.1f, 0.5f), 0.25f, steel);

  Scene scene = b.take();
  for (float x : { -7.5f, -2.5f, 2.5f, 7.5f })
  {
    scene.lights.push_back(pointLight(Vec3f(x, 5.5f, 0.f), Vec3f(30.f, 30.f, 27.f)));
  }
  return scene;
}

namespace
{
/// Office chair facing +z turned by `yaw`: seat, back, arm rests, gas spring, five-star base
/// with casters.
void addOfficeChair(MeshBuilder& b, const Vec3f& at, float yaw, const Vec3f& fabric)
{
  const Index first = b.vertexCount();
  const Vec3f black(0.06f), metal(0.6f);
  const float cell = 0.042f;
  addBoxAt(b, at + Vec3f(0.f, 0.48f, 0.f), Vec3f(0.5f, 0.08f, 0.48f), cell, fabric);
  addBoxAt(b, at + Vec3f(0.f, 0.85f, -0.24f), Vec3f(0.48f, 0.55f, 0.06f), cell, fabric);
  for (float side : { -1.f, 1.f })
  {
    addBoxAt(b, at + Vec3f(side * 0.27f, 0.66f, 0.f), Vec3f(0.05f, 0.03f, 0.3f), cell, black);
    addBoxAt(b, at + Vec3f(side * 0.27f, 0.58f, -0.08f), Vec3f(0.03f, 0.14f, 0.03f), cell, black);
  }
  b.addCylinder(at + Vec3f(0.f, 0.1f, 0.f), at + Vec3f(0.f, 0.44f, 0.f), 0.025f, 16, 4, false,
    metal);
  b.addCylinder(at + Vec3f(0.f, 0.07f, 0.f), at + Vec3f(0.f, 0.11f, 0.f), 0.05f, 16, 1, true,
    black);
  for (int k = 0; k < 5; ++k)
  {
    const float a = 2.f * kPi * float(k) / 5.f;
    const Vec3f dir(std::sin(a), 0.f, std::cos(a));
    addBoxAt(b, at + dir * 0.17f + Vec3f(0.f, 0.09f, 0.f), Vec3f(0.04f, 0.03f, 0.28f), cell,
      black, a, at);
    b.addSphere(at + dir * 0.3f + Vec3f(0.f, 0.025f, 0.f), 0.025f, 6, 10, black);
  }
  b.rotateY(first, at, yaw);
}
}

/// A 14 x 3.2 x 9 m conference room: a long table with office chairs around it, a whiteboard,
/// a projection screen, a credenza, plants, and four pendant lamps with their point lights.
Scene makeConference()
{
  MeshBuilder b;
  const Vec3f carpet(0.35f, 0.3f, 0.3f), wall(0.75f, 0.73f, 0.7f), accent(0.5f, 0.58f, 0.7f);
  const Vec3f wood(0.5f, 0.33f, 0.2f), metal(0.6f), fabric(0.2f, 0.3f, 0.55f);
  const Vec3f white(0.85f), dark(0.15f), leaf(0.15f, 0.4f, 0.12f), pot(0.55f, 0.3f, 0.2f);
  addRoom(b, Vec3f(-7.f, 0.f, -4.5f), Vec3f(7.f, 3.2f, 4.5f), 0.09f, carpet, Vec3f(0.8f),
    { accent, wall, wall, wall });

  // Long table (two joined tops) with 9 chairs per side and one at each end.
  addTable(b, Vec3f(-2.25f, 0.f, 0.f), Vec3f(4.5f, 0.74f, 1.6f), 0.08f, wood, metal, 16);
  addTable(b, Vec3f(2.25f, 0.f, 0.f), Vec3f(4.5f, 0.74f, 1.6f), 0.08f, wood, metal, 16);
  for (int k = 0; k < 9; ++k)
  {
    const float x = -4.f + 1.f * float(k);
    addOfficeChair(b, Vec3f(x, 0.f, -1.25f), 0.f, fabric);
    addOfficeChair(b, Vec3f(x, 0.f, 1.25f), kPi, fabric);
  }
  addOfficeChair(b, Vec3f(-5.1f, 0.f, 0.f), 0.5f * kPi, fabric);
  addOfficeChair(b, Vec3f(5.1f, 0.f, 0.f), -0.5f * kPi, fabric);

  // Whiteboard with a tray on the -x wall; projection screen on the +x wall.
  addBoxAt(b, Vec3f(-6.97f, 1.5f, 0.f), Vec3f(0.04f, 1.2f, 3.f), 0.05f, white);
  addBoxAt(b, Vec3f(-6.92f, 0.88f, 0.f), Vec3f(0.08f, 0.03f, 2.6f), 0.05f, metal);
  addBoxAt(b, Vec3f(6.98f, 1.7f, 0.f), Vec3f(0.02f, 1.6f, 2.8f), 0.05f, white);
  // Credenza along the +z wall, plants in the corners.
  addBoxAt(b, Vec3f(0.f, 0.4f, 4.2f), Vec3f(4.f, 0.8f, 0.5f), 0.08f, wood);
  for (int k = 0; k < 4; ++k)
  {
    const Vec3f c((k & 1) ? 6.4f : -6.4f, 0.f, (k & 2) ? 3.9f : -3.9f);
    b.addCone(c, c + Vec3f(0.f, 0.45f, 0.f), 0.16f, 0.22f, 32, 4, true, pot);
    b.addSphere(c + Vec3f(0.f, 0.85f, 0.f), 0.4f, 20, 32, leaf);
  }
  // Pendant lamps: a cable and a flat shade over each light.
  std::vector<Vec3f> lamps;
  for (float x : { -4.5f, -1.5f, 1.5f, 4.5f })
  {
    const Vec3f c(x, 2.45f, 0.f);
    lamps.push_back(c - Vec3f(0.f, 0.02f, 0.f));
    b.addCylinder(c + Vec3f(0.f, 0.05f, 0.f), Vec3f(x, 3.2f, 0.f), 0.005f, 6, 2, false, dark);
    addShade(b, c - Vec3f(0.f, 0.05f, 0.f), 0.1f, 0.3f, 0.28f, 64, white);
    // Closed top: a thin two-sided lid, so that the light goes down only.
    b.addDisk(c + Vec3f(0.f, 0.045f, 0.f), -kUp, 0.28f, 64, 6, white);
    b.addDisk(c + Vec3f(0.f, 0.05f, 0.f), kUp, 0.28f, 64, 6, white);
  }

  Scene scene = b.take();
  for (const Vec3f& p : lamps)
  {
    scene.lights.push_back(pointLight(p, Vec3f(8.f, 7.6f, 7.f)));
  }
  return scene;
}
}
