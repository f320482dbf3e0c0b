// SPDX-License-Identifier: BSD-3-Clause
#include "FileBytes.h"

#include "InputError.h"

#include <fstream>
#include <sstream>

namespace av
{

std::string ReadFileBytes(const std::string& fileName)
{
  std::ifstream in(fileName, std::ios::binary);
  if (!in)
    throw InputError("cannot open '" + fileName + "' for reading");
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

void WriteFileBytes(const std::string& fileName, const std::string& bytes)
{
  std::ofstream out(fileName, std::ios::binary);
  if (!out)
    throw InputError("cannot open '" + fileName + "' for writing");
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  out.close();
  // A full disk shows only when the buffered bytes are flushed.
  if (!out)
    throw InputError("error while writing '" + fileName + "' (disk full?)");
}

} // namespace av
