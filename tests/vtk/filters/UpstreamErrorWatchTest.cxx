// SPDX-License-Identifier: BSD-3-Clause
// The distributed filters' watch over the errors reported upstream of them (a reader that returns
// part of its pieces): remembered against the input, for a filter added later, until the input
// changes or is deleted.
#include "PointSetSurfacesErrorWatch.h"

#include "vtkNew.h"
#include "vtkOutputWindow.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"

#include <gtest/gtest.h>

#include <string>

namespace
{
const char* const ReaderError = "vtkReader (0x1): File for piece 1 cannot be read";

// An error as vtkErrorMacro reports it: through the output window, file and line first.
void ReportUpstreamError()
{
  vtkOutputWindow::GetInstance()->DisplayErrorText(
    (std::string("ERROR: In reader.cxx, line 1\n") + ReaderError + "\n\n").c_str());
}
}

TEST(UpstreamErrorWatch, RemembersAnErrorUntilItsInputIsModified)
{
  vtkNew<vtkPolyData> input;
  pss_vtk::UpstreamErrorWatch filter;
  pss_vtk::UpstreamErrorWatch addedLater;
  filter.Arm();
  ReportUpstreamError();
  EXPECT_EQ(filter.Check({ input }), ReaderError);
  // The upstream does not execute again for a filter added later: the record tells it.
  EXPECT_EQ(addedLater.Check({ input }), ReaderError);
  // Re-executed upstream (a new modification time): the error no longer applies.
  input->Modified();
  EXPECT_EQ(addedLater.Check({ input }), "");
  // Armed again with nothing reported meanwhile: no error.
  filter.Arm();
  EXPECT_EQ(filter.Check({ input }), "");
}

TEST(UpstreamErrorWatch, ForgetsTheErrorOfADeletedInput)
{
  pss_vtk::UpstreamErrorWatch filter;
  {
    vtkNew<vtkPolyData> input;
    filter.Arm();
    ReportUpstreamError();
    ASSERT_EQ(filter.Check({ input }), ReaderError);
  }
  // Objects made afterwards (one may take the deleted input's address) inherit nothing.
  for (int i = 0; i < 8; ++i)
  {
    vtkNew<vtkPolyData> other;
    EXPECT_EQ(filter.Check({ other }), "") << i;
  }
}
