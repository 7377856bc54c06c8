/**
 * @class   vtkGlobalIlluminationBlockMerger
 * @brief   one surface out of a composite dataset (or any vtkDataSet), and the results
 *          back onto its blocks
 *
 * Light bounces between blocks, so vtkGlobalIlluminationFilter solves all the leaves of a
 * vtkMultiBlockDataSet, vtkPartitionedDataSetCollection or vtkPartitionedDataSet as one
 * scene. Merge() appends the leaves into one vtkPolyData, GetMerged(), with points in leaf
 * order: polydata leaves as they are, other datasets as their surface
 * (vtkDataSetSurfaceFilter). The merged surface has point normals only where every leaf
 * has them, and the colour arrays the filter reads (Carried): each leaf's array as float
 * RGB (read by vtkGlobalIlluminationColors), or the fallback colour for leaves without it.
 *
 * Deliver() copies point arrays of the lit merged surface back onto one output leaf per
 * input leaf (shallow copies of the polydata leaves; the surfaces of the others), in a
 * dataset of the input's structure; nested trees, empty nodes and metadata are kept.
 *
 * Not wrapped; the filter's plumbing, here so that tests can call it without a pipeline.
 * Merge() throws linkgi::Error with a sentence naming the problem.
 */
#ifndef vtkGlobalIlluminationBlockMerger_h
#define vtkGlobalIlluminationBlockMerger_h

#include "LinkGIFiltersGlobalIlluminationModule.h" // for export macro
#include "vtkNew.h"                                // for vtkNew
#include "vtkSmartPointer.h"                       // for vtkSmartPointer
#include "vtkType.h"                               // for vtkMTimeType

#include <array>  // for std::array
#include <string> // for std::string
#include <vector> // for std::vector

class vtkDataArray;
class vtkDataObject;
class vtkPolyData;

class LINKGIFILTERSGLOBALILLUMINATION_EXPORT vtkGlobalIlluminationBlockMerger
{
public:
  /// A colour array of the leaves that the merged surface carries, under the same name.
  struct Carried
  {
    std::string Name;
    int Association = 0; ///< vtkDataObject::FIELD_ASSOCIATION_POINTS or _CELLS
    std::array<double, 3> Fallback{ { 0.0, 0.0, 0.0 } }; ///< for leaves without the array
    std::string Role; ///< names the array in messages ("albedo")
    bool operator==(const Carried& o) const
    {
      return this->Name == o.Name && this->Association == o.Association &&
        this->Fallback == o.Fallback && this->Role == o.Role;
    }
  };

  /**
   * Makes GetMerged() the merged surface of `data` with the `carried` arrays. Does
   * nothing when neither `data` (the object, its or its leaves' modification times) nor
   * `carried` changed since the last call. Returns whether GetMerged() changed.
   */
  bool Merge(vtkDataObject* data, const std::vector<Carried>& carried);

  /// The merged surface: the same object every time; its contents change in Merge().
  vtkPolyData* GetMerged() { return this->Merged; }

  /// Number of leaves of the last Merge() (empty nodes are no leaves).
  std::size_t GetNumberOfLeaves() const { return this->Leaves.size(); }

  /**
   * Copies the point arrays of `lit` (the lit GetMerged(): the same points, in order)
   * that GetMerged() does not have onto the output leaves, and makes `output` the input's
   * structure with those leaves and `lit`'s field data added to the input's. `output` is
   * of the input's type (a vtkPolyData when the input is a non-polydata vtkDataSet).
   * A leaf whose arrays would come from the same `lit` arrays as at the last delivery is
   * left as it is (not modified), so that a mapper drawing it rebuilds nothing.
   */
  void Deliver(vtkPolyData* lit, vtkDataObject* output);

private:
  struct Leaf
  {
    vtkSmartPointer<vtkPolyData> Input; ///< the leaf, or its surface
    vtkSmartPointer<vtkPolyData> Output;
    vtkIdType FirstPoint = 0;
    std::vector<vtkSmartPointer<vtkDataArray>> Delivered; ///< `lit`'s arrays in Output
    vtkMTimeType DeliveredTime = 0;                       ///< their newest modification
  };

  void CollectLeaves(vtkDataObject* data);
  vtkSmartPointer<vtkPolyData> Strip(const Leaf& leaf, std::size_t index, bool withNormals) const;
  void BuildStructure(vtkDataObject* data);

  vtkNew<vtkPolyData> Merged;
  vtkSmartPointer<vtkDataObject> Structure; ///< the input's structure with the output leaves
  std::vector<Leaf> Leaves;
  std::vector<Carried> CarriedArrays;
  vtkSmartPointer<vtkDataObject> Input;
  vtkMTimeType InputTime = 0;
};

#endif
// VTK-HeaderTest-Exclude: vtkGlobalIlluminationBlockMerger.h
