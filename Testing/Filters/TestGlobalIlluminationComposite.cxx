// vtkGlobalIlluminationFilter on composite input: all blocks are one scene (light bounces
// and shadows cross blocks), the output keeps the input's structure, and every block gets
// the arrays it would have as part of the appended surface.
#include "FilterTestUtilities.h"

#include "vtkAppendPolyData.h"
#include "vtkDataObjectTreeIterator.h"
#include "vtkDataSetSurfaceFilter.h"
#include "vtkGlobalIlluminationBlockMerger.h"
#include "vtkGlobalIlluminationFilter.h"
#include "vtkImageData.h"
#include "vtkMultiBlockDataSet.h"
#include "vtkPartitionedDataSet.h"
#include "vtkPartitionedDataSetCollection.h"
#include "vtkTransform.h"
#include "vtkTransformPolyDataFilter.h"

#include <gtest/gtest.h>


using namespace linkgi_test;

namespace
{
const char* const Results[] = { "DirectIrradiance", "IndirectIrradiance", "Radiance" };

/// A 2 x 2 floor (z = 0) with a grey "Albedo" point array.
vtkSmartPointer<vtkPolyData> Floor()
{
  vtkSmartPointer<vtkPolyData> floor = MakeFloor(1, 10);
  vtkNew<vtkFloatArray> albedo;
  albedo->SetName("Albedo");
  albedo->SetNumberOfComponents(3);
  for (vtkIdType i = 0; i < floor->GetNumberOfPoints(); ++i)
  {
    albedo->InsertNextTuple3(0.8, 0.8, 0.8);
  }
  floor->GetPointData()->AddArray(albedo);
  return floor;
}

/// A cube of edge 0.5 standing on the floor, off centre, without normals or albedo array.
vtkSmartPointer<vtkPolyData> Box()
{
  vtkNew<vtkTransform> place;
  place->Translate(-0.1, -0.3, 0.0);
  place->Scale(0.5, 0.5, 0.5);
  vtkNew<vtkTransformPolyDataFilter> transform;
  transform->SetInputData(MakeCube());
  transform->SetTransform(place);
  transform->Update();
  return transform->GetOutput();
}

/// The filter's settings for every run: the box gets the constant albedo.
vtkSmartPointer<vtkGlobalIlluminationFilter> Filter(vtkDataObject* input)
{
  auto filter = vtkSmartPointer<vtkGlobalIlluminationFilter>::New();
  filter->SetInputData(input);
  filter->SetRaysPerVertex(64);
  filter->SetAlbedoArrayName("Albedo");
  filter->SetAlbedo(0.9, 0.3, 0.1);
  const double lamp[3] = { 0.6, 0.4, 1.5 }, origin[3] = { 0, 0, 0 };
  filter->AddLight(MakeLight(lamp, origin, 2.0));
  return filter;
}

/// What the blocks are as one vtkPolyData: appended, with the box's constant albedo.
vtkSmartPointer<vtkPolyData> Appended(const std::vector<vtkPolyData*>& blocks)
{
  vtkNew<vtkAppendPolyData> append;
  for (vtkPolyData* block : blocks)
  {
    auto copy = vtkSmartPointer<vtkPolyData>::New();
    copy->ShallowCopy(block);
    if (!copy->GetPointData()->GetArray("Albedo"))
    {
      vtkNew<vtkFloatArray> albedo;
      albedo->SetName("Albedo");
      albedo->SetNumberOfComponents(3);
      for (vtkIdType i = 0; i < copy->GetNumberOfPoints(); ++i)
      {
        albedo->InsertNextTuple3(0.9, 0.3, 0.1);
      }
      copy->GetPointData()->AddArray(albedo);
    }
    copy->GetPointData()->SetTCoords(nullptr);
    copy->GetPointData()->SetNormals(nullptr);
    append->AddInputData(copy);
  }
  append->Update();
  return append->GetOutput();
}

/// The leaves of `data` in traversal order (empty nodes skipped).
std::vector<vtkPolyData*> Leaves(vtkDataObject* data)
{
  std::vector<vtkPolyData*> leaves;
  auto tree = vtkDataObjectTree::SafeDownCast(data);
  auto it = vtk::TakeSmartPointer(tree->NewTreeIterator());
  it->VisitOnlyLeavesOn();
  it->SkipEmptyNodesOn();
  for (it->InitTraversal(); !it->IsDoneWithTraversal(); it->GoToNextItem())
  {
    leaves.push_back(vtkPolyData::SafeDownCast(it->GetCurrentDataObject()));
  }
  return leaves;
}

/// Every leaf's result arrays equal the appended surface's at its points.
void ExpectSameAsAppended(vtkDataObject* output, vtkPolyData* appended)
{
  vtkIdType first = 0;
  for (vtkPolyData* leaf : Leaves(output))
  {
    ASSERT_NE(leaf, nullptr);
    for (const char* name : Results)
    {
      ASSERT_NE(PointArray(leaf, name), nullptr) << name;
      ASSERT_EQ(PointArray(leaf, name)->GetNumberOfTuples(), leaf->GetNumberOfPoints());
      for (vtkIdType i = 0; i < leaf->GetNumberOfPoints(); ++i)
      {
        for (int c = 0; c < 3; ++c)
        {
          const double expected = Value(appended, name, first + i, c);
          ASSERT_NEAR(Value(leaf, name, i, c), expected, 1e-5 * std::max(1.0, expected))
            << name << " point " << first + i;
        }
      }
    }
    first += leaf->GetNumberOfPoints();
  }
  EXPECT_EQ(first, appended->GetNumberOfPoints());
}

double Max(vtkPolyData* data, const char* name)
{
  return PointArray(data, name)->GetRange(0)[1];
}
}

