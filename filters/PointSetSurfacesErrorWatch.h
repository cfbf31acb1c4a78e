// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file PointSetSurfacesErrorWatch.h
 * @brief Private to the filters: notices the errors that the pipeline upstream of a filter
 *        reports during an update, so that a distributed run can stop on every rank alike.
 */
#ifndef PointSetSurfacesErrorWatch_h
#define PointSetSurfacesErrorWatch_h

#include <cstdint>
#include <string>
#include <vector>

class vtkDataObject;

namespace pss_vtk
{

/**
 * Notices the errors that the pipeline upstream of a distributed filter reports on this rank
 * (through vtkOutputWindow, whose messages it counts). Why: a reader that cannot read its piece
 * may still report success with fewer points (VTK 9.2's XML P-readers do), and the other ranks
 * would then compute over part of the cloud, silently. Arm() in RequestUpdateExtent, which the
 * executive calls before the upstream RequestData; Check() in RequestData.
 */
class UpstreamErrorWatch
{
public:
  /// Errors reported from now until Check() come from the pipeline upstream.
  void Arm();
  /**
   * The errors reported since Arm() (the last line of each, "vtkClass (0x...): text", joined by
   * "; "), which are then recorded against each of @p inputs; else the error recorded earlier, by any filter of
   * this process, against one of @p inputs still unchanged (so that a filter added later, whose
   * upstream does not execute again, still sees it); else empty. A record is held by weak
   * pointer and dropped once its object is deleted or modified, so none outlives what it is about.
   */
  std::string Check(const std::vector<vtkDataObject*>& inputs);

private:
  std::uint64_t Mark = 0;
  bool Armed = false;
};

}

#endif
