// SPDX-License-Identifier: BSD-3-Clause
#include "vtkAnisoFilterUtilities.h"

#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkNew.h>

void vtkAnisoFilterUtilities::AddFieldValue(vtkFieldData* fd, const char* name, double value)
{
  vtkNew<vtkDoubleArray> a;
  a->SetName(name);
  a->InsertNextValue(value);
  fd->AddArray(a);
}