TEST(GlobalIlluminationComposite, TwoBlocksAreSolvedAsOneScene)
{
  vtkSmartPointer<vtkPolyData> floor = Floor(), box = Box();
  vtkNew<vtkMultiBlockDataSet> blocks;
  blocks->SetBlock(0, floor);
  blocks->SetBlock(1, box);
  auto filter = Filter(blocks);
  filter->Update();
  vtkDataObject* output = filter->GetOutputDataObject(0);
  ASSERT_NE(vtkMultiBlockDataSet::SafeDownCast(output), nullptr);
  EXPECT_EQ(filter->GetOutput(), nullptr) << "GetOutput() is for vtkPolyData input";

  auto single = Filter(Appended({ floor, box }));
  single->Update();
  ExpectSameAsAppended(output, single->GetOutput());

  // The floor alone has nothing to bounce light off (the sky is black), nothing to shadow it.
  auto alone = Filter(floor);
  alone->Update();
  vtkPolyData* litFloor = Leaves(output)[0];
  EXPECT_EQ(Max(alone->GetOutput(), "IndirectIrradiance"), 0.0);
  EXPECT_GT(Max(litFloor, "IndirectIrradiance"), 0.01) << "the box bounces light onto the floor";
  double shadowed = 0;
  for (vtkIdType i = 0; i < floor->GetNumberOfPoints(); ++i)
  {
    shadowed += Value(litFloor, "DirectIrradiance", i) < 0.5 * Value(alone->GetOutput(), "DirectIrradiance", i);
  }
  EXPECT_GT(shadowed, 0) << "the box shadows the floor";
  EXPECT_EQ(Stat(single->GetOutput(), "Elements"),
    vtkDataArray::SafeDownCast(output->GetFieldData()->GetArray("LinkGI.Elements"))->GetTuple1(0));
}

TEST(GlobalIlluminationComposite, NestedAndPartitionedStructuresAreKept)
{
  vtkSmartPointer<vtkPolyData> floor = Floor(), box = Box();
  auto reference = Filter(Appended({ floor, box }));
  reference->Update();

  vtkNew<vtkMultiBlockDataSet> inner, outer, deeper;
  inner->SetBlock(0, floor);
  deeper->SetBlock(0, box);
  outer->SetBlock(0, inner);
  outer->SetBlock(1, nullptr);
  outer->SetBlock(2, deeper);
  auto nested = Filter(outer);
  nested->Update();
  auto out = vtkMultiBlockDataSet::SafeDownCast(nested->GetOutputDataObject(0));
  ASSERT_NE(out, nullptr);
  ASSERT_EQ(out->GetNumberOfBlocks(), 3u);
  EXPECT_EQ(out->GetBlock(1), nullptr);
  ASSERT_NE(vtkMultiBlockDataSet::SafeDownCast(out->GetBlock(2)), nullptr);
  EXPECT_NE(out->GetBlock(2), deeper.GetPointer()) << "the input's nested blocks are not reused";
  ExpectSameAsAppended(out, reference->GetOutput());

  vtkNew<vtkPartitionedDataSet> floorParts, boxParts;
  floorParts->SetPartition(0, floor);
  boxParts->SetPartition(0, box);
  vtkNew<vtkPartitionedDataSetCollection> collection;
  collection->SetPartitionedDataSet(0, floorParts);
  collection->SetPartitionedDataSet(1, boxParts);
  auto partitioned = Filter(collection);
  partitioned->Update();
  ASSERT_NE(vtkPartitionedDataSetCollection::SafeDownCast(partitioned->GetOutputDataObject(0)), nullptr);
  ExpectSameAsAppended(partitioned->GetOutputDataObject(0), reference->GetOutput());

  vtkNew<vtkPartitionedDataSet> parts;
  parts->SetPartition(0, floor);
  parts->SetPartition(1, box);
  auto flat = Filter(parts);
  flat->Update();
  ASSERT_NE(vtkPartitionedDataSet::SafeDownCast(flat->GetOutputDataObject(0)), nullptr);
  ExpectSameAsAppended(flat->GetOutputDataObject(0), reference->GetOutput());
}

