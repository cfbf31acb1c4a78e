// SPDX-License-Identifier: BSD-3-Clause
#include "Pcd.h"

#include "vtkCallbackCommand.h"
#include "vtkCommand.h"
#include "vtkNew.h"
#include "vtkPCDReader.h"
#include "vtkPCDWriter.h"
#include "vtkPointSet.h"
#include "vtkPolyData.h"

#include <cstdio>
#include <stdexcept>

namespace pss_cli
{
namespace io
{

namespace
{

// The text of the last error an algorithm reported (without VTK's "ERROR: In file, line" prefix);
// observing ErrorEvent also keeps VTK from printing it a second time.
struct ErrorCatcher
{
  std::string message;

  explicit ErrorCatcher(vtkAlgorithm* algorithm)
  {
    this->command->SetClientData(this);
    this->command->SetCallback([](vtkObject*, unsigned long, void* client, void* call) {
      std::string text = call ? static_cast<const char*>(call) : "";
      const auto start = text.find("): ");
      if (start != std::string::npos)
      {
        text = text.substr(start + 3);
      }
      while (!text.empty() && (text.back() == '\n' || text.back() == '\r'))
      {
        text.pop_back();
      }
      static_cast<ErrorCatcher*>(client)->message = text;
    });
    algorithm->AddObserver(vtkCommand::ErrorEvent, this->command);
  }

  vtkNew<vtkCallbackCommand> command;
};

}

vtkSmartPointer<vtkPolyData> ReadPcd(const std::string& path)
{
  vtkNew<vtkPCDReader> reader;
  const ErrorCatcher errors(reader);
  reader->SetFileName(path.c_str());
  reader->Update();
  if (!errors.message.empty())
  {
    throw std::runtime_error(errors.message);
  }
  if (reader->GetNumberOfSkippedPoints() > 0)
  {
    std::fprintf(stderr, "pss: %s: %lld of its %lld points have NaN/Inf coordinates (invalid pixels) and are left out\n",
      path.c_str(), static_cast<long long>(reader->GetNumberOfSkippedPoints()),
      static_cast<long long>(reader->GetNumberOfPointsInFile()));
  }
  return reader->GetOutput();
}

void WritePcd(vtkPointSet* data, const std::string& path, bool compress)
{
  vtkNew<vtkPCDWriter> writer;
  const ErrorCatcher errors(writer);
  writer->SetInputData(data);
  writer->SetFileName(path.c_str());
  writer->SetDataMode(compress ? vtkPCDWriter::BINARY_COMPRESSED : vtkPCDWriter::BINARY);
  if (!writer->Write() || !errors.message.empty())
  {
    throw std::runtime_error(errors.message.empty() ? "cannot write " + path : errors.message);
  }
}

}
}
