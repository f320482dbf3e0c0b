// SPDX-License-Identifier: BSD-3-Clause
// FileBytes: whole-file reads and writes of the file parsers, with the one set of error
// messages (InputError) they all give.
#ifndef av_FileBytes_h
#define av_FileBytes_h

#include <string>

namespace av
{

/// The bytes of a file; throws InputError("cannot open '<file>' for reading").
std::string ReadFileBytes(const std::string& fileName);

/// Replaces a file by `bytes`; throws InputError when it cannot be opened or written.
void WriteFileBytes(const std::string& fileName, const std::string& bytes);

} // namespace av

#endif