TEST(GlobalIlluminationComposite, EmptyBlocksAndBlocksWithoutTrianglesPassThrough)
{
  vtkSmartPointer<vtkPolyData> floor = Floor();
  vtkNew<vtkPolyData> empty;
  vtkNew<vtkPolyData> wire; // a line above the floor: no triangles, casts no shadow
  vtkNew<vtkPoints> points;
  points->InsertNextPoint(0, 0, 0.5);
  points->InsertNextPoint(0.5, 0, 0.5);
  vtkNew<vtkCellArray> lines;
  const vtkIdType line[2] = { 0, 1 };
  lines->InsertNextCell(2, line);
  wire->SetPoints(points);
  wire->SetLines(lines);
  vtkNew<vtkMultiBlockDataSet> blocks;
  blocks->SetBlock(0, empty);
  blocks->SetBlock(1, floor);
  blocks->SetBlock(2, nullptr);
  blocks->SetBlock(3, wire);
  auto filter = Filter(blocks);
  MessageCapture messages(filter);
  filter->Update();
  EXPECT_TRUE(messages.Errors.empty());
  auto out = vtkMultiBlockDataSet::SafeDownCast(filter->GetOutputDataObject(0));
  ASSERT_NE(out, nullptr);
  ASSERT_EQ(out->GetNumberOfBlocks(), 4u);
  EXPECT_EQ(out->GetBlock(2), nullptr);
  auto litEmpty = vtkPolyData::SafeDownCast(out->GetBlock(0));
  auto litWire = vtkPolyData::SafeDownCast(out->GetBlock(3));
  ASSERT_TRUE(litEmpty && litWire);
  ASSERT_NE(PointArray(litEmpty, "Radiance"), nullptr);
  EXPECT_EQ(PointArray(litEmpty, "Radiance")->GetNumberOfTuples(), 0);
  EXPECT_EQ(Max(litWire, "Radiance"), 0.0) << "lines are passed through unlit";
  EXPECT_EQ(litWire->GetNumberOfLines(), 1);

  auto alone = Filter(floor);
  alone->Update();
  auto litFloor = vtkPolyData::SafeDownCast(out->GetBlock(1));
  for (vtkIdType i = 0; i < floor->GetNumberOfPoints(); ++i)
  {
    ASSERT_NEAR(Value(litFloor, "Radiance", i), Value(alone->GetOutput(), "Radiance", i), 1e-6);
  }

  vtkNew<vtkMultiBlockDataSet> nothing; // only empty blocks: an empty output, a warning
  nothing->SetBlock(0, empty);
  nothing->SetBlock(1, nullptr);
  filter->SetInputData(nothing);
  messages.Clear();
  filter->Update();
  EXPECT_TRUE(messages.HasWarning("The input is empty"));
  EXPECT_TRUE(messages.Errors.empty());
  ASSERT_NE(vtkMultiBlockDataSet::SafeDownCast(filter->GetOutputDataObject(0)), nullptr);
}

