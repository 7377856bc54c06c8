/**
 * @class   vtkGlobalIlluminationBlockMerger
 * @brief   one vtkPolyData out of the blocks a ParaView representation draws, and back
 *
 * A representation draws a composite dataset (ParaView wraps even a single vtkPolyData in
 * a vtkMultiBlockDataSet), but light bounces between blocks, so the global illumination
 * filter must see them as one surface. Merge() appends the polydata leaves into one
 * vtkPolyData (points in leaf order) with the arrays the filter reads: the albedo as drawn
 * (see Albedo), `Emission` and point normals where every leaf has them. Scatter() copies
 * the filter's point arrays back onto shallow copies of the leaves, in a composite dataset
 * of the same structure, so that block colours, visibilities and selections still apply.
 *
 * Not wrapped; plugin glue used by vtkGlobalIlluminationRepresentation.
 */
#ifndef vtkGlobalIlluminationBlockMerger_h
#define vtkGlobalIlluminationBlockMerger_h

#include "vtkNew.h"          // for vtkNew
#include "vtkSmartPointer.h" // for vtkSmartPointer

#include <string> // for std::string
#include <vector> // for std::vector

class vtkDataObject;
class vtkMultiBlockDataSet;
class vtkPolyData;
class vtkScalarsToColors;

class vtkGlobalIlluminationBlockMerger
{
public:
  /// Where the albedo comes from: what the mapper draws as the surface colour.
  struct Albedo
  {
    /// Colours mapped from an array through a lookup table (ParaView's "Coloring").
    bool MapScalars = false;
    std::string ArrayName;
    int Association = 0; ///< vtkDataObject::FIELD_ASSOCIATION_POINTS or _CELLS
    vtkScalarsToColors* LookupTable = nullptr;
    int ColorMode = 0; ///< VTK_COLOR_MODE_*
    int Component = -1;
    /// The solid colour, for blocks without the array or when not mapping scalars.
    double Color[3] = { 1.0, 1.0, 1.0 };
    /// vtkProperty's Diffuse coefficient, which scales the albedo.
    double Diffuse = 1.0;

    /// Identifies the colours this produces (to skip needless rebuilds).
    std::string Key() const;
  };

  /// The name of the albedo array on the merged polydata (point or cell data).
  static const char* AlbedoArrayName() { return "GlobalIlluminationAlbedo"; }

  /**
   * Merges the polydata leaves of `data` (a vtkPolyData or a composite dataset) into
   * GetMerged(), and prepares one output leaf per input leaf. Does nothing when neither
   * `data` (object or modification time) nor the albedo changed since the last call.
   * Returns whether GetMerged() changed.
   */
  bool Merge(vtkDataObject* data, const Albedo& albedo);

  /// The merged surface: the same object every time; its contents change in Merge().
  vtkPolyData* GetMerged() { return this->Merged; }

  /// Whether the merged polydata carries the albedo array, and its association.
  bool HasAlbedoArray() const { return this->AlbedoAssociation >= 0; }
  int GetAlbedoAssociation() const { return this->AlbedoAssociation; }

  /// Whether the merged polydata has an `Emission` point array.
  bool HasEmission() const { return this->Emission; }

  /**
   * Copies the point arrays `names` of `lit` (the filter's output for GetMerged()) onto
   * the output leaves. Arrays that `lit` lacks are removed from them.
   */
  void Scatter(vtkPolyData* lit, const std::vector<std::string>& names);

  /// The input's structure with the scattered arrays; nullptr before the first Merge().
  vtkDataObject* GetOutput() { return this->Output; }

  /// Number of points of the merged surface.
  long long GetNumberOfPoints() const;

private:
  struct Leaf
  {
    vtkSmartPointer<vtkPolyData> Input;
    vtkSmartPointer<vtkPolyData> Output;
    long long FirstPoint = 0;
  };

  vtkSmartPointer<vtkPolyData> Strip(vtkPolyData* leaf, const Albedo& albedo,
    bool withNormals, bool withEmission) const;

  vtkNew<vtkPolyData> Merged;
  vtkSmartPointer<vtkDataObject> Output;
  std::vector<Leaf> Leaves;
  vtkSmartPointer<vtkDataObject> Input;
  unsigned long InputTime = 0;
  std::string AlbedoKey;
  int AlbedoAssociation = -1;
  bool Emission = false;
};

#endif
