// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkPCDReader
 * @brief   reads PCD files, the point clouds of PCL, ROS and depth cameras
 *
 * vtkPCDReader reads a PCD file (versions 0.5 to 0.7; DATA ascii, binary or binary_compressed)
 * into a vtkPolyData with one vertex cell per point. Every field the header allows is read: types
 * I, U and F of 1 to 8 bytes, COUNT > 1 as components.
 * - `x y z` become the points (float points when all three are 4-byte floats, else double);
 * - `rgb` / `rgba` (4 bytes, 0x00RRGGBB with alpha in the top byte; the bits are used as they
 *   are, also when the field is declared as a float) become the unsigned-char `RGB` / `RGBA`
 *   array, the active scalars;
 * - `normal_x normal_y normal_z` become `Normals`, the active normals;
 * - every other field becomes a point array of its own name and type (`label`, `intensity`,
 *   `curvature`, ...); PCL's padding fields `_` are left out.
 *
 * Field data: `GridDimensions` (WIDTH, HEIGHT), `Viewpoint` (tx ty tz qw qx qy qz, when the
 * header has a VIEWPOINT line) and `SkippedPoints`. An organized cloud (HEIGHT > 1, one point per
 * pixel of a depth image) also gets the point array `Pixel` (column, row), so that the image can
 * be rebuilt after its invalid pixels were left out.
 *
 * Points whose x, y or z is not finite (a depth camera's invalid pixels) are left out by default
 * (SkipNaNPoints) and counted (GetNumberOfSkippedPoints).
 *
 * The whole file is checked before anything is allocated for it: a header that claims more points
 * than the file holds, a compressed block whose sizes lie, fields whose SIZE, TYPE and COUNT do not
 * add up, an unknown DATA kind or a truncated body fail the update with an error naming what is
 * wrong (docs/bad-input.md).
 *
 * @sa vtkPCDWriter
 */
#ifndef vtkPCDReader_h
#define vtkPCDReader_h

#include "PointSetSurfacesFiltersModule.h" // for export macro
#include "vtkPolyDataAlgorithm.h"

class POINTSETSURFACESFILTERS_EXPORT vtkPCDReader : public vtkPolyDataAlgorithm
{
public:
  static vtkPCDReader* New();
  vtkTypeMacro(vtkPCDReader, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// The file to read.
  vtkSetStringMacro(FileName);
  vtkGetStringMacro(FileName);
  ///@}

  ///@{
  /**
   * Leave out points whose x, y or z is NaN or infinite. Default on. Off keeps every point of the
   * file in its order (an organized cloud then keeps its whole image).
   */
  vtkSetMacro(SkipNaNPoints, bool);
  vtkGetMacro(SkipNaNPoints, bool);
  vtkBooleanMacro(SkipNaNPoints, bool);
  ///@}

  /// Points left out by the last update (0 with SkipNaNPoints off).
  vtkGetMacro(NumberOfSkippedPoints, vtkIdType);

  /// Points the last file's header announced (POINTS).
  vtkGetMacro(NumberOfPointsInFile, vtkIdType);

  /// True when @p fileName starts like a PCD file (a header line PCD uses).
  static bool CanReadFile(const char* fileName);

protected:
  vtkPCDReader();
  ~vtkPCDReader() override;

  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  char* FileName = nullptr;
  bool SkipNaNPoints = true;
  vtkIdType NumberOfSkippedPoints = 0;
  vtkIdType NumberOfPointsInFile = 0;

private:
  vtkPCDReader(const vtkPCDReader&) = delete;
  void operator=(const vtkPCDReader&) = delete;
};

#endif