TEST(GlobalIlluminationComposite, OtherDatasetsAreLitAsTheirSurface)
{
  vtkSmartPointer<vtkPolyData> floor = Floor();
  vtkNew<vtkImageData> block; // a 0.4 cube of 2 x 2 x 2 cells on the floor
  block->SetDimensions(3, 3, 3);
  block->SetSpacing(0.2, 0.2, 0.2);
  block->SetOrigin(0.1, 0.1, 0.0);
  vtkNew<vtkMultiBlockDataSet> blocks;
  blocks->SetBlock(0, floor);
  blocks->SetBlock(1, block);
  auto filter = Filter(blocks);
  filter->Update();
  vtkPolyData* surface = Leaves(filter->GetOutputDataObject(0))[1];
  ASSERT_NE(surface, nullptr) << "the image's block is its lit surface";
  vtkNew<vtkDataSetSurfaceFilter> extract;
  extract->SetInputData(block);
  extract->Update();
  EXPECT_EQ(surface->GetNumberOfPoints(), extract->GetOutput()->GetNumberOfPoints());
  auto reference = Filter(Appended({ floor, extract->GetOutput() }));
  reference->Update();
  ExpectSameAsAppended(filter->GetOutputDataObject(0), reference->GetOutput());

  filter->SetInputData(block); // a lone vtkImageData gives a vtkPolyData
  filter->SetAlbedoArrayName(nullptr);
  filter->Update();
  ASSERT_NE(filter->GetOutput(), nullptr);
  EXPECT_EQ(filter->GetOutput()->GetNumberOfPoints(), extract->GetOutput()->GetNumberOfPoints());
  EXPECT_GT(Max(filter->GetOutput(), "DirectIrradiance"), 0.0);
}

TEST(GlobalIlluminationComposite, InputIsUntouchedAndLightChangesDoNotRelink)
{
  vtkSmartPointer<vtkPolyData> floor = Floor(), box = Box();
  vtkNew<vtkMultiBlockDataSet> blocks;
  blocks->SetBlock(0, floor);
  blocks->SetBlock(1, box);
  blocks->GetFieldData()->AddArray(vtkSmartPointer<vtkFloatArray>::New());
  blocks->GetFieldData()->GetAbstractArray(0)->SetName("Mine");
  auto filter = Filter(blocks);
  filter->Update();
  EXPECT_EQ(PointArray(floor, "DirectIrradiance"), nullptr);
  EXPECT_EQ(blocks->GetFieldData()->GetAbstractArray("LinkGI.Elements"), nullptr);
  vtkDataObject* output = filter->GetOutputDataObject(0);
  EXPECT_NE(output->GetFieldData()->GetAbstractArray("Mine"), nullptr) << "field data passes";
  const auto stat = [&](const char* name) {
    return vtkDataArray::SafeDownCast(output->GetFieldData()->GetArray(name))->GetTuple1(0);
  };
  const double before = Value(Leaves(output)[0], "DirectIrradiance", 0);

  filter->GetLight(0)->SetPosition(-0.6, 0.4, 1.5);
  filter->Update();
  output = filter->GetOutputDataObject(0);
  EXPECT_EQ(stat("LinkGI.LinkBuilds"), 1.0) << "a moved light does not relink";
  EXPECT_EQ(stat("LinkGI.LightLinkBuilds"), 2.0);
  const double moved = Value(Leaves(output)[0], "DirectIrradiance", 0);
  EXPECT_NE(moved, before);

  floor->Modified(); // a block changed: merged and solved again, to the same result
  filter->Update();
  output = filter->GetOutputDataObject(0);
  EXPECT_NEAR(Value(Leaves(output)[0], "DirectIrradiance", 0), moved, 1e-6);

  filter->TwoSidedOn(); // arrays of an earlier update do not linger on the blocks
  filter->Update();
  EXPECT_NE(PointArray(Leaves(filter->GetOutputDataObject(0))[1], "RadianceBack"), nullptr);
  filter->TwoSidedOff();
  filter->Update();
  EXPECT_EQ(PointArray(Leaves(filter->GetOutputDataObject(0))[1], "RadianceBack"), nullptr);
}

TEST(GlobalIlluminationComposite, ColourArraysAreCheckedPerBlock)
{
  vtkSmartPointer<vtkPolyData> floor = Floor(), box = Box();
  vtkNew<vtkMultiBlockDataSet> blocks;
  blocks->SetBlock(0, box);
  blocks->SetBlock(1, floor);
  auto filter = Filter(blocks);
  filter->SetAlbedoArrayName("NoSuchAlbedo");
  MessageCapture messages(filter);
  filter->Update();
  EXPECT_TRUE(messages.HasError("'NoSuchAlbedo' is not a numeric array of the point data of any block"));

  vtkNew<vtkFloatArray> shortAlbedo;
  shortAlbedo->SetName("Short");
  shortAlbedo->InsertNextValue(0.5f);
  floor->GetPointData()->AddArray(shortAlbedo);
  filter->SetAlbedoArrayName("Short");
  messages.Clear();
  filter->Update();
  EXPECT_TRUE(messages.HasError("'Short' of block 1 has 1 tuples, but the block has 121 points"));
}

