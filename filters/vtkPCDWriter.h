// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkPCDWriter
 * @brief   writes a point set as a PCD file (PCL's format, version 0.7)
 *
 * vtkPCDWriter writes the points of any vtkPointSet and its numeric point arrays as PCD fields,
 * so that vtkPCDReader reads back the same points and arrays bit for bit:
 * - the points become `x y z` (4-byte floats for float points, else 8-byte doubles);
 * - the active scalars when they are `RGB` / `RGBA` (3 or 4 unsigned-char components) become the
 *   packed `rgb` / `rgba` field;
 * - the active normals (3 float or double components) become `normal_x normal_y normal_z`;
 * - every other numeric array becomes a field of its name (spaces replaced by `_`), its type and
 *   its number of components (COUNT); non-numeric arrays are left out with a warning.
 *
 * An input with the field data `GridDimensions` (WIDTH, HEIGHT > 1) and the point array `Pixel`,
 * as vtkPCDReader makes them, is written as an organized cloud: the whole image, with NaN
 * coordinates (and NaN or 0 in the other fields) at the pixels that have no point. The field data
 * `Viewpoint` (7 values: tx ty tz qw qx qy qz) becomes the VIEWPOINT line.
 *
 * DataMode chooses the body: BINARY_COMPRESSED (LZF, the default), BINARY, or ASCII (numbers
 * written in their shortest form that reads back to the same bits).
 *
 * @sa vtkPCDReader
 */
#ifndef vtkPCDWriter_h
#define vtkPCDWriter_h

#include "PointSetSurfacesFiltersModule.h" // for export macro
#include "vtkWriter.h"

class POINTSETSURFACESFILTERS_EXPORT vtkPCDWriter : public vtkWriter
{
public:
  static vtkPCDWriter* New();
  vtkTypeMacro(vtkPCDWriter, vtkWriter);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// The file to write.
  vtkSetStringMacro(FileName);
  vtkGetStringMacro(FileName);
  ///@}

  /// The body's encodings (the PCD DATA kinds).
  enum DataModeType
  {
    ASCII = 0,
    BINARY = 1,
    BINARY_COMPRESSED = 2
  };

  ///@{
  /// The body's encoding. Default BINARY_COMPRESSED.
  vtkSetClampMacro(DataMode, int, ASCII, BINARY_COMPRESSED);
  vtkGetMacro(DataMode, int);
  void SetDataModeToAscii() { this->SetDataMode(ASCII); }
  void SetDataModeToBinary() { this->SetDataMode(BINARY); }
  void SetDataModeToBinaryCompressed() { this->SetDataMode(BINARY_COMPRESSED); }
  ///@}

protected:
  vtkPCDWriter();
  ~vtkPCDWriter() override;

  void WriteData() override;
  int FillInputPortInformation(int port, vtkInformation* info) override;

  char* FileName = nullptr;
  int DataMode = BINARY_COMPRESSED;

private:
  vtkPCDWriter(const vtkPCDWriter&) = delete;
  void operator=(const vtkPCDWriter&) = delete;
};

#endif
