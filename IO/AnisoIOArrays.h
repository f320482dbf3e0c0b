// Internal to AnisoVoronoi::IO (not wrapped): VTK arrays filled from the parsers' std::vectors.
#ifndef AnisoIOArrays_h
#define AnisoIOArrays_h

#include <vtkDoubleArray.h>
#include <vtkIntArray.h>
#include <vtkSmartPointer.h>

#include <algorithm>
#include <cstdint>
#include <vector>

namespace AnisoIOArrays
{
/// An int array holding `values` (one component).
inline vtkSmartPointer<vtkIntArray> Int(const char* name, const std::vector<std::int32_t>& values)
{
  auto a = vtkSmartPointer<vtkIntArray>::New();
  a->SetName(name);
  a->SetNumberOfTuples(static_cast<vtkIdType>(values.size()));
  std::copy(values.begin(), values.end(), a->GetPointer(0));
  return a;
}

/// A double array holding `values` as tuples of `components`.
inline vtkSmartPointer<vtkDoubleArray> Double(
  const char* name, int components, const std::vector<double>& values)
{
  auto a = vtkSmartPointer<vtkDoubleArray>::New();
  a->SetName(name);
  a->SetNumberOfComponents(components);
  a->SetNumberOfTuples(static_cast<vtkIdType>(values.size() / components));
  std::copy(values.begin(), values.end(), a->GetPointer(0));
  return a;
}
}

#endif