TEST(GlobalIlluminationComposite, TheMergerMergesOnlyWhatChanged)
{
  vtkSmartPointer<vtkPolyData> floor = Floor(), box = Box();
  vtkNew<vtkMultiBlockDataSet> blocks;
  blocks->SetBlock(0, floor);
  blocks->SetBlock(1, box);
  vtkGlobalIlluminationBlockMerger merger;
  const std::vector<vtkGlobalIlluminationBlockMerger::Carried> albedo = { { "Albedo",
    vtkDataObject::FIELD_ASSOCIATION_POINTS, { { 0.9, 0.3, 0.1 } }, "albedo" } };
  EXPECT_TRUE(merger.Merge(blocks, albedo));
  EXPECT_EQ(merger.GetNumberOfLeaves(), 2u);
  vtkPolyData* merged = merger.GetMerged();
  EXPECT_EQ(merged->GetNumberOfPoints(), floor->GetNumberOfPoints() + box->GetNumberOfPoints());
  vtkDataArray* colours = PointArray(merged, "Albedo");
  ASSERT_NE(colours, nullptr);
  EXPECT_NEAR(colours->GetComponent(0, 0), 0.8, 1e-6);                             // the floor's
  EXPECT_NEAR(colours->GetComponent(floor->GetNumberOfPoints(), 0), 0.9, 1e-6);  // the fallback
  EXPECT_EQ(merged->GetPointData()->GetNormals(), nullptr) << "the box has none";

  const vtkMTimeType time = merged->GetMTime();
  EXPECT_FALSE(merger.Merge(blocks, albedo));
  EXPECT_EQ(merger.GetMerged(), merged);
  EXPECT_EQ(merged->GetMTime(), time) << "nothing changed: the filter keeps its mesh";
  box->Modified();
  EXPECT_TRUE(merger.Merge(blocks, albedo));
  EXPECT_FALSE(merger.Merge(blocks, albedo));
  EXPECT_TRUE(merger.Merge(blocks, {}));
  EXPECT_EQ(PointArray(merger.GetMerged(), "Albedo"), nullptr);
}

TEST(GlobalIlluminationComposite, AnAsynchronousReExecutionWithoutANewResultKeepsTheLeaves)
{
  // A render loop re-executes the filter at every light move; until a new result arrives
  // the output's leaves must stay the same, unmodified objects, or a mapper rebuilds all
  // its buffers at every frame.
  vtkSmartPointer<vtkPolyData> floor = Floor(), box = Box();
  vtkNew<vtkMultiBlockDataSet> blocks;
  blocks->SetBlock(0, floor);
  blocks->SetBlock(1, box);
  auto filter = Filter(blocks);
  filter->AsynchronousOn();
  const auto waitForResult = [&]() {
    // The wait finds nothing new when an update already picked the result up (it came in
    // time): what counts is that the newest request is the one shown afterwards.
    filter->WaitForAsynchronousResult(600.0);
    filter->Update();
    vtkDataArray* shown =
      filter->GetOutputDataObject(0)->GetFieldData()->GetArray("LinkGI.ShownRequest");
    ASSERT_NE(shown, nullptr);
    ASSERT_EQ(vtkTypeUInt64(shown->GetTuple1(0)), filter->GetAsynchronousRequest());
  };
  filter->Update();
  waitForResult();
  const std::vector<vtkPolyData*> leaves = Leaves(filter->GetOutputDataObject(0));
  ASSERT_EQ(leaves.size(), 2u);
  const vtkMTimeType times[2] = { leaves[0]->GetMTime(), leaves[1]->GetMTime() };
  // held: an array freed by the next delivery could be replaced by one at its address
  vtkSmartPointer<vtkDataArray> direct = PointArray(leaves[1], "DirectIrradiance");
  const double before = Max(leaves[1], "DirectIrradiance");
  ASSERT_GT(before, 0.0);

  filter->Modified(); // the same scene: nothing new to show
  filter->Update();
  EXPECT_EQ(Leaves(filter->GetOutputDataObject(0)), leaves);
  EXPECT_EQ(leaves[0]->GetMTime(), times[0]);
  EXPECT_EQ(leaves[1]->GetMTime(), times[1]);
  EXPECT_EQ(PointArray(leaves[1], "DirectIrradiance"), direct);

  filter->GetLight(0)->SetPosition(-0.6, 0.4, 1.5); // a new result: new arrays on the leaves
  filter->Update();
  waitForResult();
  std::vector<vtkPolyData*> after = Leaves(filter->GetOutputDataObject(0));
  ASSERT_EQ(after.size(), 2u);
  EXPECT_NE(PointArray(after[1], "DirectIrradiance"), direct);
  EXPECT_NE(Max(after[1], "DirectIrradiance"), before);
}
