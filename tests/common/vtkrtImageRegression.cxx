#include "vtkrtImageRegression.h"

#include "vtkImageData.h"
#include "vtkImageDifference.h"
#include "vtkImageExtractComponents.h"
#include "vtkNew.h"
#include "vtkPNGReader.h"
#include "vtkPNGWriter.h"
#include "vtkRenderWindow.h"
#include "vtkSmartPointer.h"
#include "vtkWindowToImageFilter.h"
#include "vtksys/SystemTools.hxx"

#include <cstdlib>
#include <iostream>

namespace
{
double LastError = -1.0;

// RGB copy of an unsigned char image (grey is replicated, alpha dropped).
vtkSmartPointer<vtkImageData> ToRGB(vtkImageData* image)
{
  vtkNew<vtkImageExtractComponents> extract;
  extract->SetInputData(image);
  const int n = image->GetNumberOfScalarComponents();
  if (n >= 3)
  {
    extract->SetComponents(0, 1, 2);
  }
  else
  {
    extract->SetComponents(0, 0, 0);
  }
  extract->Update();
  vtkSmartPointer<vtkImageData> rgb = vtkSmartPointer<vtkImageData>::New();
  rgb->ShallowCopy(extract->GetOutput());
  return rgb;
}

bool WritePNG(vtkImageData* image, const std::string& path)
{
  vtksys::SystemTools::MakeDirectory(vtksys::SystemTools::GetFilenamePath(path));
  vtkNew<vtkPNGWriter> writer;
  writer->SetInputData(image);
  writer->SetFileName(path.c_str());
  writer->Write();
  return vtksys::SystemTools::FileExists(path, true);
}
} // namespace

double vtkrtLastImageError()
{
  return LastError;
}

int vtkrtCompareWithBaselineIn(vtkImageData* image, const std::string& baselineDir,
  const std::string& outputDir, const std::string& name, double threshold)
{
  LastError = -1.0;
  if (!image || image->GetNumberOfPoints() == 0 || image->GetScalarType() != VTK_UNSIGNED_CHAR)
  {
    std::cerr << "Image regression '" << name
              << "': no image, or not unsigned char scalars: nothing to compare\n";
    return 0;
  }
  vtkSmartPointer<vtkImageData> actual = ToRGB(image);
  const std::string baselinePath = baselineDir + "/" + name + ".png";
  const std::string actualPath = outputDir + "/" + name + ".png";
  const std::string diffPath = outputDir + "/" + name + ".diff.png";

  if (!vtksys::SystemTools::FileExists(baselinePath, true))
  {
    const char* update = std::getenv("VTKRT_UPDATE_BASELINES");
    if (update && std::string(update) == "1")
    {
      if (!WritePNG(actual, baselinePath))
      {
        std::cerr << "Image regression '" << name << "': could not write the new baseline "
                  << baselinePath << "\n";
        return 0;
      }
      std::cout << "Image regression '" << name << "': baseline was missing; wrote "
                << baselinePath << " (VTKRT_UPDATE_BASELINES=1). Check it and commit it.\n";
      LastError = 0.0;
      return 1;
    }
    WritePNG(actual, actualPath);
    std::cerr << "Image regression '" << name << "': baseline " << baselinePath
              << " is missing. The image is in " << actualPath
              << "; run with VTKRT_UPDATE_BASELINES=1 to record it as the baseline.\n";
    return 0;
  }

  vtkNew<vtkPNGReader> reader;
  reader->SetFileName(baselinePath.c_str());
  reader->Update();
  vtkImageData* baselineRaw = reader->GetOutput();
  if (!baselineRaw || baselineRaw->GetNumberOfPoints() == 0)
  {
    std::cerr << "Image regression '" << name << "': cannot read baseline " << baselinePath
              << "\n";
    return 0;
  }
  vtkSmartPointer<vtkImageData> baseline = ToRGB(baselineRaw);

  int da[3], db[3];
  actual->GetDimensions(da);
  baseline->GetDimensions(db);
  if (da[0] != db[0] || da[1] != db[1])
  {
    WritePNG(actual, actualPath);
    std::cerr << "Image regression '" << name << "': size " << da[0] << "x" << da[1]
              << " differs from the baseline's " << db[0] << "x" << db[1] << ".\n  actual:   "
              << actualPath << "\n  baseline: " << baselinePath << "\n";
    return 0;
  }

  vtkNew<vtkImageDifference> difference;
  difference->SetInputData(actual);
  difference->SetImageData(baseline);
  difference->SetThreshold(16);
  difference->SetAllowShift(false);
  difference->SetAveraging(true);
  difference->Update();
  LastError = difference->GetThresholdedError();
  if (LastError <= threshold)
  {
    std::cout << "Image regression '" << name << "': passed (error " << LastError
              << " <= " << threshold << ")\n";
    return 1;
  }
  WritePNG(actual, actualPath);
  WritePNG(difference->GetOutput(), diffPath);
  std::cerr << "Image regression '" << name << "': FAILED, error " << LastError << " > "
            << threshold << "\n  actual:   " << actualPath << "\n  diff:     " << diffPath
            << "\n  baseline: " << baselinePath << "\n";
  return 0;
}

int vtkrtCompareWithBaseline(vtkImageData* image, const std::string& name, double threshold)
{
  return vtkrtCompareWithBaselineIn(
    image, std::string(VTKRT_DATA_DIR) + "/baselines", VTKRT_TEMP_DIR, name, threshold);
}

int vtkrtCompareWithBaseline(vtkRenderWindow* window, const std::string& name, double threshold)
{
  if (!window)
  {
    std::cerr << "Image regression '" << name << "': no window\n";
    return 0;
  }
  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(window);
  grab->SetInputBufferTypeToRGB();
  grab->ReadFrontBufferOn();
  grab->ShouldRerenderOff();
  grab->Update();
  return vtkrtCompareWithBaseline(grab->GetOutput(), name, threshold);
}
