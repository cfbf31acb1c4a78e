// SPDX-License-Identifier: BSD-3-Clause
// main() of the test executables that run the VTK filters: gtest_main's, after choosing
// vtkSMPTools' threaded backend as an application does at its start (the filters never change
// it), so that the filters' threaded paths are the ones under test.
#include "vtkPointSetSurface.h"

#include <gtest/gtest.h>

int main(int argc, char** argv)
{
  vtkPointSetSurface::UseThreadedBackend();
  ::testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
