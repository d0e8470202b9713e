// Geometry from files against analytic answers: a trimesh floor, a heightfield, an OctoMap,
// the occupancy map of known boxes, OGRE material scripts, and one-line errors for bad files.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>

#include <octomap/OcTree.h>

#include "rotors_core/geometry/ogre_material.h"
#include "rotors_core/error.h"
#include "rotors_core/geometry/occupancy_mapper.h"
#include "rotors_core/geometry/shapes.h"
#include "rotors_core/model_builder.h"
#include "rotors_core/physics/link.h"
#include "rotors_core/physics/model.h"
#include "rotors_core/physics/world.h"
#include "rotors_core/world_loader.h"
#include "test_worlds.h"

using namespace rotors_sim;
namespace fs = std::filesystem;

namespace {

std::string StaticModel(const std::string& name, const std::string& geometry, const std::string& pose = "0 0 0 0 0 0") {
  return "<model name='" + name + "'><static>true</static><pose>" + pose + "</pose><link name='link'>" +
         "<collision name='collision'><geometry>" + geometry + "</geometry></collision>" +
         "<visual name='visual'><geometry>" + geometry + "</geometry></visual></link></model>";
}

std::string World(const std::string& models, const std::string& solver = "world") {
  std::string w = WorldSdf(0.01, -9.8, false, solver);
  return w.substr(0, w.find("</world>")) + models + "</world></sdf>";
}

physics::ModelPtr DropBox(const physics::WorldPtr& w, const std::string& name, double x, double y, double z) {
  SpawnRequest r;
  r.xml = BoxUrdf(name, 1.5, 0.0347563, 0.0458929, 0.0977, 0.1, 0.1, 0.16);
  r.X_WM = physics::Pose3d(x, y, z, 0, 0, 0);
  return ModelBuilder::Spawn(w, r);
}

std::string LoadError(const std::string& world_text) {
  try {
    WorldGuard g{WorldLoader::LoadString(world_text, "bad")};
  } catch (const SimError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

// A box dropped on a mesh floor at z = 0.5 m rests with its centre half its height above it.
TEST(Geometry, BoxRestsOnTrimeshFloorAtAnalyticHeight) {
  WorldGuard g{
      WorldLoader::LoadString(World(StaticModel("floor", "<mesh><uri>" + FloorObj(5, 0.5) + "</uri></mesh>")), "mesh")};
  auto box = DropBox(g.world, "box", 0.3, -0.2, 1.0);
  const uint64_t messages = physics::OdeMessageCount();
  g.world->Step(500);
  const auto link = box->GetLinks().front();
  EXPECT_NEAR(link->WorldPose().Pos().Z(), 0.5 + 0.08, 1.5e-3);  // within the 1 mm surface layer
  EXPECT_LT(link->WorldLinearVel().Length(), 1e-4);
  EXPECT_EQ(physics::OdeMessageCount(), messages);
  ASSERT_EQ(g.world->ModelByName("floor")->Visuals().size(), 1u);
  EXPECT_EQ(g.world->ModelByName("floor")->Visuals()[0].shape.mesh->TriangleCount(), 2u);
}

// A heightmap ramp (height = x-fraction * 4 m over 20 m) carries small balls at the ramp's
// height wherever they land.
TEST(Geometry, HeightfieldGivesContactHeightOfTheTerrain) {
  const std::string hm = "<heightmap><uri>" + RampPgm(33) + "</uri><size>20 20 4</size><pos>1 2 0.5</pos></heightmap>";
  WorldGuard g{WorldLoader::LoadString(World(StaticModel("terrain", hm), "quick"), "heightmap")};
  const auto field = geometry::LoadHeightmap(TempDir() / "ramp.pgm", {20, 20, 4}, {1, 2, 0.5});
  const double points[][2] = {{-5, 0}, {1, 2}, {6, 7}, {9.5, -6}};
  std::vector<physics::ModelPtr> balls;
  for (int i = 0; i < 4; ++i) {
    SpawnRequest r;
    r.xml =
        "<robot name='b'><link name='ball" + std::to_string(i) +
        "'><inertial><mass value='0.1'/><inertia ixx='1e-4' ixy='0' ixz='0' iyy='1e-4' iyz='0' izz='1e-4'/></inertial>"
        "<collision><geometry><sphere radius='0.1'/></geometry></collision></link></robot>";
    r.model_name = "ball" + std::to_string(i);
    r.X_WM = physics::Pose3d(points[i][0], points[i][1], field->HeightAt(points[i][0], points[i][1]) + 0.105, 0, 0, 0);
    balls.push_back(ModelBuilder::Spawn(g.world, r));
  }
  g.world->Step(100);  // 1 s: landed and rolling down the 11 deg slope, in contact
  for (int i = 0; i < 4; ++i) {
    const auto p = balls[i]->GetLinks().front()->WorldPose().Pos();
    // on a slope of angle a the centre of a resting ball is r / cos(a) above the terrain
    const double slope = 4.0 / 20.0, r_over_cos = 0.1 * std::sqrt(1 + slope * slope);
    EXPECT_NEAR(p.Z(), field->HeightAt(p.X(), p.Y()) + r_over_cos, 3e-3) << "ball " << i;
  }
  // the field itself: 0.5 m at the west edge, 4.5 m at the east edge, linear between
  EXPECT_NEAR(field->HeightAt(1 - 10, 2), 0.5, 1e-9);
  EXPECT_NEAR(field->HeightAt(1 + 10, 2), 4.5, 1e-9);
  EXPECT_NEAR(field->HeightAt(1 + 2.5, 2), 0.5 + 4 * 12.5 / 20, 4.0 / 255 + 1e-9);
}

// Boxes of known size give exactly the cells they cover: a 1 x 0.5 x 0.75 m box aligned with the
// 0.25 m grid covers 4 x 2 x 3 = 24 cells; a unit cube offset by half a cell overlaps 5^3 = 125.
TEST(Geometry, OccupancyOfKnownBoxesHasExactlyTheExpectedLeaves) {
  const std::string models = StaticModel("a", "<box><size>1 0.5 0.75</size></box>", "2.5 0.25 0.375 0 0 0") +
                             StaticModel("b", "<box><size>1 1 1</size></box>", "-2.125 -2.125 1.125 0 0 0");
  WorldGuard g{WorldLoader::LoadString(World(models), "boxes")};
  geometry::OccupancyRequest request;
  request.center_W = {0, 0, 2};
  request.lengths_m = {10, 10, 4};
  request.leaf_size_m = 0.25;
  auto tree = geometry::BuildOccupancy(*g.world, request);
  int in_a = 0, in_b = 0, total = 0;
  for (auto it = tree->begin_leafs(); it != tree->end_leafs(); ++it) {
    if (!tree->isNodeOccupied(*it)) continue;
    const double cells = std::pow(it.getSize() / 0.25, 3);
    total += static_cast<int>(std::lround(cells));
    (it.getX() > 0 ? in_a : in_b) += static_cast<int>(std::lround(cells));
  }
  EXPECT_EQ(in_a, 24);
  EXPECT_EQ(in_b, 125);
  EXPECT_EQ(total, 149);
}

// A box dropped on an OctoMap floor (a slab of leaves) rests on the slab's top face.
TEST(Geometry, BoxRestsOnOcTreeFloor) {
  octomap::OcTree slab(0.25);
  for (double x = -2; x < 2; x += 0.25)
    for (double y = -2; y < 2; y += 0.25) slab.updateNode(octomap::point3d(x + 0.125, y + 0.125, 0.125), true);
  const std::string path = (TempDir() / "slab.bt").string();
  ASSERT_TRUE(slab.writeBinary(path));
  WorldGuard g{WorldLoader::LoadString(World(StaticModel("slab", "<mesh><uri>" + path + "</uri></mesh>")), "octree")};
  auto box = DropBox(g.world, "box", 0.1, 0.05, 1.0);  // across four leaves
  const uint64_t messages = physics::OdeMessageCount();
  g.world->Step(500);
  const auto link = box->GetLinks().front();
  EXPECT_NEAR(link->WorldPose().Pos().Z(), 0.25 + 0.08, 1.5e-3);
  EXPECT_NEAR(link->WorldPose().Pos().X(), 0.1, 1e-3);
  EXPECT_LT(link->WorldAngularVel().Length(), 1e-4);
  EXPECT_EQ(physics::OdeMessageCount(), messages);
}

// Bad files: one line naming the file and the problem; nothing half-loaded.
TEST(Geometry, BadFilesGiveOneLineNamingTheFile) {
  const std::string missing = (TempDir() / "no_such_mesh.dae").string();
  std::string e = LoadError(World(StaticModel("m", "<mesh><uri>" + missing + "</uri></mesh>")));
  EXPECT_NE(e.find("no_such_mesh.dae"), std::string::npos) << e;
  EXPECT_NE(e.find("does not exist"), std::string::npos) << e;

  const fs::path garbage = TempDir() / "garbage.stl";
  std::ofstream(garbage) << "this is not a mesh\n";
  e = LoadError(World(StaticModel("m", "<mesh><uri>" + garbage.string() + "</uri></mesh>")));
  EXPECT_NE(e.find("garbage.stl"), std::string::npos) << e;

  e = LoadError(World(
      StaticModel("h", "<heightmap><uri>" + RampPgm(30, "wrong.pgm") + "</uri><size>10 10 1</size></heightmap>")));
  EXPECT_NE(e.find("wrong.pgm"), std::string::npos) << e;
  EXPECT_NE(e.find("30 x 30"), std::string::npos) << e;

  e = LoadError(World(StaticModel("u", "<mesh><uri>model://no_such_model/meshes/x.dae</uri></mesh>")));
  EXPECT_NE(e.find("model://no_such_model"), std::string::npos) << e;

  const fs::path corrupt = TempDir() / "corrupt.bt";
  std::ofstream(corrupt) << "# Octomap OcTree binary file\nid OcTree\nsize 1000\nres 0.25\ndata\n\x01\x02";
  e = LoadError(World(StaticModel("o", "<mesh><uri>" + corrupt.string() + "</uri></mesh>")));
  EXPECT_NE(e.find("corrupt.bt"), std::string::npos) << e;

  for (const std::string& message : {e}) EXPECT_EQ(message.find('\n'), std::string::npos) << message;
}

// Gazebo's material scripts: RotorS' asphalt material (first pass colours, the texture unit's
// image and scale), comments and nested blocks; a broken script names its file and line.
TEST(OgreMaterial, ParsesColoursTextureAndScaleOfTheFirstPass) {
  const std::string text = R"(// RotorS' asphalt_plane
material vrc/asphalt
{
  technique
  {
    pass
    {
      ambient 0.5 0.5 0.5 1.0
      diffuse 0.4 0.5 0.6 1.0
      specular 0.2 0.2 0.2 1.0 12.5
      texture_unit
      {
        texture tarmac.png
        filtering anistropic
        max_anisotropy 16
        scale 0.1 0.2
      }
    }
    pass
    {
      diffuse 1 0 0 1
    }
  }
}
material plain { technique { pass { diffuse 0.1 0.2 0.3 } } }
)";
  const auto materials = rotors_sim::geometry::ParseOgreMaterials(text, "asphalt.material");
  ASSERT_EQ(materials.size(), 2u);
  const auto& asphalt = materials.at("vrc/asphalt");
  EXPECT_FLOAT_EQ(asphalt.diffuse[0], 0.4f);
  EXPECT_FLOAT_EQ(asphalt.diffuse[2], 0.6f);
  EXPECT_FLOAT_EQ(asphalt.ambient[1], 0.5f);
  EXPECT_EQ(asphalt.texture, "tarmac.png");
  EXPECT_FLOAT_EQ(asphalt.scale[0], 0.1f);
  EXPECT_FLOAT_EQ(asphalt.scale[1], 0.2f);
  EXPECT_FLOAT_EQ(asphalt.max_anisotropy, 16.0f);  // RotorS' misspelt "anistropic" filter counts
  EXPECT_FLOAT_EQ(materials.at("plain").diffuse[1], 0.2f);
  EXPECT_TRUE(materials.at("plain").texture.empty());
  EXPECT_FLOAT_EQ(materials.at("plain").max_anisotropy, 1.0f);
  try {
    rotors_sim::geometry::ParseOgreMaterials("material m\n{\n  technique\n  {\n    pass\n    {\n      diffuse a b c\n",
                                             "m.material");
    FAIL() << "a broken script must be refused";
  } catch (const rotors_sim::SimError& e) {
    EXPECT_STREQ(e.what(), "m.material:7: 'diffuse' needs numbers");
  }
}

// Gazebo's built-in material names (file://media/materials/scripts/gazebo.material) in Gazebo's
// colours, from SDF scripts and from a URDF's <gazebo><material>; an unknown name is one line
// naming it and the files searched.
TEST(OgreMaterial, GazebosBuiltInNamesHaveGazebosColours) {
  auto scripted = [](const std::string& name) {
    return "<model name='m'><static>true</static><link name='link'><visual name='v'><geometry><box><size>1 1 1"
           "</size></box></geometry><material><script><uri>file://media/materials/scripts/gazebo.material</uri>"
           "<name>" +
           name + "</name></script></material></visual></link></model>";
  };
  WorldGuard g{WorldLoader::LoadString(World(scripted("Gazebo/Orange")), "builtin")};
  const auto& orange = g.world->ModelByName("m")->Visuals().at(0).rgba;
  EXPECT_FLOAT_EQ(orange[0], 1.0f);
  EXPECT_FLOAT_EQ(orange[1], 0.5088f);
  EXPECT_FLOAT_EQ(orange[2], 0.0468f);

  SpawnRequest urdf;
  urdf.xml = R"(<robot name="crate"><link name="body"><visual><geometry><box size="1 1 1"/></geometry></visual>
    <inertial><mass value="1"/><inertia ixx="0.1" iyy="0.1" izz="0.1" ixy="0" ixz="0" iyz="0"/></inertial></link>
    <gazebo reference="body"><material>Gazebo/SkyBlue</material></gazebo></robot>)";
  const auto crate = ModelBuilder::Spawn(g.world, urdf);
  const auto& sky_blue = crate->Visuals().at(0).rgba;
  EXPECT_FLOAT_EQ(sky_blue[0], 0.0f);  // Gazebo's diffuse of SkyBlue is 0 0 1 (its ambient 0.13 0.44 0.70)
  EXPECT_FLOAT_EQ(sky_blue[2], 1.0f);

  const std::string e = LoadError(World(scripted("Gazebo/NoSuchColour")));
  EXPECT_NE(e.find("material 'Gazebo/NoSuchColour' is in none of the .material files"), std::string::npos) << e;
  EXPECT_NE(e.find("gazebo.material"), std::string::npos) << e;
  EXPECT_EQ(e.find('\n'), std::string::npos) << e;
}
